// The frame's sun, E_sun and slot weights (see frame_lighting.h for the rules).

#include "gusuku/maths/frame_lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

#include "gusuku/maths/sun_air_mass.h"

namespace gusuku {
namespace {

constexpr double kCivilTwilightDeg = 6.0;  // the sunny blend is gone when the sun is this far below the horizon

}  // namespace

double angleBetweenDeg(const glm::dvec3& a, const glm::dvec3& b) {
    // atan2 of |a x b| and a . b: accurate at every angle, unlike acos near 0 and 180.
    const double sine = glm::length(glm::cross(a, b));
    const double cosine = glm::dot(a, b);
    return std::atan2(sine, cosine) * 180.0 / std::numbers::pi;
}

FrameLighting computeFrameLighting(const BakeSetManifest& manifest, const SunObserver& observer,
                                   double utc_seconds, float cloud_cover, bool blend_slots) {
    const float cover = std::isnan(cloud_cover) ? 0.0f : std::clamp(cloud_cover, 0.0f, 1.0f);
    return computeFrameLighting(manifest, observer, utc_seconds, SkyAndSun{cover, 1.0f - cover}, blend_slots);
}

FrameLighting computeFrameLighting(const BakeSetManifest& manifest, const SunObserver& observer,
                                   double utc_seconds, const SkyAndSun& sky_and_sun, bool blend_slots) {
    FrameLighting lighting;
    lighting.sun = computeSunPosition(observer, utc_seconds);
    const float cover = std::isnan(sky_and_sun.sky_overcast) ? 0.0f : std::clamp(sky_and_sun.sky_overcast, 0.0f, 1.0f);
    const double sun_scale = std::isfinite(sky_and_sun.sun_scale) ? std::max(double(sky_and_sun.sun_scale), 0.0) : 0.0;

    // The two sunny slots nearest the current sun, ordered by (angle, slot index): kept as two running bests, not
    // a sorted list, because a frame allocates nothing (runtime.h) and a bake set has a handful of slots.
    using SlotByAngle = std::pair<double, int>;  // (angle to the current sun, slot index)
    SlotByAngle nearest[2];
    size_t sunny_count = 0;
    for (size_t index = 0; index < manifest.slots.size(); ++index) {
        const BakeSetSlot& slot = manifest.slots[index];
        if (slot.sky == BakeSetSky::Overcast) {
            if (lighting.overcast_slot < 0) lighting.overcast_slot = int(index);
        } else if (slot.sun.present && slot.sun.position) {
            const SlotByAngle candidate{angleBetweenDeg(lighting.sun.direction_enu, slot.sun.position->direction_enu),
                                        int(index)};
            if (sunny_count == 0 || candidate < nearest[0]) {
                nearest[1] = nearest[0];
                nearest[0] = candidate;
            } else if (sunny_count == 1 || candidate < nearest[1]) {
                nearest[1] = candidate;
            }
            ++sunny_count;
        }
    }

    const double elevation = lighting.sun.apparent_elevation_deg;
    const double twilight = std::clamp(1.0 + elevation / kCivilTwilightDeg, 0.0, 1.0);
    if (sunny_count > 0) {
        lighting.slot_a = nearest[0].second;
        lighting.slot_b = nearest[0].second;
        if (blend_slots && sunny_count >= 2) {
            const double angle_a = nearest[0].first, angle_b = nearest[1].first;
            const double angle_ab =
                angleBetweenDeg(manifest.slots[size_t(nearest[0].second)].sun.position->direction_enu,
                                manifest.slots[size_t(nearest[1].second)].sun.position->direction_enu);
            if (angle_ab > 1e-6) {
                const double t = (angle_a * angle_a - angle_b * angle_b + angle_ab * angle_ab) /
                                 (2.0 * angle_ab * angle_ab);
                lighting.slot_b = nearest[1].second;
                lighting.slot_b_weight = float(std::clamp(t, 0.0, 1.0));
            }
        }
        const bool has_overcast = lighting.overcast_slot >= 0;
        lighting.sunny_weight = float((has_overcast ? 1.0 - cover : 1.0) * (elevation > 0.0 ? 1.0 : twilight));
        lighting.overcast_weight = has_overcast ? cover : 0.0f;
        if (lighting.sun.above_horizon) {
            auto carried = [&](int slot_index) {
                const BakeSetSun& sun = manifest.slots[size_t(slot_index)].sun;
                return carryMeasuredSunRgb(sun.irradiance_rgb, sun.position->apparent_elevation_deg, elevation);
            };
            const double t = lighting.slot_b_weight;
            lighting.sun_irradiance_rgb =
                ((1.0 - t) * carried(lighting.slot_a) + t * carried(lighting.slot_b)) * sun_scale;
        }
    } else if (lighting.overcast_slot >= 0) {
        lighting.overcast_weight = 1.0f;
    }
    return lighting;
}

}  // namespace gusuku
