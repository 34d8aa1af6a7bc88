// The analytic skies against their formulas: the CIE general sky (ISO 15469:2004 / CIE S 011/E:2003) and the
// CIE overcast sky, the sun disc's energy, and the images' integrals. The CIE formula is re-derived here from
// the published coefficients, independently of sky_model.cpp.
#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/assets/image.h"
#include "gusuku_bake/sky_model.h"
#include "gpu_test_support.h"

namespace {

using namespace gusuku;
using namespace gusuku::bake;

using std::numbers::pi;
constexpr int kWidth = 1024, kHeight = 512;

glm::dvec3 fromAzimuthElevation(double azimuth_deg, double elevation_deg) {
    const double a = azimuth_deg * pi / 180.0, e = elevation_deg * pi / 180.0;
    return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

double luminanceOf(const float* texel) { return luminanceRec709(glm::dvec3(texel[0], texel[1], texel[2])); }

// Darula and Kittler's standard clear sky, type 12: gradation group V (a = -1, b = -0.32), indicatrix group 4
// (c = 10, d = -3, e = 0.45). L / Lz = f(chi) phi(Z) / (f(Zs) phi(0)).
double referenceType12RelativeLuminance(const glm::dvec3& direction, const glm::dvec3& sun) {
    const double a = -1.0, b = -0.32, c = 10.0, d = -3.0, e = 0.45;
    auto phi = [&](double zenith) { return 1.0 + a * std::exp(b / std::cos(zenith)); };
    auto f = [&](double chi) {
        return 1.0 + c * (std::exp(d * chi) - std::exp(d * pi / 2.0)) + e * std::cos(chi) * std::cos(chi);
    };
    const double zenith = std::acos(direction.z), sun_zenith = std::acos(sun.z);
    const double chi = std::acos(std::fmin(1.0, std::fmax(-1.0, direction.x * sun.x + direction.y * sun.y +
                                                                    direction.z * sun.z)));
    return f(chi) * phi(zenith) / (f(sun_zenith) * phi(0.0));
}

TEST(SkyModel, PublishedCoefficientsForTheClearSkies) {
    const CieSkyCoefficients type12 = cieSkyCoefficients(12);
    EXPECT_DOUBLE_EQ(type12.a, -1.0);
    EXPECT_DOUBLE_EQ(type12.b, -0.32);
    EXPECT_DOUBLE_EQ(type12.c, 10.0);
    EXPECT_DOUBLE_EQ(type12.d, -3.0);
    EXPECT_DOUBLE_EQ(type12.e, 0.45);
    const CieSkyCoefficients type13 = cieSkyCoefficients(13);
    EXPECT_DOUBLE_EQ(type13.c, 16.0);
    EXPECT_DOUBLE_EQ(type13.e, 0.30);
    const CieSkyCoefficients type1 = cieSkyCoefficients(1);  // overcast alternative form: a = 4, b = -0.7
    EXPECT_DOUBLE_EQ(type1.a, 4.0);
    EXPECT_DOUBLE_EQ(type1.b, -0.7);
    EXPECT_THROW(cieSkyCoefficients(0), std::invalid_argument);
    EXPECT_THROW(cieSkyCoefficients(16), std::invalid_argument);
}

TEST(SkyModel, ClearSkyRelativeLuminanceMatchesTheCieFormula) {
    const glm::dvec3 sun = fromAzimuthElevation(135.0, 40.0);
    EXPECT_NEAR(cieRelativeLuminance({0.0, 0.0, 1.0}, sun, 12), 1.0, 1e-12);
    for (double azimuth = 0.0; azimuth < 360.0; azimuth += 37.0)
        for (double elevation = 2.0; elevation < 90.0; elevation += 11.0) {
            const glm::dvec3 direction = fromAzimuthElevation(azimuth, elevation);
            EXPECT_NEAR(cieRelativeLuminance(direction, sun, 12), referenceType12RelativeLuminance(direction, sun),
                        1e-12)
                << "azimuth " << azimuth << " elevation " << elevation;
        }
    // A clear sky is brightest around the sun and darkest about 90 deg from it, not at the horizon.
    const glm::dvec3 near_sun = fromAzimuthElevation(135.0, 43.0), away = fromAzimuthElevation(315.0, 40.0);
    EXPECT_GT(cieRelativeLuminance(near_sun, sun, 12), 3.0 * cieRelativeLuminance(away, sun, 12));
    EXPECT_EQ(cieRelativeLuminance(fromAzimuthElevation(10.0, -5.0), sun, 12), 0.0);
}

TEST(SkyModel, OvercastQuadratureMatchesClosedForm) {
    // Integral over the hemisphere of (1 + 2 cos Z) / 3 cos Z: 2 pi / 3 (1/2 + 2/3) = 7 pi / 9.
    EXPECT_NEAR(overcastDiffuseHorizontalPerZenith(), 7.0 * pi / 9.0, 1e-4);
    // A uniform sky (type 5: a = 0, c = 0) integrates to pi.
    EXPECT_NEAR(cieDiffuseHorizontalPerZenith(fromAzimuthElevation(0.0, 30.0), 5), pi, 1e-4);
}

class ClearSkyImage : public ::testing::TestWithParam<glm::dvec2> {};  // (sun azimuth, sun elevation) deg

TEST_P(ClearSkyImage, MatchesFormulaAndCarriesTheRequestedIrradiances) {
    ClearSkySpec spec;
    spec.sun_direction = fromAzimuthElevation(GetParam().x, GetParam().y);
    const double north = 180.0;
    const ImageRGBA image = renderClearSky(spec, kWidth, kHeight, north);
    const ClearSkyModel model(spec);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);

    const double cos_near_sun = std::cos(3.0 * pi / 180.0);
    double sky_horizontal_irradiance = 0.0, sun_normal_irradiance = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        const double solid_angle = equirectTexelSolidAngle(y, kWidth, kHeight);
        for (int x = 0; x < kWidth; ++x) {
            const float* texel = image.texel(x, y);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(texel[c])) << x << "," << y;
                ASSERT_GE(texel[c], 0.0f) << x << "," << y;
            }
            const glm::dvec3 direction = equirectDirection((x + 0.5) / kWidth, (y + 0.5) / kHeight, north);
            const double luminance = luminanceOf(texel);
            if (direction.z <= 0.0) {
                // The ground: albedo times global horizontal irradiance over pi.
                const double ghi = spec.diffuse_horizontal_irradiance *
                                   (1.0 + spec.direct_normal_to_diffuse_horizontal * spec.sun_direction.z);
                ASSERT_NEAR(luminance, spec.ground_albedo * ghi / pi, 1e-5);
                continue;
            }
            const double smooth =
                model.zenithLuminance() * referenceType12RelativeLuminance(direction, spec.sun_direction);
            const double sun_cosine = direction.x * spec.sun_direction.x + direction.y * spec.sun_direction.y +
                                      direction.z * spec.sun_direction.z;
            if (sun_cosine > cos_near_sun) {
                sun_normal_irradiance += (luminance - smooth) * solid_angle;
            } else {
                ASSERT_NEAR(luminance, smooth, 1e-5 * smooth + 1e-7) << x << "," << y;
            }
            sky_horizontal_irradiance += smooth * direction.z * solid_angle;
        }
    }
    const double dni = spec.diffuse_horizontal_irradiance * spec.direct_normal_to_diffuse_horizontal;
    EXPECT_NEAR(sun_normal_irradiance, dni, 0.02 * dni);
    EXPECT_NEAR(sky_horizontal_irradiance, spec.diffuse_horizontal_irradiance,
                0.01 * spec.diffuse_horizontal_irradiance);
    EXPECT_NEAR(sun_normal_irradiance / sky_horizontal_irradiance, 6.0, 0.12);

    // The brightest texel holds the sun's direction (within one texel).
    int brightest_x = 0, brightest_y = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (luminanceOf(image.texel(x, y)) > luminanceOf(image.texel(brightest_x, brightest_y))) {
                brightest_x = x;
                brightest_y = y;
            }
    const glm::dvec3 brightest =
        equirectDirection((brightest_x + 0.5) / kWidth, (brightest_y + 0.5) / kHeight, north);
    const double texel_angle = pi / kHeight;
    EXPECT_LT(std::acos(std::fmin(1.0, glm::dot(brightest, spec.sun_direction))), 1.5 * texel_angle);
}

