// The building's sky and bounce light carried past the slots texel by texel (see sky_carry.h).

#include "sky_carry.h"

#include <algorithm>
#include <cstddef>

#include <glm/common.hpp>

#include "gusuku/maths/indirect_carry.h"

namespace gusuku::runtime_detail {
namespace {

// Slots whose g differ by less than this (relative to the largest) cannot tell the sun's bounce from the sky's
// (indirect_carry.cpp's rule for the mean).
constexpr double kDistinctSunFraction = 1e-3;

// std140: the ratio (a vec3) at a 16-byte offset, its tail filled by the weight of slot A (interface_types.h).
static_assert(offsetof(shader_interface::FrameUniforms, sky_sun_ratio) == 304);
static_assert(offsetof(shader_interface::FrameUniforms, sky_carried_weight_a) == 316);

}  // namespace

BakeSetImage fitTexelSky(const BakeSetManifest& manifest, const std::vector<BakeSetSlotImages>& slots) {
    // Per channel c the least squares S = mean_E - B mean_g, B = sum_k (g_k - mean_g) E_k / (n var_g), with g_k the
    // slot's sun on the horizontal ground in that channel: fixed weights per slot and channel.
    std::vector<size_t> used;
    std::vector<glm::dvec3> g;
    for (size_t index = 0; index < manifest.slots.size() && index < slots.size(); ++index) {
        const glm::dvec3 slot_g = slotHorizontalSunRgb(manifest.slots[index]);
        if (slot_g.x < 0.0) continue;
        used.push_back(index);
        g.push_back(slot_g);
    }
    BakeSetImage sky;
    if (used.size() < 2) return sky;
    const BakeSetImage& first = slots[used[0]].building;
    for (size_t index : used)
        if (slots[index].building.rgba.size() != first.rgba.size()) return sky;
    const double count = double(used.size());
    glm::dvec3 mean_g(0.0), largest_g(0.0), variance_g(0.0);
    for (const glm::dvec3& slot_g : g) mean_g += slot_g / count, largest_g = glm::max(largest_g, slot_g);
    for (const glm::dvec3& slot_g : g) variance_g += (slot_g - mean_g) * (slot_g - mean_g) / count;
    for (int channel = 0; channel < 3; ++channel) {
        const double spread = kDistinctSunFraction * largest_g[channel];
        if (!(variance_g[channel] > spread * spread)) return sky;
    }
    std::vector<glm::dvec3> slope_weight;
    for (const glm::dvec3& slot_g : g) slope_weight.push_back((slot_g - mean_g) / (count * variance_g));

    sky.width = first.width;
    sky.height = first.height;
    sky.rgba.assign(first.rgba.size(), 1.0f);
    for (size_t texel = 0; texel + 3 < first.rgba.size(); texel += 4)
        for (int channel = 0; channel < 3; ++channel) {
            double mean_e = 0.0, per_sun = 0.0;
            for (size_t k = 0; k < used.size(); ++k) {
                const double e = slots[used[k]].building.rgba[texel + size_t(channel)];
                mean_e += e / count;
                per_sun += slope_weight[k][channel] * e;
            }
            // A bounce cannot be negative, nor the sky's light.
            sky.rgba[texel + size_t(channel)] = float(std::max(mean_e - std::max(per_sun, 0.0) * mean_g[channel], 0.0));
        }
    return sky;
}

void writeSkyCarry(const SlotBlend& uncarried_blend, const glm::dvec3& ratio, int sky_layer,
                   shader_interface::FrameUniforms& uniforms) {
    if (sky_layer < 0 || !(ratio.x < 1.0 || ratio.y < 1.0 || ratio.z < 1.0)) return;
    const double sunny_a = uncarried_blend.weights[0], sunny_b = uncarried_blend.weights[1];
    if (!(sunny_a + sunny_b > 0.0)) return;
    uniforms.sky_layer = float(sky_layer);
    uniforms.sky_weight = float(sunny_a + sunny_b);
    for (int channel = 0; channel < 3; ++channel)
        uniforms.sky_sun_ratio[channel] = float(glm::clamp(ratio[channel], 0.0, 1.0));
    uniforms.sky_carried_weight_a = float(sunny_a);
    uniforms.sky_carried_weight_b = float(sunny_b);
}

}  // namespace gusuku::runtime_detail
