#pragma once
// The building's sky and bounce light carried past the slots texel by texel (issue 44 item 4; the model and the
// building's mean fit: gusuku/maths/indirect_carry.h). Every sunny slot holds, per texel, E_k = S + B g_k: S the
// sunny sky map's light and its bounce, the same in every slot, and B g_k the sun's light bounced onto the texel.
// Each texel's own S is fitted when the runtime opens (least squares over the sunny slots, per channel against the
// slot's sun on the horizontal ground in that channel, B >= 0 and S >= 0) and kept as one more lightmap layer; past
// the slots the building pass reads, per channel,
//   E = S + (E_blend - S) r,   r = g_now / g_blend   (sunBounceRatio: the sun on the ground now over the blend's)
// as the blend's sunny layers times r plus the S layer times (1 - r): one fetch more, only while r < 1. So a wall
// that sees the sunlit ground loses its own bounce with the sun (redder as the sun reddens) and a roof that sees the
// sky keeps its sky, where the building's mean factor moved both by the mean's (a wall 7 % too bright at 16:38 on
// the sample). At and between the slots r = 1 and the frame is unchanged. The ground, the colour match and
// direct-only's ambient keep the mean factor; so does the building where the fit cannot be made (fewer than two
// sunny slots of distinct g) or where the lightmaps are the bake's ASTC blocks (the runtime encodes no layer of its
// own). Private to gusuku_runtime.

#include <vector>

#include <glm/vec3.hpp>

#include "frame_preparation.h"
#include "gusuku/formats/bakeset_data.h"
#include "gusuku/formats/bakeset_manifest.h"
#include "runtime_interface.h"

namespace gusuku::runtime_detail {

/// Each building texel's S in the slots' texel order and units, alpha 1; empty (no rgba) when the manifest's sunny
/// slots cannot tell S from B (fewer than two with a sun, or their g all but equal).
BakeSetImage fitTexelSky(const BakeSetManifest& manifest, const std::vector<BakeSetSlotImages>& slots);

/// The building's own light past the slots: with a ratio below 1 in some channel (sunBounceRatio) and a sky layer
/// (>= 0), the sky layer, the ratio, slot A's and B's weights of the uncarried blend and their sum (sky_weight);
/// otherwise nothing is written (sky_weight stays 0 and the building reads slot_weights as the ground does).
void writeSkyCarry(const SlotBlend& uncarried_blend, const glm::dvec3& ratio, int sky_layer,
                   shader_interface::FrameUniforms& uniforms);

}  // namespace gusuku::runtime_detail