INSTANTIATE_TEST_SUITE_P(SunPositions, ClearSkyImage,
                         ::testing::Values(glm::dvec2(135.0, 40.0), glm::dvec2(250.0, 8.0), glm::dvec2(100.0, 83.0)));

TEST(SkyModel, SunDiscSurvivesTheHdrFile) {
    ClearSkySpec spec;
    spec.sun_direction = fromAzimuthElevation(200.0, 55.0);
    const ImageRGBA image = renderClearSky(spec, kWidth, kHeight, 0.0);
    const std::string path = gusuku::testing::makeTemporaryDirectory("sky_model") + "/sky.hdr";
    writeHdr(path, image);
    const ImageRGBA read = readRadianceMap(path);
    ASSERT_EQ(read.width, kWidth);
    ASSERT_EQ(read.height, kHeight);
    const ClearSkyModel model(spec);
    const double cos_near_sun = std::cos(3.0 * pi / 180.0);
    double sun_normal_irradiance = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 direction = equirectDirection((x + 0.5) / kWidth, (y + 0.5) / kHeight, 0.0);
            if (glm::dot(direction, spec.sun_direction) <= cos_near_sun) continue;
            const double smooth =
                model.zenithLuminance() * referenceType12RelativeLuminance(direction, spec.sun_direction);
            sun_normal_irradiance +=
                (luminanceOf(read.texel(x, y)) - smooth) * equirectTexelSolidAngle(y, kWidth, kHeight);
        }
    EXPECT_NEAR(sun_normal_irradiance, model.directNormalIrradiance(), 0.02 * model.directNormalIrradiance());
}

