// The baked sky and bounce light carried past the slots (gusuku/maths/indirect_carry.h, issue 44 item 4): pinned
// against the closed form of the model it assumes. A bake set whose sunny slots' mean E_ind is exactly S + B g_k,
// g_k = luminance(E_sun) sin(h) with E_sun the air-mass model's own sun (ET_c T_c(h, beta), sun_air_mass.h), must
// give back S and B, and after the last slot a carry of (S + B g(h)) / (S + B g(h_slot)) in luminance, g(h) from
// the same closed form at the frame's elevation; 1 at and between the slots; S / (S + B g) at the horizon.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "gusuku/maths/indirect_carry.h"
#include "gusuku/maths/sun_air_mass.h"

namespace gusuku {
namespace {

constexpr double kBeta = 0.12;             // the slots' aerosol depth (inside the fit's clamp)
constexpr double kSunScale = 7.5;          // the bake set's units per unit of the model's luminance
const glm::dvec3 kSky{0.30, 0.34, 0.45};   // S
const glm::dvec3 kPerSun{0.021, 0.019, 0.016};  // B

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z; }

// The closed form of the sun the slots hold and the frame's sun is carried to.
glm::dvec3 modelSun(double elevation_deg) {
    return kSunScale * extraterrestrialSunColourRgb() * sunTransmittanceRgb(elevation_deg, kBeta);
}
double modelG(double elevation_deg) {
    return luminance(modelSun(elevation_deg)) * std::sin(elevation_deg * std::numbers::pi / 180.0);
}

// Sunny slots at these elevations (a morning, noon and afternoon), then an overcast slot; per slot its mean E_ind.
struct Bake {
    BakeSetManifest manifest;
    std::vector<glm::vec3> means;
};
Bake bakeWithSunnySlotsAt(const std::vector<double>& elevations) {
    Bake bake;
    for (double elevation : elevations) {
        BakeSetSlot slot;
        slot.name = "sunny_" + std::to_string(int(elevation));
        slot.sun.present = true;
        slot.sun.position = BakeSetSunPosition{180.0, elevation, {0.0, 0.0, 1.0}};
        slot.sun.irradiance_rgb = modelSun(elevation);
        bake.manifest.slots.push_back(slot);
        bake.means.push_back(glm::vec3(kSky + kPerSun * modelG(elevation)));
    }
    BakeSetSlot overcast;
    overcast.name = "overcast";
    overcast.sky = BakeSetSky::Overcast;
    bake.manifest.slots.push_back(overcast);
    bake.means.push_back(glm::vec3(0.9f));  // any: the overcast slot is not part of the fit
    return bake;
}

FrameLighting sunAt(double elevation_deg, int slot_a, int slot_b, float slot_b_weight) {
    FrameLighting lighting;
    lighting.sun.apparent_elevation_deg = elevation_deg;
    lighting.sun.above_horizon = elevation_deg > 0.0;
    lighting.slot_a = slot_a;
    lighting.slot_b = slot_b;
    lighting.slot_b_weight = slot_b_weight;
    lighting.sunny_weight = 1.0f;
    return lighting;
}

TEST(IndirectCarry, FitRecoversTheSkyAndTheSunsBounce) {
    const Bake bake = bakeWithSunnySlotsAt({45.0, 85.0, 58.0});
    const SunBounceFit fit = fitSunBounce(bake.manifest, bake.means);
    ASSERT_TRUE(fit.fitted);
    for (int channel = 0; channel < 3; ++channel) {
        // The means are floats: S and B come back to float's precision over the slots' spread of g.
        EXPECT_NEAR(fit.sky[channel], kSky[channel], 1e-5) << channel;
        EXPECT_NEAR(fit.per_sun[channel], kPerSun[channel], 1e-6) << channel;
    }
}

TEST(IndirectCarry, AfterTheLastSlotTheLightFollowsTheClosedForm) {
    const Bake bake = bakeWithSunnySlotsAt({45.0, 85.0, 58.0});
    const SunBounceFit fit = fitSunBounce(bake.manifest, bake.means);
    const double held = luminance(kSky + kPerSun * modelG(58.0));
    for (double elevation : {50.0, 40.0, 30.0, 20.0, 10.0, 3.0}) {
        const double expected = luminance(kSky + kPerSun * modelG(elevation)) / held;
        const double carry = indirectCarry(bake.manifest, fit, sunAt(elevation, 2, 1, 0.0f));
        EXPECT_NEAR(carry, expected, 2e-5) << elevation;
        EXPECT_LT(carry, 1.0) << elevation;
    }
    // At the horizon the sun's bounce is gone: the sky's alone.
    EXPECT_NEAR(indirectCarry(bake.manifest, fit, sunAt(0.0, 2, 1, 0.0f)), luminance(kSky) / held, 2e-5);
    EXPECT_NEAR(indirectCarry(bake.manifest, fit, sunAt(-3.0, 2, 1, 0.0f)), luminance(kSky) / held, 2e-5);
}

TEST(IndirectCarry, NothingChangesAtOrBetweenTheSlots) {
    const Bake bake = bakeWithSunnySlotsAt({45.0, 85.0, 58.0});
    const SunBounceFit fit = fitSunBounce(bake.manifest, bake.means);
    // At a slot's own elevation: exactly 1 (the baked instant's composite is unchanged).
    for (int slot = 0; slot < 3; ++slot) {
        const double elevation = bake.manifest.slots[size_t(slot)].sun.position->apparent_elevation_deg;
        EXPECT_EQ(indirectCarry(bake.manifest, fit, sunAt(elevation, slot, slot, 0.0f)), 1.0) << slot;
    }
    // Between 58 and 85 degrees the sun gives the ground more than the blend of the two: held at 1.
    EXPECT_EQ(indirectCarry(bake.manifest, fit, sunAt(75.0, 1, 2, 0.4f)), 1.0);
    // The overcast slot alone, or a bake set of one sunny slot, cannot carry: 1.
    EXPECT_EQ(indirectCarry(bake.manifest, fit, sunAt(20.0, -1, -1, 0.0f)), 1.0);
    const Bake one = bakeWithSunnySlotsAt({58.0});
    const SunBounceFit one_fit = fitSunBounce(one.manifest, one.means);
    EXPECT_FALSE(one_fit.fitted);
    EXPECT_EQ(indirectCarry(one.manifest, one_fit, sunAt(20.0, 0, 0, 0.0f)), 1.0);
}

TEST(IndirectCarry, FallsContinuouslyWithTheSun) {
    const Bake bake = bakeWithSunnySlotsAt({45.0, 85.0, 58.0});
    const SunBounceFit fit = fitSunBounce(bake.manifest, bake.means);
    double previous = 1.0;
    for (double elevation = 58.0; elevation >= -1.0; elevation -= 0.25) {
        const double carry = indirectCarry(bake.manifest, fit, sunAt(elevation, 2, 1, 0.0f));
        EXPECT_LE(carry, previous + 1e-12) << elevation;
        EXPECT_LT(previous - carry, 0.01) << elevation;  // no step
        previous = carry;
    }
}

}  // namespace
}  // namespace gusuku
