// The clear-sky sun (gusuku/maths/sun_irradiance.h): Kasten-Young air mass and the ESRA beam model against their
// published formulas, the colour and elevation behaviour the header documents, the carrying of a measured
// E_sun between elevations, and values pinned from the baker's own copy before the model moved to
// gusuku_maths (so bake sets did not change).

#include <cmath>
#include <numbers>

#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include "gusuku/maths/sun_irradiance.h"

namespace {

using gusuku::carrySunIrradianceRgb;
using gusuku::clearSkySunIrradianceRgb;
using gusuku::kastenYoungAirMass;
using gusuku::sunElevationScaleRgb;

constexpr double kDeg = std::numbers::pi / 180.0;

void expectRelativelyNear(const glm::dvec3& actual, const glm::dvec3& expected, double relative) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], relative * std::fabs(expected[c])) << "channel " << c;
}

TEST(SunIrradiance, KastenYoungAirMassMatchesItsFormulaInZenithForm) {
    // Kasten and Young (1989) as usually printed, with the zenith angle z: 1 / (cos z + 0.50572 (96.07995 - z)^-1.6364)
    auto zenithForm = [](double zenith_deg) {
        return 1.0 / (std::cos(zenith_deg * kDeg) + 0.50572 * std::pow(96.07995 - zenith_deg, -1.6364));
    };
    EXPECT_NEAR(kastenYoungAirMass(90.0), 1.0, 1e-3);
    EXPECT_NEAR(kastenYoungAirMass(30.0), 1.994, 1e-3);
    for (double zenith : {0.0, 30.0, 60.0, 80.0, 89.0, 90.0})
        EXPECT_NEAR(kastenYoungAirMass(90.0 - zenith), zenithForm(zenith), 1e-9 * zenithForm(zenith));
    EXPECT_NEAR(kastenYoungAirMass(0.0), 37.92, 0.05);  // the formula's horizon value
    EXPECT_TRUE(std::isinf(kastenYoungAirMass(-1.0)));
    EXPECT_THROW(kastenYoungAirMass(std::nan("")), std::invalid_argument);
}

TEST(SunIrradiance, ClearSkyIsPlausibleMonotonicAndZeroBelowHorizon) {
    const glm::dvec3 zenith = clearSkySunIrradianceRgb(90.0);
    // ESRA, T_L = 3, m = 1: 1367 exp(-0.8662 * 3 / 8.26674) ~ 1000 W/m^2 (a typical clear-sky DNI).
    const double zenith_expected = 1367.0 * std::exp(-0.8662 * 3.0 * 0.99971 /
                                                     (6.6296 + 1.7513 * 0.99971 - 0.1202 * 0.99942 +
                                                      0.0065 * 0.99913 - 0.00013 * 0.99884));
    EXPECT_NEAR(zenith.y, zenith_expected, 0.5);
    EXPECT_NEAR(zenith.x, zenith.y, 1e-9);  // neutral at the zenith
    EXPECT_NEAR(zenith.z, zenith.y, 1e-9);
    glm::dvec3 previous(0.0);
    for (double elevation = 0.25; elevation <= 90.0; elevation += 0.25) {
        const glm::dvec3 e = clearSkySunIrradianceRgb(elevation);
        for (int c = 0; c < 3; ++c) EXPECT_GT(e[c], previous[c]) << "elevation " << elevation << " channel " << c;
        previous = e;
    }
    for (double below : {0.0, -0.5, -10.0, -90.0}) EXPECT_EQ(clearSkySunIrradianceRgb(below), glm::dvec3(0.0));
    EXPECT_LT(clearSkySunIrradianceRgb(40.0, 6.0).y, clearSkySunIrradianceRgb(40.0, 3.0).y);  // hazier: dimmer
    EXPECT_THROW(clearSkySunIrradianceRgb(std::nan(""), 3.0), std::invalid_argument);
    EXPECT_THROW(clearSkySunIrradianceRgb(30.0, 0.0), std::invalid_argument);
    EXPECT_THROW(clearSkySunIrradianceRgb(30.0, INFINITY), std::invalid_argument);
}

