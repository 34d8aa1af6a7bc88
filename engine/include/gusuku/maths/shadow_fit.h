#pragma once
// The runtime's shadow map placement (docs/design.md 8 step 3): an orthographic view from the sun fitted to what can
// receive the building's shadow (the building and the ground grid), snapped to the map's texel grid so the
// shadow does not shimmer. Pure maths (glm only), tested without a GPU.
//
// Light frame: forward f = -s (s the unit direction towards the sun, ENU), right r = normalize(up x f)... with
// up = ENU z, or ENU y when the sun is within 1e-6 of the zenith; u = f x r. The window:
//   - side W: the receivers' extent across r and u (square), rounded UP to the next step of a ladder 2^(k/8):
//     the texel size W / size then stays fixed while the sun moves a little and changes in steps of 9 % only
//     when the extent has grown past a rung, so texels do not swim from frame to frame;
//   - centre: on multiples of the texel size along r and u, so a sub-texel change of the fit does not move the
//     texel grid against the world. The camera never enters: moving it cannot move the shadow.
//   - depth: from the nearest caster towards the sun (casters: the building and the site's occluders, whose
//     bounds are given) to the farthest receiver, with a margin; mapped to [0, 1] with 0 nearest the sun.
// Clip space is Vulkan's: x right, y down, z in [0, 1]; light-space u maps to clip y DOWN (u = -y_clip).

#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace gusuku {

struct ShadowFit {
    glm::dmat4 enu_to_clip{1.0};  ///< ENU point -> clip (x, y in [-1, 1] over the window, z in [0, 1])
    double texel_size_m = 0.0;    ///< side of one shadow-map texel, metres (W / map size)
    double depth_range_m = 0.0;   ///< metres from z = 0 to z = 1
    glm::dvec3 right_enu{1, 0, 0}, up_enu{0, 1, 0}, forward_enu{0, 0, -1};
};

/// Fits the window (see above). receivers_min/max and casters_min/max are axis-aligned ENU bounds (casters may
/// be empty: min > max). map_size > 0. The sun direction need not be above the horizon (the fit is still
/// defined), but must be finite and non-zero.
ShadowFit fitShadowMap(const glm::dvec3& receivers_min, const glm::dvec3& receivers_max, const glm::dvec3& casters_min,
                       const glm::dvec3& casters_max, const glm::dvec3& sun_direction_enu, uint32_t map_size);

}  // namespace gusuku
