// The building's light carried past the slots texel by texel (engine/src/runtime/sky_carry.h, issue 44 item 4),
// against the closed form of a building of two texels under a uniform sky over flat ground in the sun:
//   a roof (horizontal, sees the whole sky and no ground):       E = E_sky
//   a wall (vertical, beside sunlit ground of albedo rho):       E = E_sky / 2 + rho (E_sky + E_sun,c sin h) / 2
// (a vertical face sees half the sky and half the ground; the ground's irradiance is the sky's plus the sun's on
// the horizontal, E_sun,c per channel from the air-mass model, sun_air_mass.h, reddening as the sun sets). The
// slots bake both at three suns; past the last slot the building pass must read, per texel, what the closed form
// gives at the frame's sun: the roof keeps its sky, the wall loses its ground's sun. The building's mean factor
// (indirectCarry, before this) moves both by the same ratio: the roof too dark, the wall too bright.

#include <gtest/gtest.h>

#include <glm/common.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "frame_preparation.h"
#include "gusuku/maths/indirect_carry.h"
#include "gusuku/maths/sun_air_mass.h"
#include "sky_carry.h"

namespace gusuku::runtime_detail {
namespace {

constexpr double kBeta = 0.12;      // the slots' aerosol depth
constexpr double kSunScale = 7.5;   // the bake set's units per unit of the model's luminance
const glm::dvec3 kSky{0.30, 0.34, 0.45};  // the uniform sky's irradiance on the horizontal
const glm::dvec3 kRho{0.35, 0.30, 0.22};  // the ground's albedo
// The slots' suns (a morning, noon, the afternoon's last) and, after it, the frame's.
const std::vector<double> kSlotElevations{38.0, 62.0, 33.0};
constexpr int kLastSlot = 2;

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

glm::dvec3 modelSun(double elevation_deg) {
    return kSunScale * extraterrestrialSunColourRgb() * sunTransmittanceRgb(elevation_deg, kBeta);
}
glm::dvec3 horizontalSun(double elevation_deg) {
    if (elevation_deg <= 0.0) return glm::dvec3(0.0);
    return modelSun(elevation_deg) * std::sin(elevation_deg * std::numbers::pi / 180.0);
}
glm::dvec3 roofClosedForm(double) { return kSky; }
glm::dvec3 wallClosedForm(double elevation_deg) { return 0.5 * kSky + 0.5 * kRho * (kSky + horizontalSun(elevation_deg)); }

struct Bake {
    BakeSetManifest manifest;
    std::vector<BakeSetSlotImages> slots;  // building: 2 x 1 texels, the roof's then the wall's
    std::vector<glm::vec3> means;
};
Bake bakeTheSlots() {
    Bake bake;
    for (double elevation : kSlotElevations) {
        BakeSetSlot slot;
        slot.name = "sunny_" + std::to_string(int(elevation));
        slot.sun.present = true;
        slot.sun.position = BakeSetSunPosition{240.0, elevation, {0.0, 0.0, 1.0}};
        slot.sun.irradiance_rgb = modelSun(elevation);
        bake.manifest.slots.push_back(slot);
        const glm::dvec3 roof = roofClosedForm(elevation), wall = wallClosedForm(elevation);
        BakeSetSlotImages images;
        images.building = {2, 1, {float(roof.x), float(roof.y), float(roof.z), 1.0f,
                                  float(wall.x), float(wall.y), float(wall.z), 1.0f}};
        bake.slots.push_back(images);
        bake.means.push_back(glm::vec3(0.5 * (roof + wall)));
    }
    return bake;
}

// The frame after the last slot: its sun at this elevation, the last slot alone (computeFrameLighting's clamp).
FrameLighting afterTheLastSlot(double elevation_deg) {
    FrameLighting lighting;
    lighting.sun.apparent_elevation_deg = elevation_deg;
    lighting.sun.above_horizon = elevation_deg > 0.0;
    lighting.slot_a = kLastSlot;
    lighting.slot_b = kLastSlot;
    lighting.sunny_weight = 1.0f;
    return lighting;
}

glm::dvec3 texel(const BakeSetImage& image, int index) {
    return glm::dvec3(image.rgba[size_t(index) * 4], image.rgba[size_t(index) * 4 + 1],
                      image.rgba[size_t(index) * 4 + 2]);
}

// What building.frag sums for a texel with these uniforms (sky layer = slot count).
glm::dvec3 buildingReads(const Bake& bake, const BakeSetImage& sky, const shader_interface::FrameUniforms& u,
                         int index) {
    const bool carried = u.sky_weight > 0.0f;
    const double weight_a = carried ? u.sky_carried_weight_a : u.slot_weights[0];
    const double weight_b = carried ? u.sky_carried_weight_b : u.slot_weights[1];
    glm::dvec3 irradiance = weight_a * texel(bake.slots[size_t(u.slot_layers[0])].building, index) +
                            weight_b * texel(bake.slots[size_t(u.slot_layers[1])].building, index);
    if (carried) {
        const glm::dvec3 ratio(u.sky_sun_ratio[0], u.sky_sun_ratio[1], u.sky_sun_ratio[2]);
        irradiance = glm::mix(double(u.sky_weight) * texel(sky, index), irradiance, ratio);
    }
    return irradiance;
}

shader_interface::FrameUniforms uniformsFor(const Bake& bake, const FrameLighting& lighting) {
    shader_interface::FrameUniforms u{};
    const SlotBlend blend = slotBlendFor(lighting);
    u.slot_layers = {{float(lighting.slot_a), float(lighting.slot_b), 0.0f}};
    u.slot_weights = {{blend.weights[0], blend.weights[1], 0.0f}};
    writeSkyCarry(blend, sunBounceRatio(bake.manifest, lighting), int(bake.slots.size()), u);
    return u;
}

TEST(SkyCarry, EachTexelsSkyIsFitted) {
    const Bake bake = bakeTheSlots();
    const BakeSetImage sky = fitTexelSky(bake.manifest, bake.slots);
    ASSERT_EQ(sky.rgba.size(), 8u);
    // The roof holds no sun: its sky is its light. The wall's is the closed form's at a sun of 0 (the slots' light
    // is stored in floats).
    for (int channel = 0; channel < 3; ++channel) {
        EXPECT_NEAR(texel(sky, 0)[channel], kSky[channel], 1e-6) << channel;
        EXPECT_NEAR(texel(sky, 1)[channel], wallClosedForm(0.0)[channel], 1e-5) << channel;
    }
}

TEST(SkyCarry, AfterTheLastSlotEachTexelFollowsTheClosedForm) {
    const Bake bake = bakeTheSlots();
    const BakeSetImage sky = fitTexelSky(bake.manifest, bake.slots);
    const SunBounceFit mean_fit = fitSunBounce(bake.manifest, bake.means);
    ASSERT_TRUE(mean_fit.fitted);
    for (double elevation : {25.0, 15.0, 8.0, 2.0}) {
        const FrameLighting lighting = afterTheLastSlot(elevation);
        const shader_interface::FrameUniforms u = uniformsFor(bake, lighting);
        ASSERT_GT(u.sky_weight, 0.0f) << elevation;
        const double mean_carry = indirectCarry(bake.manifest, mean_fit, lighting);
        for (int index = 0; index < 2; ++index) {
            const glm::dvec3 truth = index == 0 ? roofClosedForm(elevation) : wallClosedForm(elevation);
            const glm::dvec3 read = buildingReads(bake, sky, u, index);
            // The closed form to float precision in every channel (the goal is 5 %)...
            for (int channel = 0; channel < 3; ++channel)
                EXPECT_NEAR(read[channel] / truth[channel], 1.0, 1e-4) << elevation << " " << index << " " << channel;
            // ... where the building's mean factor misses by more (the roof dark, the wall bright).
            const glm::dvec3 held = texel(bake.slots[kLastSlot].building, index);
            const double mean_error = luminance(mean_carry * held) / luminance(truth) - 1.0;
            if (elevation <= 15.0) {
                EXPECT_GT(std::abs(mean_error), 0.05) << elevation << " texel " << index;
            }
        }
    }
    // At and below the horizon the sun's bounce is gone and each texel keeps its own sky.
    const shader_interface::FrameUniforms u = uniformsFor(bake, afterTheLastSlot(-2.0));
    EXPECT_FLOAT_EQ(u.sky_weight, 1.0f);
    for (int channel = 0; channel < 3; ++channel) EXPECT_EQ(u.sky_sun_ratio[channel], 0.0f);
}

TEST(SkyCarry, NothingChangesAtOrBetweenTheSlots) {
    const Bake bake = bakeTheSlots();
    // At the last slot's own sun, and between noon and the afternoon on the sun's arc: the building reads
    // slot_weights (sky_weight 0), the same uniforms and the same fetches as before.
    for (const FrameLighting& lighting : {afterTheLastSlot(kSlotElevations[kLastSlot]), [] {
             FrameLighting between = afterTheLastSlot(50.0);
             between.slot_a = 1;
             between.slot_b_weight = 0.4f;
             return between;
         }()}) {
        const shader_interface::FrameUniforms u = uniformsFor(bake, lighting);
        EXPECT_EQ(u.sky_weight, 0.0f);
        EXPECT_EQ(u.sky_layer, 0.0f);
        EXPECT_EQ(u.sky_carried_weight_a, 0.0f);
    }
    // No sky layer (ASTC lightmaps, or a bake set that cannot be fitted): nothing written.
    shader_interface::FrameUniforms u{};
    writeSkyCarry(slotBlendFor(afterTheLastSlot(10.0)), glm::dvec3(0.5), -1, u);
    EXPECT_EQ(u.sky_weight, 0.0f);
    Bake one = bakeTheSlots();
    one.manifest.slots.resize(1);
    EXPECT_TRUE(fitTexelSky(one.manifest, one.slots).rgba.empty());
}

TEST(SkyCarry, NeitherBounceNorSkyIsNegative) {
    // A texel brighter under the lower suns (noise, or a bounce that falls as the sun climbs): B clamps at 0 and
    // its sky is its mean; a texel whose fitted line crosses 0 above g = 0 keeps a sky of 0.
    Bake bake = bakeTheSlots();
    const float brighter_low[3] = {0.9f, 0.5f, 0.95f};
    const float steep[3] = {0.02f, 0.40f, 0.03f};
    for (size_t slot = 0; slot < 3; ++slot) {
        for (int channel = 0; channel < 3; ++channel) {
            bake.slots[slot].building.rgba[size_t(channel)] = brighter_low[slot];
            bake.slots[slot].building.rgba[4 + size_t(channel)] = steep[slot];
        }
    }
    const BakeSetImage sky = fitTexelSky(bake.manifest, bake.slots);
    EXPECT_NEAR(texel(sky, 0).x, (0.9 + 0.5 + 0.95) / 3.0, 1e-6);
    EXPECT_EQ(texel(sky, 1).x, 0.0);
}

}  // namespace
}  // namespace gusuku::runtime_detail
