// The runtime's CPU side of a frame: slot choice and weights by the sun's position (gusuku/maths/frame_lighting.h) and
// the shadow map's fit and snapping (gusuku/maths/shadow_fit.h), against closed-form expectations.

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gusuku/maths/frame_lighting.h"
#include "gusuku/maths/shadow_fit.h"
#include "gusuku/maths/sun.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

SunObserver siteObserver(const BakeSetManifest& manifest) {
    SunObserver observer;
    observer.latitude_deg = manifest.site.latitude_deg;
    observer.longitude_deg = manifest.site.longitude_deg;
    observer.height_m = manifest.site.height_m;
    return observer;
}

TEST(FrameLighting, AtASlotsInstantThatSlotHasAllTheWeight) {
    const BakeSetManifest manifest = makeSyntheticBakeSet().manifest;
    const int hours[3] = {9, 12, 15};
    for (int slot = 0; slot < 3; ++slot) {
        const FrameLighting lighting =
            computeFrameLighting(manifest, siteObserver(manifest), syntheticLocalTime(hours[slot], 0), 0.0f, true);
        const float weight_of_slot = lighting.slot_a == slot ? 1.0f - lighting.slot_b_weight
                                                             : (lighting.slot_b == slot ? lighting.slot_b_weight : 0.0f);
        EXPECT_NEAR(weight_of_slot, 1.0f, 1e-4f) << manifest.slots[size_t(slot)].name;
        EXPECT_FLOAT_EQ(lighting.sunny_weight, 1.0f);
        // E_sun carried from the slot's own elevation to the same elevation is the slot's.
        EXPECT_NEAR(lighting.sun_irradiance_rgb.x, manifest.slots[size_t(slot)].sun.irradiance_rgb.x, 1e-6);
    }
}

// A daylight-saving clock (or a phone set to the wrong zone) is one hour off: the app that reads "13:00" at the
// instant of 12:00 standard time gets the 12:00 slot, because only the instant and the sun count; and the instant
// one hour later (a real 13:00) is not the 12:00 slot alone but a blend towards 15:00.
TEST(FrameLighting, SlotIsChosenByTheSunNotTheClock) {
    const BakeSetManifest manifest = makeSyntheticBakeSet().manifest;
    const SunObserver observer = siteObserver(manifest);
    const double noon_standard = syntheticLocalTime(12, 0);
    const FrameLighting at_noon = computeFrameLighting(manifest, observer, noon_standard, 0.0f, false);
    EXPECT_EQ(manifest.slots[size_t(at_noon.slot_a)].name, "sunny_1200");
    const FrameLighting an_hour_later = computeFrameLighting(manifest, observer, noon_standard + 3600.0, 0.0f, true);
    EXPECT_TRUE(an_hour_later.slot_a == 1 || an_hour_later.slot_b == 1);
    EXPECT_TRUE(an_hour_later.slot_a == 2 || an_hour_later.slot_b == 2);
    EXPECT_GT(an_hour_later.slot_b_weight, 0.05f);
    EXPECT_LT(an_hour_later.slot_b_weight, 0.95f);
    // The nearest slot by sun direction, for every quarter hour of the day: the chosen slot_a is it.
    for (int quarter = 6 * 4; quarter <= 18 * 4; ++quarter) {
        const double utc = syntheticLocalTime(0, 15 * quarter);
        const FrameLighting lighting = computeFrameLighting(manifest, observer, utc, 0.0f, false);
        const SunPosition sun = computeSunPosition(observer, utc);
        double best_angle = 1e9;
        int best = -1;
        for (int slot = 0; slot < 3; ++slot) {
            const double angle = angleBetweenDeg(sun.direction_enu, manifest.slots[size_t(slot)].sun.position->direction_enu);
            if (angle < best_angle) best_angle = angle, best = slot;
        }
        EXPECT_EQ(lighting.slot_a, best) << "quarter hour " << quarter;
    }
}

// Blend weights move smoothly through the day: no pop when the pair of slots changes.
TEST(FrameLighting, WeightsAreContinuousThroughTheDay) {
    const BakeSetManifest manifest = makeSyntheticBakeSet().manifest;
    const SunObserver observer = siteObserver(manifest);
    std::vector<float> previous(4, -1.0f);
    for (int minute = 7 * 60; minute <= 18 * 60; minute += 1) {
        const FrameLighting lighting =
            computeFrameLighting(manifest, observer, syntheticLocalTime(0, minute), 0.0f, true);
        std::vector<float> weights(4, 0.0f);
        weights[size_t(lighting.slot_a)] += lighting.sunny_weight * (1.0f - lighting.slot_b_weight);
        weights[size_t(lighting.slot_b)] += lighting.sunny_weight * lighting.slot_b_weight;
        if (previous[0] >= 0.0f) {
            for (int slot = 0; slot < 3; ++slot) {
                EXPECT_LT(std::abs(weights[size_t(slot)] - previous[size_t(slot)]), 0.02f)
                    << "minute " << minute << " slot " << slot;
            }
        }
        previous = weights;
    }
}

