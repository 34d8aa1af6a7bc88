// Shadow map placement fitted to the receivers and snapped to texels (see shadow_fit.h).

#include "gusuku/maths/shadow_fit.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace gusuku {
namespace {

constexpr double kLadderStepsPerOctave = 8.0;  // window sides are 2^(k/8) metres: rungs 9 % apart
constexpr double kDepthMarginFraction = 0.01;

void corners(const glm::dvec3& low, const glm::dvec3& high, glm::dvec3 out[8]) {
    for (int i = 0; i < 8; ++i)
        out[i] = glm::dvec3((i & 1) ? high.x : low.x, (i & 2) ? high.y : low.y, (i & 4) ? high.z : low.z);
}

}  // namespace

ShadowFit fitShadowMap(const glm::dvec3& receivers_min, const glm::dvec3& receivers_max, const glm::dvec3& casters_min,
                       const glm::dvec3& casters_max, const glm::dvec3& sun_direction_enu, uint32_t map_size) {
    ShadowFit fit;
    const glm::dvec3 towards_sun = glm::normalize(sun_direction_enu);
    fit.forward_enu = -towards_sun;
    const glm::dvec3 up_hint = std::abs(towards_sun.z) > 1.0 - 1e-6 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    fit.right_enu = glm::normalize(glm::cross(up_hint, fit.forward_enu));
    fit.up_enu = glm::cross(fit.forward_enu, fit.right_enu);

    glm::dvec3 receiver_corners[8];
    corners(receivers_min, receivers_max, receiver_corners);
    double right_low = INFINITY, right_high = -INFINITY, up_low = INFINITY, up_high = -INFINITY;
    double depth_low = INFINITY, depth_high = -INFINITY;
    for (const glm::dvec3& corner : receiver_corners) {
        right_low = std::min(right_low, glm::dot(corner, fit.right_enu));
        right_high = std::max(right_high, glm::dot(corner, fit.right_enu));
        up_low = std::min(up_low, glm::dot(corner, fit.up_enu));
        up_high = std::max(up_high, glm::dot(corner, fit.up_enu));
        depth_low = std::min(depth_low, glm::dot(corner, fit.forward_enu));
        depth_high = std::max(depth_high, glm::dot(corner, fit.forward_enu));
    }
    // Casters only push the near plane towards the sun: they can shade a receiver only if they lie between it
    // and the sun, and anything outside the window across r and u cannot shade a point inside it.
    if (casters_min.x <= casters_max.x) {
        glm::dvec3 caster_corners[8];
        corners(casters_min, casters_max, caster_corners);
        for (const glm::dvec3& corner : caster_corners) depth_low = std::min(depth_low, glm::dot(corner, fit.forward_enu));
    }

    const double extent = std::max({right_high - right_low, up_high - up_low, 1e-3});
    const double window = std::exp2(std::ceil(std::log2(extent) * kLadderStepsPerOctave) / kLadderStepsPerOctave);
    fit.texel_size_m = window / double(map_size);
    const double centre_right = std::round(0.5 * (right_low + right_high) / fit.texel_size_m) * fit.texel_size_m;
    const double centre_up = std::round(0.5 * (up_low + up_high) / fit.texel_size_m) * fit.texel_size_m;

    const double depth_margin = kDepthMarginFraction * std::max(depth_high - depth_low, 1.0) + 0.05;
    const double near_depth = depth_low - depth_margin;
    const double far_depth = depth_high + depth_margin;
    fit.depth_range_m = far_depth - near_depth;

    // Rows: clip x from r, clip y from -u (Vulkan's y points down), clip z from the depth along f.
    const double half = 0.5 * window;
    glm::dmat4 m(0.0);  // column-major: m[column][row]
    m[0][0] = fit.right_enu.x / half;
    m[1][0] = fit.right_enu.y / half;
    m[2][0] = fit.right_enu.z / half;
    m[3][0] = -centre_right / half;
    m[0][1] = -fit.up_enu.x / half;
    m[1][1] = -fit.up_enu.y / half;
    m[2][1] = -fit.up_enu.z / half;
    m[3][1] = centre_up / half;
    m[0][2] = fit.forward_enu.x / fit.depth_range_m;
    m[1][2] = fit.forward_enu.y / fit.depth_range_m;
    m[2][2] = fit.forward_enu.z / fit.depth_range_m;
    m[3][2] = -near_depth / fit.depth_range_m;
    m[3][3] = 1.0;
    fit.enu_to_clip = m;
    return fit;
}

}  // namespace gusuku
