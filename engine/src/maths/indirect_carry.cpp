// The baked sky and bounce light carried past the slots (see indirect_carry.h for the model).

#include "gusuku/maths/indirect_carry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>

#include "gusuku/maths/sun_air_mass.h"

namespace gusuku {
namespace {

// Rec.709 luminance weights: the carry is one factor, read where the eye reads it.
double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

bool isSunnySlotWithSun(const BakeSetSlot& slot) {
    return slot.sky != BakeSetSky::Overcast && slot.sun.present && slot.sun.position.has_value();
}

// Slots whose g differ by less than this (relative to the largest) cannot tell the sun's bounce from the sky's.
constexpr double kDistinctSunFraction = 1e-3;

}  // namespace

double horizontalSunLuminance(const glm::dvec3& sun_rgb, double apparent_elevation_deg) {
    if (!(apparent_elevation_deg > 0.0)) return 0.0;
    return std::max(luminance(sun_rgb), 0.0) * std::sin(apparent_elevation_deg * std::numbers::pi / 180.0);
}

SunBounceFit fitSunBounce(const BakeSetManifest& manifest, std::span<const glm::vec3> slot_mean_indirect) {
    // Least squares of mean = S + B g per channel: sums over the sunny slots, no allocation.
    double count = 0.0, sum_g = 0.0, sum_gg = 0.0, largest_g = 0.0;
    glm::dvec3 sum_m(0.0), sum_gm(0.0);
    for (size_t index = 0; index < manifest.slots.size() && index < slot_mean_indirect.size(); ++index) {
        const BakeSetSlot& slot = manifest.slots[index];
        if (!isSunnySlotWithSun(slot)) continue;
        const double g = horizontalSunLuminance(slot.sun.irradiance_rgb, slot.sun.position->apparent_elevation_deg);
        const glm::dvec3 mean(slot_mean_indirect[index]);
        count += 1.0;
        sum_g += g;
        sum_gg += g * g;
        sum_m += mean;
        sum_gm += g * mean;
        largest_g = std::max(largest_g, g);
    }
    SunBounceFit fit;
    if (count < 2.0) return fit;
    const double variance_g = sum_gg / count - (sum_g / count) * (sum_g / count);
    const double spread = kDistinctSunFraction * largest_g;
    if (!(variance_g > spread * spread)) return fit;
    const glm::dvec3 mean_m = sum_m / count;
    const double mean_g = sum_g / count;
    fit.per_sun = glm::max((sum_gm / count - mean_g * mean_m) / variance_g, glm::dvec3(0.0));
    fit.sky = mean_m - fit.per_sun * mean_g;
    fit.fitted = true;
    return fit;
}

double indirectCarry(const BakeSetManifest& manifest, const SunBounceFit& fit, const FrameLighting& lighting) {
    if (!fit.fitted || lighting.slot_a < 0) return 1.0;
    const BakeSetSlot& slot_a = manifest.slots[size_t(lighting.slot_a)];
    const BakeSetSlot& slot_b = manifest.slots[size_t(std::max(lighting.slot_b, lighting.slot_a))];
    if (!isSunnySlotWithSun(slot_a) || !isSunnySlotWithSun(slot_b)) return 1.0;
    const double t = lighting.slot_b_weight;
    auto slotG = [](const BakeSetSlot& slot) {
        return horizontalSunLuminance(slot.sun.irradiance_rgb, slot.sun.position->apparent_elevation_deg);
    };
    const double g_blend = (1.0 - t) * slotG(slot_a) + t * slotG(slot_b);
    // The clear sky's sun now (the sunny slots' sky, sun_scale 1), carried from the blend's slots as
    // computeFrameLighting carries E_sun.
    const double elevation = lighting.sun.apparent_elevation_deg;
    glm::dvec3 sun_now(0.0);
    if (elevation > 0.0) {
        auto carried = [&](const BakeSetSlot& slot) {
            return carryMeasuredSunRgb(slot.sun.irradiance_rgb, slot.sun.position->apparent_elevation_deg, elevation);
        };
        sun_now = (1.0 - t) * carried(slot_a) + t * carried(slot_b);
    }
    const double g_now = std::min(horizontalSunLuminance(sun_now, elevation), g_blend);
    const double sky = luminance(fit.sky), per_sun = luminance(fit.per_sun);
    const double held = sky + per_sun * g_blend;
    if (!(held > 0.0) || !(g_now < g_blend)) return 1.0;
    return std::clamp((sky + per_sun * g_now) / held, 0.0, 1.0);
}

}  // namespace gusuku
