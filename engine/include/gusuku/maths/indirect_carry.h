#pragma once
// The baked sky and bounce light carried past the slots (issue 44 item 4): when the sun stands lower than the
// slots the frame blends (after the last sunny slot of the afternoon, before the first of the morning), E_ind is
// not held at the slots' value but scaled by the light's change with the sun's elevation.
//
// Model. Every sunny slot of a bake set is lit by the same sunny sky map (its sun disc removed) and by the sun
// at the slot's instant (docs/design.md 3). So the part of E_ind that changes from slot to slot is the sun's
// light bounced by the ground and the building, which grows with the sun's irradiance on the horizontal ground:
//   g(h) = E_sun(h) sin(h)      (luminance; E_sun carried by air mass, gusuku/maths/sun_air_mass.h)
// and over the building's valid texels the slots' mean E_ind follows
//   mean_k = S + B g_k          (S: the sky's light and its bounce, the same in every slot; B: the sun's bounce)
// S and B are fitted per channel by least squares over the bake set's sunny slots (at least two of distinct g;
// B clamped at 0, a bounce cannot be negative). The frame's sunny blend, whose slots hold S + B g_blend
// (g_blend the weighted g of its slots), is then multiplied by
//   carry = (S + B min(g_now, g_blend)) / (S + B g_blend)     (luminance of each; in [0, 1])
// which is 1 while the sun gives the ground at least the blend's own horizontal sun (at every baked instant and
// between slots on the sun's arc) and falls continuously, with the sun, towards S / (S + B g_blend) at the
// horizon, where the twilight fade (frame_lighting.h) takes over. One factor for the whole building: the fit is
// the building's mean, so a texel that sees more ground than the mean (a wall) keeps some of its excess, and one
// that sees mostly sky (a roof) loses a little it should keep (docs/measurements.md, "After the last slot"). A
// texel's own S + B g was tried (commit 1609f5c): within 1.2 % on the shrine's texels at 16:30 (this: wood 16 %
// bright), but the sample's walls 16 % dark (this: 5 % bright), their bounce coming from stone faces that catch the
// low sun and not falling with sin h. Neither holds both sites; a low-sun slot would.
// With fewer than two sunny slots of distinct g the model cannot tell S from B, and the carry is 1 (held).
// Pure functions, no allocation (a frame calls them).

#include <span>

#include <glm/vec3.hpp>

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/maths/frame_lighting.h"

namespace gusuku {

/// The fit above, per channel, in the bake set's units (fitted = false: fewer than two sunny slots of distinct g).
struct SunBounceFit {
    glm::dvec3 sky{0.0};      ///< S
    glm::dvec3 per_sun{0.0};  ///< B, per unit of g (luminance of E_sun times sin h, the manifest's units)
    bool fitted = false;
};

/// g of a sun of irradiance sun_rgb (on a plane facing it) at an apparent elevation: luminance(sun_rgb) sin(h),
/// 0 at or below the horizon.
double horizontalSunLuminance(const glm::dvec3& sun_rgb, double apparent_elevation_deg);

/// Fits S and B over the manifest's sunny slots with a sun (slot_mean_indirect: per manifest slot, the mean
/// E_ind over the building's valid texels; a slot beyond its size is left out).
SunBounceFit fitSunBounce(const BakeSetManifest& manifest, std::span<const glm::vec3> slot_mean_indirect);

/// The carry above for the frame's light (its sunny slots, their blend and the sun's apparent elevation), in
/// [0, 1]; 1 when the fit is not fitted or the frame has no sunny slot. Multiply FrameLighting::sunny_weight by it.
double indirectCarry(const BakeSetManifest& manifest, const SunBounceFit& fit, const FrameLighting& lighting);

}  // namespace gusuku