TEST(SkyModel, OvercastZenithToHorizonRatioIsThree) {
    const OvercastSkySpec spec;
    // A tall map puts the last sky row within 0.006 deg of the horizon, where (1 + 2 cos Z) / 3 -> 1/3.
    const int tall_height = 16384;
    const ImageRGBA tall = renderOvercastSky(spec, 8, tall_height, 0.0);
    const double zenith = luminanceOf(tall.texel(3, 0)), horizon = luminanceOf(tall.texel(3, tall_height / 2 - 1));
    EXPECT_NEAR(zenith / horizon, 3.0, 1e-3);

    // The map used by the sample: every row follows the formula at its centre, grey, azimuth-independent.
    const ImageRGBA image = renderOvercastSky(spec, kWidth, kHeight, 0.0);
    const double zenith_luminance = spec.diffuse_horizontal_irradiance / (7.0 * pi / 9.0);
    double horizontal_irradiance = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        const double elevation = (0.5 - (y + 0.5) / kHeight) * pi;
        const double expected = elevation > 0.0 ? zenith_luminance * (1.0 + 2.0 * std::sin(elevation)) / 3.0
                                                : spec.ground_albedo * spec.diffuse_horizontal_irradiance / pi;
        for (int x = 0; x < kWidth; x += 97) {
            const float* texel = image.texel(x, y);
            ASSERT_TRUE(std::isfinite(texel[0]) && std::isfinite(texel[1]) && std::isfinite(texel[2]));
            ASSERT_GE(std::fmin(texel[0], std::fmin(texel[1], texel[2])), 0.0f);
            ASSERT_NEAR(luminanceOf(texel), expected, 1e-5 * expected) << "row " << y;
            if (elevation > 0.0) {
                ASSERT_FLOAT_EQ(texel[0], texel[1]);  // grey
                ASSERT_FLOAT_EQ(texel[1], texel[2]);
            }
        }
        if (elevation > 0.0)
            horizontal_irradiance += kWidth * luminanceOf(image.texel(0, y)) * std::sin(elevation) *
                                     equirectTexelSolidAngle(y, kWidth, kHeight);
    }
    EXPECT_NEAR(horizontal_irradiance, spec.diffuse_horizontal_irradiance, 0.005 * spec.diffuse_horizontal_irradiance);
}

}  // namespace