TEST(SunIrradiance, ReddeningAsTheHeaderStates) {
    // gusuku/maths/sun_irradiance.h: with T_L = 3, R/G 1.04 and B/G 0.92 at 30 deg, R/G 1.25 and B/G 0.62 at 5 deg.
    const glm::dvec3 at30 = clearSkySunIrradianceRgb(30.0);
    const glm::dvec3 at5 = clearSkySunIrradianceRgb(5.0);
    EXPECT_NEAR(at30.x / at30.y, 1.04, 0.005);
    EXPECT_NEAR(at30.z / at30.y, 0.92, 0.005);
    EXPECT_NEAR(at5.x / at5.y, 1.25, 0.005);
    EXPECT_NEAR(at5.z / at5.y, 0.62, 0.005);
    EXPECT_NEAR(clearSkySunIrradianceRgb(90.0).y, 998.0, 0.5);
}

TEST(SunIrradiance, SameNumbersAsTheBakersFormerCopy) {
    // Printed (%.17g) from baker/src/clear_sky_sun.cpp at commit a84ad4b, the last bake before the move.
    expectRelativelyNear(clearSkySunIrradianceRgb(60.0), {967.5777136789394, 960.63013307481265, 945.97588539322669},
                         1e-14);
    expectRelativelyNear(clearSkySunIrradianceRgb(37.5), {884.73481405862981, 860.47750848569069, 810.93165946754129},
                         1e-14);
    expectRelativelyNear(clearSkySunIrradianceRgb(3.0), {287.438787454433, 215.83896222999149, 117.14612100070813},
                         1e-14);
    expectRelativelyNear(clearSkySunIrradianceRgb(25.0, 5.5),
                         {500.36230692315576, 453.34320397705437, 367.28566563831271}, 1e-14);
    expectRelativelyNear(sunElevationScaleRgb(48.7, 21.3),
                         {0.80076261663301507, 0.76085462841001295, 0.68224504070138958}, 1e-14);
}

TEST(SunIrradiance, CarryingBetweenElevations) {
    const glm::dvec3 measured(3.1, 2.9, 2.4);  // a photo's disc, in its own units
    EXPECT_EQ(carrySunIrradianceRgb(measured, 37.0, 37.0), measured);
    // Carrying the model's own value lands on the model's value at the new elevation.
    expectRelativelyNear(carrySunIrradianceRgb(clearSkySunIrradianceRgb(20.0), 20.0, 65.0),
                         clearSkySunIrradianceRgb(65.0), 1e-13);
    // Composition: 20 -> 60 -> 45 is 20 -> 45.
    expectRelativelyNear(carrySunIrradianceRgb(carrySunIrradianceRgb(measured, 20.0, 60.0), 60.0, 45.0),
                         carrySunIrradianceRgb(measured, 20.0, 45.0), 1e-13);
    // Towards a lower sun every channel drops, blue most.
    const glm::dvec3 lower = carrySunIrradianceRgb(measured, 60.0, 10.0);
    for (int c = 0; c < 3; ++c) EXPECT_LT(lower[c], measured[c]);
    EXPECT_GT(lower.x / measured.x, lower.z / measured.z);
    // No beam at either end: nothing to carry.
    EXPECT_EQ(carrySunIrradianceRgb(measured, 30.0, -2.0), glm::dvec3(0.0));
    EXPECT_EQ(carrySunIrradianceRgb(measured, -2.0, 30.0), glm::dvec3(0.0));
    // The factor is the ratio of the model's values, per channel.
    const glm::dvec3 scale = sunElevationScaleRgb(48.7, 21.3);
    const glm::dvec3 ratio = clearSkySunIrradianceRgb(21.3) / clearSkySunIrradianceRgb(48.7);
    expectRelativelyNear(scale, ratio, 1e-15);
    EXPECT_EQ(carrySunIrradianceRgb(measured, 48.7, 21.3), measured * scale);
}

}  // namespace
