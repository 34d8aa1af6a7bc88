#pragma once
// The light of one runtime frame, worked out on the CPU from the instant, the place and the weather
// (docs/design.md 8, steps 1 and 2): where the sun is (NREL SPA), its irradiance E_sun carried from the baked slots to
// the current elevation, and the weights of the baked slots. Pure maths (glm only), so it is
// tested without a GPU and the runtime calls it once per frame.
//
// Slot choice is by the sun's position, never by the clock: a daylight-saving clock, a wrong time zone or a
// slot's name cannot pick a slot whose sun stood elsewhere.
//   - Sunny slots (sun present in the manifest): the two whose sun directions are nearest the current sun
//     (angle between unit vectors). The current sun is projected onto the arc between them:
//       t = clamp((a^2 - b^2 + ab^2) / (2 ab^2), 0, 1)
//     with a and b the angles to the two slots' suns and ab the angle between them (a plane approximation of
//     the sphere, exact to well under 1 % at the tens of degrees between slots); slot B gets weight t, slot A
//     1 - t. Beyond the last slot t clamps to 0 (the nearest alone, no extrapolation), and the pair changes only
//     where one slot has all the weight, so the weights are continuous as the sun moves: no pop.
//     Without blending (blend = false) the nearest slot has weight 1.
//   - Cloud cover c in [0, 1]: the sunny blend gets (1 - c), the overcast slot c; E_sun is multiplied by (1 - c).
//     A bake set without an overcast slot keeps the sunny blend at full weight (only the sun fades); one without
//     sunny slots uses the overcast slot alone.
//   - Sun below the horizon: E_sun = 0; the sunny blend (the slot nearest the sun, now below the horizon) fades
//     linearly to 0 between 0 and -6 degrees apparent elevation (civil twilight) while the overcast slot keeps
//     its cloud weight. Defined, finite, never NaN; the colour match then adapts the building to the dim camera.
//   - E_sun: each chosen sunny slot's irradiance_rgb carried from its baked elevation to the current one
//     (carryMeasuredSunRgb of gusuku/maths/sun_air_mass.h, the baker's air-mass model: the aerosol depth refitted to
//     the slot's own colour is the one the baker used), blended with the slot weights.

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/maths/sun.h"

namespace gusuku {

struct FrameLighting {
    SunPosition sun;
    glm::dvec3 sun_irradiance_rgb{0.0};  ///< E_sun on a plane facing the sun, after cloud cover; 0 at night
    int slot_a = -1;                     ///< sunny slot with weight sunny_weight * (1 - slot_b_weight); -1 none
    int slot_b = -1;                     ///< second sunny slot (may equal slot_a); -1 none
    float slot_b_weight = 0.0f;          ///< t above
    float sunny_weight = 0.0f;           ///< weight of the whole sunny blend: (1 - c), times the twilight fade
    int overcast_slot = -1;              ///< -1 none
    float overcast_weight = 0.0f;        ///< c (1 with no sunny slot)
};

/// Works out the frame's light (see above). cloud_cover is clamped to [0, 1]; a NaN cover counts as 0. Throws
/// std::invalid_argument for an observer out of range (SunObserver's checks).
FrameLighting computeFrameLighting(const BakeSetManifest& manifest, const SunObserver& observer,
                                   double utc_seconds, float cloud_cover, bool blend_slots);

/// The sky's state and the sun's kept apart (gusuku/maths/sun_visibility.h): sky_overcast in [0, 1] blends the
/// slots as the cover above does; sun_scale (>= 0) multiplies E_sun in place of (1 - cover): the sun's visibility
/// times its strength. The cloud_cover overload is {c, 1 - c}. A NaN overcast counts as 0, a NaN or negative scale
/// as 0 (no sun).
struct SkyAndSun {
    float sky_overcast = 0.0f;
    float sun_scale = 1.0f;
};
FrameLighting computeFrameLighting(const BakeSetManifest& manifest, const SunObserver& observer,
                                   double utc_seconds, const SkyAndSun& sky_and_sun, bool blend_slots);

/// Angle in degrees between two directions (any length > 0), robust near 0 and 180.
double angleBetweenDeg(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace gusuku