TEST(FrameLighting, CloudCoverBlendsSunnyAndOvercastAndFadesTheSun) {
    const BakeSetManifest manifest = makeSyntheticBakeSet().manifest;
    const SunObserver observer = siteObserver(manifest);
    const double noon = syntheticLocalTime(12, 0);
    const FrameLighting clear = computeFrameLighting(manifest, observer, noon, 0.0f, true);
    const FrameLighting half = computeFrameLighting(manifest, observer, noon, 0.5f, true);
    const FrameLighting overcast = computeFrameLighting(manifest, observer, noon, 1.0f, true);
    EXPECT_EQ(half.overcast_slot, 3);
    EXPECT_FLOAT_EQ(half.sunny_weight, 0.5f);
    EXPECT_FLOAT_EQ(half.overcast_weight, 0.5f);
    EXPECT_NEAR(half.sun_irradiance_rgb.x, 0.5 * clear.sun_irradiance_rgb.x, 1e-9);
    EXPECT_EQ(overcast.sun_irradiance_rgb, glm::dvec3(0.0));
    EXPECT_FLOAT_EQ(overcast.sunny_weight, 0.0f);
    // NaN or out-of-range cover is clamped, never propagated.
    const FrameLighting nan_cover = computeFrameLighting(manifest, observer, noon, std::nanf(""), true);
    EXPECT_FLOAT_EQ(nan_cover.overcast_weight, 0.0f);
}

TEST(FrameLighting, NightHasNoSunAndTwilightFades) {
    const BakeSetManifest manifest = makeSyntheticBakeSet().manifest;
    const SunObserver observer = siteObserver(manifest);
    const FrameLighting night = computeFrameLighting(manifest, observer, syntheticLocalTime(23, 0), 0.0f, true);
    EXPECT_FALSE(night.sun.above_horizon);
    EXPECT_EQ(night.sun_irradiance_rgb, glm::dvec3(0.0));
    EXPECT_FLOAT_EQ(night.sunny_weight, 0.0f);
    // Sunset is near 19:20 here: a few minutes after it, part of the sunny light remains.
    bool saw_twilight = false;
    for (int minute = 19 * 60; minute < 20 * 60 + 30; ++minute) {
        const FrameLighting lighting = computeFrameLighting(manifest, observer, syntheticLocalTime(0, minute), 0.0f, true);
        if (!lighting.sun.above_horizon && lighting.sunny_weight > 0.0f && lighting.sunny_weight < 1.0f) {
            saw_twilight = true;
            EXPECT_NEAR(lighting.sunny_weight, 1.0 + lighting.sun.apparent_elevation_deg / 6.0, 1e-4);
        }
    }
    EXPECT_TRUE(saw_twilight);
}

TEST(ShadowFit, ReceiversLieInsideTheWindowAndTheSunIsNearest) {
    const glm::dvec3 low(-3, -3, 0), high(3, 3, 4);
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    const ShadowFit fit = fitShadowMap(low, high, low, high, sun, 1024);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y, (corner & 4) ? high.z : low.z);
        const glm::dvec4 clip = fit.enu_to_clip * glm::dvec4(p, 1.0);
        EXPECT_LE(std::abs(clip.x), 1.0);
        EXPECT_LE(std::abs(clip.y), 1.0);
        EXPECT_GT(clip.z, 0.0);
        EXPECT_LT(clip.z, 1.0);
    }
    // Of two points on one sun ray, the one towards the sun is nearer (smaller depth) at the same texel.
    const glm::dvec4 far = fit.enu_to_clip * glm::dvec4(0, 0, 0, 1);
    const glm::dvec4 near = fit.enu_to_clip * glm::dvec4(sun * 2.0, 1.0);
    EXPECT_LT(near.z, far.z);
    EXPECT_NEAR(near.x, far.x, 1e-12);
    EXPECT_NEAR(near.y, far.y, 1e-12);
}

// Snapping: a sun moving by a hundredth of a degree keeps the texel size, and the world point at a texel corner
// stays on a texel corner (its clip coordinates move by whole texels), so the shadow's texels do not swim.
TEST(ShadowFit, SmallSunMotionKeepsTheTexelGrid) {
    const glm::dvec3 low(-4, -4, 0), high(4, 4, 3);
    const glm::dvec3 sun_a = glm::normalize(glm::dvec3(0.4, -0.3, 0.8));
    const glm::dvec3 sun_b = glm::normalize(sun_a + glm::dvec3(1.5e-4, 0.0, 0.0));
    const ShadowFit a = fitShadowMap(low, high, low, high, sun_a, 512);
    const ShadowFit b = fitShadowMap(low, high, low, high, sun_b, 512);
    EXPECT_EQ(a.texel_size_m, b.texel_size_m);
    // The window's centre is a whole number of texels along the light's right and up axes.
    const glm::dvec4 origin = a.enu_to_clip * glm::dvec4(0, 0, 0, 1);
    const double texels_x = (origin.x + 1.0) * 0.5 * 512.0, texels_y = (origin.y + 1.0) * 0.5 * 512.0;
    EXPECT_NEAR(texels_x, std::round(texels_x), 1e-6);
    EXPECT_NEAR(texels_y, std::round(texels_y), 1e-6);
}

}  // namespace
}  // namespace gusuku
