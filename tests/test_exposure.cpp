// gusuku/maths/exposure.h against analytic values: the ISO 12232 camera relations (sunny 16, Filament's
// 1 / (1.2 2^EV100)), the meter's middle grey, the platforms' neutral values, the Planckian locus at CIE
// illuminant A, and the errors for values no exposure follows from.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/exposure.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun_irradiance.h"

namespace {

using gusuku::CameraSpeedModel;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The InputError's message, or "" when the call did not throw one.
template <typename Call> std::string inputErrorOf(Call call) {
    try {
        call();
    } catch (const gusuku::InputError& error) {
        return error.what();
    }
    return "";
}

TEST(Exposure, SunnySixteenIsEv14Point6) {
    // ISO 100, f/16, 1/100 s: log2(16^2 / 0.01) = log2(25600).
    EXPECT_NEAR(gusuku::ev100FromCamera(16.0, 0.01, 100.0), 14.643856, 1e-6);
    // One stop of ISO is one EV: ISO 200 at the same setting sees a scene one stop darker.
    EXPECT_NEAR(gusuku::ev100FromCamera(16.0, 0.01, 200.0), 13.643856, 1e-6);
    EXPECT_NEAR(gusuku::ev100FromCamera(1.0, 1.0, 100.0), 0.0, 1e-12);
}

TEST(Exposure, WhiteLuminanceFollowsIso12232) {
    // Saturation: 78 / (0.65 x 100) = 1.2 cd m^-2 at EV100 0 (Frostbite's and Filament's constant).
    EXPECT_NEAR(gusuku::whiteLuminanceFromEv100(0.0), 1.2, 1e-12);
    EXPECT_NEAR(gusuku::whiteLuminanceFromEv100(10.0), 1.2 * 1024.0, 1e-9);
    // SOS: 10 / (0.65 x 100 x 0.18).
    EXPECT_NEAR(gusuku::whiteLuminanceFromEv100(0.0, CameraSpeedModel::kStandardOutputSensitivity),
                0.8547008547, 1e-9);
    for (double ev : {-3.0, 0.0, 7.5, 14.64, 20.0})
        for (CameraSpeedModel model : {CameraSpeedModel::kSaturation, CameraSpeedModel::kStandardOutputSensitivity})
            EXPECT_NEAR(gusuku::ev100FromWhiteLuminance(gusuku::whiteLuminanceFromEv100(ev, model), model), ev, 1e-12);
}

TEST(Exposure, MeteredMeanShowsAsMiddleGreyWithHeadroom) {
    // A reflected-light meter (K = 12.5) on a scene of mean luminance 4000 cd m^-2 (a sunlit street).
    const double average = 4000.0;
    const double ev = gusuku::ev100FromAverageLuminance(average);
    EXPECT_NEAR(ev, std::log2(4000.0 * 100.0 / 12.5), 1e-12);
    // Saturation-based: the mean lands at 12.5 / 120 of white; SOS: 12.5 / 85.47 = 0.146, 0.3 stop under middle
    // grey (0.18): the headroom the meter's K leaves.
    EXPECT_NEAR(average / gusuku::whiteLuminanceFromEv100(ev), 12.5 / 120.0, 1e-12);
    EXPECT_NEAR(average / gusuku::whiteLuminanceFromEv100(ev, CameraSpeedModel::kStandardOutputSensitivity),
                0.14625, 1e-12);
}

TEST(Exposure, RuntimeExposureOfAnEv) {
    // With k = 1 (the bake set's unit is 1 cd m^-2) the exposure is Filament's 1 / (1.2 2^EV100).
    for (double ev : {0.0, 8.0, 14.643856})
        EXPECT_NEAR(gusuku::exposureFromEv100(ev, 1.0), 1.0 / (1.2 * std::exp2(ev)), 1e-15);
    // A sky map in Radiance's W sr^-1 m^-2 (k = 179) under sunny 16: a grey of radiance Y shows at 179 Y / 30720.
    const double sunny16 = gusuku::ev100FromCamera(16.0, 0.01, 100.0);
    const double exposure = gusuku::exposureFromEv100(sunny16, gusuku::kRadianceWhiteEfficacy);
    EXPECT_NEAR(exposure, 179.0 / (1.2 * 25600.0), 1e-12);
    // The radiance that reaches display 1 is white luminance / k.
    EXPECT_NEAR(1.0 / exposure * gusuku::kRadianceWhiteEfficacy, gusuku::whiteLuminanceFromEv100(sunny16), 1e-9);
    for (CameraSpeedModel model : {CameraSpeedModel::kSaturation, CameraSpeedModel::kStandardOutputSensitivity})
        for (double ev : {-2.0, 6.0, 15.0})
            EXPECT_NEAR(gusuku::ev100FromExposure(gusuku::exposureFromEv100(ev, 179.0, model), 179.0, model), ev,
                        1e-12);
}

TEST(Exposure, LuminancePerUnitFromTheClearSun) {
    // E_sun given in the model's own W m^-2 at the zenith (neutral there): k is the sun's efficacy, lm/W.
    const glm::dvec3 zenith_sun = gusuku::clearSkySunIrradianceRgb(90.0);
    EXPECT_NEAR(gusuku::luminancePerUnitFromClearSun(zenith_sun, 90.0), 133800.0 / 1367.0, 1e-9);
    // A bake set stored at half that scale has units twice as bright.
    EXPECT_NEAR(gusuku::luminancePerUnitFromClearSun(0.5 * zenith_sun, 90.0), 2.0 * 133800.0 / 1367.0, 1e-9);
    // At 30 degrees the reddened beam's luminance is within 2 % of its green channel.
    const glm::dvec3 low_sun = gusuku::clearSkySunIrradianceRgb(30.0);
    EXPECT_NEAR(gusuku::luminancePerUnitFromClearSun(low_sun, 30.0) / gusuku::kSunLuminousEfficacy, 1.0, 0.02);
    EXPECT_NE(inputErrorOf([&] { gusuku::luminancePerUnitFromClearSun(zenith_sun, 0.0); })
                  .find("apparent_elevation_deg"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([] { gusuku::luminancePerUnitFromClearSun(glm::dvec3(0.0), 45.0); })
                  .find("sun_irradiance_rgb"),
              std::string::npos);
}

TEST(Exposure, ArkitNeutralIntensityGivesTheNeutralExposure) {
    const double reference = 0.05;  // the ground's predicted luminance, bake set units
    EXPECT_NEAR(gusuku::neutralExposure(reference), 0.18 / 0.05, 1e-12);
    EXPECT_NEAR(gusuku::exposureFromArkitAmbientIntensity(1000.0, reference), gusuku::neutralExposure(reference),
                1e-12);
    // Twice the lumens, twice the display value.
    EXPECT_NEAR(gusuku::exposureFromArkitAmbientIntensity(2000.0, reference), 2.0 * 0.18 / 0.05, 1e-12);
    // The neutral exposure shows the reference at middle grey.
    EXPECT_NEAR(reference * gusuku::exposureFromArkitAmbientIntensity(1000.0, reference), 0.18, 1e-12);
}

TEST(Exposure, ArcorePixelIntensityIsTheFramesGammaMean) {
    const double reference = 0.05;
    // Middle grey in ARCore's gamma 2.2 gives the neutral exposure, as ARKit's 1000 lm does.
    EXPECT_NEAR(gusuku::exposureFromArcorePixelIntensity(std::pow(0.18, 1.0 / 2.2), reference),
                gusuku::exposureFromArkitAmbientIntensity(1000.0, reference), 1e-12);
    // A white frame: the reference shows at 1.
    EXPECT_NEAR(reference * gusuku::exposureFromArcorePixelIntensity(1.0, reference), 1.0, 1e-12);
    // ARCore's samples' middle grey 0.466 is 0.466^2.2 = 0.1864, within 4 % of neutral.
    EXPECT_NEAR(reference * gusuku::exposureFromArcorePixelIntensity(0.466, reference), 0.18639, 1e-4);
}

TEST(Exposure, ArcoreColorCorrectionIsLinearisedByPower22) {
    const glm::dvec3 neutral = gusuku::whiteBalanceGainsFromArcoreColorCorrection(glm::dvec3(1.0));
    EXPECT_DOUBLE_EQ(neutral.r, 1.0);
    EXPECT_DOUBLE_EQ(neutral.g, 1.0);
    EXPECT_DOUBLE_EQ(neutral.b, 1.0);
    const glm::dvec3 warm = gusuku::whiteBalanceGainsFromArcoreColorCorrection({1.1, 1.0, 0.9});
    EXPECT_NEAR(warm.r, std::pow(1.1, 2.2), 1e-12);
    EXPECT_NEAR(warm.g, 1.0, 1e-15);
    EXPECT_NEAR(warm.b, std::pow(0.9, 2.2), 1e-12);
}

TEST(Exposure, PlanckianLocusAtIlluminantA) {
    // CIE illuminant A: 2856 K with c2 = 1.435e-2 m K, i.e. 2848 K at today's 1.4388e-2; chromaticity
    // (0.44757, 0.40745) (CIE 15).
    const glm::dvec2 a = gusuku::planckianChromaticity(2856.0 * 1.435 / 1.4388);
    EXPECT_NEAR(a.x, 0.44757, 3e-4);
    EXPECT_NEAR(a.y, 0.40745, 3e-4);
    // 6500 K sits just below D65 (0.3127, 0.3290), on the Planckian side.
    const glm::dvec2 neutral = gusuku::planckianChromaticity(6500.0);
    EXPECT_NEAR(neutral.x, 0.3135, 5e-4);
    EXPECT_NEAR(neutral.y, 0.3237, 5e-4);
}

TEST(Exposure, ColourTemperatureGainsFollowTheLight) {
    const glm::dvec3 neutral = gusuku::whiteBalanceGainsFromColourTemperature(6500.0);
    EXPECT_NEAR(neutral.r, 1.0, 1e-12);
    EXPECT_NEAR(neutral.g, 1.0, 1e-12);
    EXPECT_NEAR(neutral.b, 1.0, 1e-12);
    // Convention: the gains are the light's colour. Warm 3000 K: red > 1 > blue; cool 10000 K: the other way.
    const glm::dvec3 warm = gusuku::whiteBalanceGainsFromColourTemperature(3000.0);
    EXPECT_GT(warm.r, 1.0);
    EXPECT_LT(warm.b, 1.0);
    EXPECT_GT(warm.r, warm.g);
    EXPECT_GT(warm.g, warm.b);
    const glm::dvec3 cool = gusuku::whiteBalanceGainsFromColourTemperature(10000.0);
    EXPECT_LT(cool.r, 1.0);
    EXPECT_GT(cool.b, 1.0);
    // A tint, not a brightness: luminance 1 at every temperature.
    for (double kelvin : {2000.0, 3000.0, 4500.0, 6500.0, 10000.0, 25000.0})
        EXPECT_NEAR(gusuku::luminanceRec709(gusuku::whiteBalanceGainsFromColourTemperature(kelvin)), 1.0, 1e-12);
    // Redder as the light gets warmer, all the way down.
    double previous_ratio = 0.0;
    for (double kelvin = 25000.0; kelvin >= 2000.0; kelvin -= 500.0) {
        const glm::dvec3 gains = gusuku::whiteBalanceGainsFromColourTemperature(kelvin);
        EXPECT_GT(gains.b, 0.0) << kelvin;
        EXPECT_GT(gains.r / gains.b, previous_ratio) << kelvin;
        previous_ratio = gains.r / gains.b;
    }
}

TEST(Exposure, BadValuesAreInputErrorsNamingTheArgument) {
    struct Case {
        std::string expected;
        std::string message;
    };
    const Case cases[] = {
        {"pixel_intensity: must be finite and > 0, got nan",
         inputErrorOf([] { gusuku::exposureFromArcorePixelIntensity(kNaN, 0.05); })},
        {"pixel_intensity: must be finite and > 0, got 0",
         inputErrorOf([] { gusuku::exposureFromArcorePixelIntensity(0.0, 0.05); })},
        {"pixel_intensity: must be finite and > 0, got -0.2",
         inputErrorOf([] { gusuku::exposureFromArcorePixelIntensity(-0.2, 0.05); })},
        {"pixel_intensity: must be in (0, 1], got 1.5",
         inputErrorOf([] { gusuku::exposureFromArcorePixelIntensity(1.5, 0.05); })},
        {"reference_luminance: must be finite and > 0, got 0",
         inputErrorOf([] { gusuku::exposureFromArcorePixelIntensity(0.5, 0.0); })},
        {"ambient_intensity_lumens: must be finite and > 0, got nan",
         inputErrorOf([] { gusuku::exposureFromArkitAmbientIntensity(kNaN, 0.05); })},
        {"ambient_intensity_lumens: must be finite and > 0, got 0",
         inputErrorOf([] { gusuku::exposureFromArkitAmbientIntensity(0.0, 0.05); })},
        {"ambient_intensity_lumens: must be finite and > 0, got -1000",
         inputErrorOf([] { gusuku::exposureFromArkitAmbientIntensity(-1000.0, 0.05); })},
        {"reference_luminance: must be finite and > 0, got inf",
         inputErrorOf([] { gusuku::neutralExposure(std::numeric_limits<double>::infinity()); })},
        {"temperature_kelvin: must be in [2000, 25000] K",
         inputErrorOf([] { gusuku::whiteBalanceGainsFromColourTemperature(1000.0); })},
        {"temperature_kelvin: must be in [2000, 25000] K",
         inputErrorOf([] { gusuku::whiteBalanceGainsFromColourTemperature(kNaN); })},
        {"temperature_kelvin: must be in [1667, 25000] K",
         inputErrorOf([] { gusuku::planckianChromaticity(30000.0); })},
        {"color_correction_rgb[2]: must be finite and > 0, got 0",
         inputErrorOf([] { gusuku::whiteBalanceGainsFromArcoreColorCorrection({1.0, 1.0, 0.0}); })},
        {"exposure: must be finite and > 0, got -1", inputErrorOf([] { gusuku::ev100FromExposure(-1.0, 179.0); })},
        {"f_number: must be finite and > 0, got 0", inputErrorOf([] { gusuku::ev100FromCamera(0.0, 0.01, 100.0); })},
        {"ev100: must be finite, got nan", inputErrorOf([] { gusuku::exposureFromEv100(kNaN, 179.0); })},
    };
    for (const Case& c : cases) EXPECT_NE(c.message.find(c.expected), std::string::npos) << c.message;
    // One line, starting with the function.
    const std::string message = inputErrorOf([] { gusuku::exposureFromArkitAmbientIntensity(0.0, 0.05); });
    EXPECT_EQ(message.rfind("exposureFromArkitAmbientIntensity: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
}

}  // namespace
