// Sky light: sun disc extraction on synthetic skies with known suns, sky importance sampling against direct
// quadrature, and the GLSL twin against the CPU. (The clear-sky sun model: test_sun_irradiance.cpp.)

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "sky_probe.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/sky_light.h"

namespace {

using gusuku::ImageRGBA;
using namespace gusuku::bake;

using std::numbers::pi;
constexpr double kDeg = pi / 180.0;

glm::dvec3 enuFromElevationAzimuth(double elevation_deg, double azimuth_deg) {
    const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
    return {std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
}

double angleBetweenDeg(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) / kDeg;
}

ImageRGBA uniformMap(int width, int height, float value) {
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, value);
    for (size_t i = 3; i < image.texels.size(); i += 4) image.texels[i] = 1.0f;
    return image;
}

/// Uniform sky of radiance sky_radiance plus a disc of angular radius disc_radius_deg and radiance disc_radiance
/// at sun_direction, each texel holding the solid-angle-weighted average over 24 x 24 sub-samples (the disc's
/// sub-texel coverage), then capped at `cap`.
ImageRGBA renderSunSky(int width, int height, double north_deg, const glm::dvec3& sun_direction,
                       const glm::dvec3& disc_radiance, double sky_radiance, double disc_radius_deg,
                       double cap = std::numeric_limits<double>::infinity()) {
    ImageRGBA image = uniformMap(width, height, float(sky_radiance));
    const double cos_radius = std::cos(disc_radius_deg * kDeg);
    const double cos_near = std::cos(disc_radius_deg * kDeg + 3.0 * pi / height);  // texels that may touch it
    constexpr int kSub = 24;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 centre = gusuku::equirectDirection((x + 0.5) / width, (y + 0.5) / height, north_deg);
            if (glm::dot(centre, sun_direction) < cos_near && y > 2 && y < height - 3) continue;
            double covered = 0.0, total = 0.0;
            for (int j = 0; j < kSub; ++j)
                for (int i = 0; i < kSub; ++i) {
                    const double u = (x + (i + 0.5) / kSub) / width, v = (y + (j + 0.5) / kSub) / height;
                    const double weight = std::sin(v * pi);  // solid angle of the sub-sample
                    total += weight;
                    if (glm::dot(gusuku::equirectDirection(u, v, north_deg), sun_direction) >= cos_radius)
                        covered += weight;
                }
            const double coverage = covered / total;
            if (coverage <= 0.0) continue;
            float* t = image.texel(x, y);
            for (int c = 0; c < 3; ++c)
                t[c] = float(std::min(cap, sky_radiance + coverage * (disc_radiance[c] - sky_radiance)));
        }
    return image;
}

double discSolidAngle(double radius_deg) { return 2.0 * pi * (1.0 - std::cos(radius_deg * kDeg)); }

// ---------------------------------------------------------------------------------------------------------
// Sun disc extraction
// ---------------------------------------------------------------------------------------------------------

struct SunCase {
    double elevation_deg;
    double azimuth_deg;
};

class SunDiscTest : public ::testing::TestWithParam<SunCase> {};

TEST_P(SunDiscTest, FindsDirectionIrradianceAndLeavesOnlySky) {
    const double north_deg = 90.0;  // azimuth 270 lands on the image's left/right seam
    const glm::dvec3 sun = enuFromElevationAzimuth(GetParam().elevation_deg, GetParam().azimuth_deg);
    const glm::dvec3 disc_radiance = 1.0e5 * glm::dvec3(1.0, 0.9, 0.8);  // a real sun is ~1e5x its sky
    ImageRGBA sky = renderSunSky(1024, 512, north_deg, sun, disc_radiance, 1.0, kSunDiscAngularRadiusDeg);

    const SunDiscEstimate estimate = extractSunDisc(sky, north_deg);
    ASSERT_TRUE(estimate.found);
    EXPECT_FALSE(estimate.clipped);
    EXPECT_LT(angleBetweenDeg(estimate.direction_enu, sun), 0.3);
    const double solid_angle = discSolidAngle(kSunDiscAngularRadiusDeg);
    for (int c = 0; c < 3; ++c) {
        const double expected = (disc_radiance[c] - 1.0) * solid_angle;  // the disc's excess over the sky
        EXPECT_NEAR(estimate.irradiance_rgb[c], expected, 0.03 * expected) << "channel " << c;
    }
    EXPECT_GT(estimate.texel_count, 0);
    float max_channel = 0.0f;
    for (size_t i = 0; i < sky.texels.size(); ++i)
        if (i % 4 != 3) max_channel = std::max(max_channel, sky.texels[i]);
    EXPECT_NEAR(max_channel, 1.0f, 0.01f);
}

INSTANTIATE_TEST_SUITE_P(Suns, SunDiscTest,
                         ::testing::Values(SunCase{35.0, 140.0}, SunCase{20.0, 270.0}, SunCase{75.0, 10.0},
                                           SunCase{3.0, 95.0}));

TEST(SunDisc, OvercastSkyIsNotASunAndStaysUnchanged) {
    // CIE-like overcast: L = (1 + 2 cos theta) / 3 above the horizon, a flat ground below.
    ImageRGBA sky = uniformMap(1024, 512, 0.0f);
    for (int y = 0; y < sky.height; ++y) {
        const double cos_theta = std::cos((y + 0.5) / sky.height * pi);
        const float radiance = float((1.0 + 2.0 * std::max(0.0, cos_theta)) / 3.0);
        for (int x = 0; x < sky.width; ++x) std::fill(sky.texel(x, y), sky.texel(x, y) + 3, radiance);
    }
    const std::vector<float> before = sky.texels;
    const SunDiscEstimate estimate = extractSunDisc(sky, 0.0);
    EXPECT_FALSE(estimate.found);
    EXPECT_EQ(estimate.texel_count, 0);
    EXPECT_TRUE(sky.texels == before);
}

TEST(SunDisc, BlackMapIsNotASun) {
    ImageRGBA sky = uniformMap(64, 32, 0.0f);
    EXPECT_FALSE(extractSunDisc(sky, 0.0).found);
}

TEST(SunDisc, CappedDiscIsFoundAndMarkedClipped) {
    const glm::dvec3 sun = enuFromElevationAzimuth(40.0, 200.0);
    ImageRGBA sky = renderSunSky(1024, 512, 30.0, sun, glm::dvec3(1.0e5), 1.0, kSunDiscAngularRadiusDeg, 5.0);
    const SunDiscEstimate estimate = extractSunDisc(sky, 30.0);
    ASSERT_TRUE(estimate.found);
    EXPECT_TRUE(estimate.clipped);
    EXPECT_LT(angleBetweenDeg(estimate.direction_enu, sun), 0.5);
    float max_channel = 0.0f;
    for (size_t i = 0; i < sky.texels.size(); ++i)
        if (i % 4 != 3) max_channel = std::max(max_channel, sky.texels[i]);
    EXPECT_NEAR(max_channel, 1.0f, 0.01f);
}

TEST(SunDisc, DiscFarTooFaintForARealSunIsMarkedClipped) {
    // 300x its sky: far above the sky (found), but its irradiance (299 * 6.8e-5 = 0.02) is under 1% of
    // pi * sky radiance (0.031): no real sun is that faint against its sky.
    const glm::dvec3 sun = enuFromElevationAzimuth(50.0, 60.0);
    ImageRGBA sky = renderSunSky(1024, 512, 0.0, sun, glm::dvec3(300.0), 1.0, kSunDiscAngularRadiusDeg);
    const SunDiscEstimate estimate = extractSunDisc(sky, 0.0);
    ASSERT_TRUE(estimate.found);
    EXPECT_TRUE(estimate.clipped);
}

/// Share of a map's light (luminance integrated over the sphere) that extractSunDisc took out as the disc.
double sunShareOfLight(const SunDiscEstimate& disc, const ImageRGBA& sky_without_sun) {
    const double disc_light = gusuku::luminanceRec709(disc.irradiance_rgb);  // cos ~ 1 over the disc
    const double sky_light = buildSkySamplingTables(sky_without_sun, 0.0).table[3];
    return disc_light / (disc_light + sky_light);
}

TEST(SunDisc, RealPhotosMatchTheirDocumentedSuns) {
    GUSUKU_REQUIRE_SHARED_DATA();
    // ../shared/data/env/SOURCE.md: sun at about 35 deg holding about 25 % of the light; low sun at about
    // 10 deg holding about 68 %; an overcast map with no direct sun. North's column is irrelevant here.
    const std::string env = gusuku::testing::sharedDataDir() + "/env/";
    struct Expectation {
        const char* file;
        double elevation_deg;
        double sun_share;
    };
    for (const Expectation& e : {Expectation{"immenstadter_horn_1k.hdr", 35.0, 0.25},
                                 Expectation{"rooitou_park_1k.hdr", 10.0, 0.68}}) {
        SCOPED_TRACE(e.file);
        ImageRGBA sky = gusuku::readRadianceMap(env + e.file);
        const SunDiscEstimate disc = extractSunDisc(sky, 0.0);
        ASSERT_TRUE(disc.found);
        EXPECT_FALSE(disc.clipped);
        EXPECT_NEAR(std::asin(disc.direction_enu.z) / kDeg, e.elevation_deg, 2.0);
        EXPECT_NEAR(sunShareOfLight(disc, sky), e.sun_share, 0.05);
        EXPECT_LT(disc.angular_radius_deg, 5.0);
    }
    ImageRGBA overcast = gusuku::readRadianceMap(env + "potsdamer_platz_1k.hdr");
    const std::vector<float> before = overcast.texels;
    EXPECT_FALSE(extractSunDisc(overcast, 0.0).found);
    EXPECT_TRUE(overcast.texels == before);
}

TEST(SunDisc, BadMapsAreInputErrors) {
    ImageRGBA empty;
    EXPECT_THROW(extractSunDisc(empty, 0.0), gusuku::InputError);
    ImageRGBA wrong = uniformMap(8, 4, 1.0f);
    wrong.texels.pop_back();
    EXPECT_THROW(extractSunDisc(wrong, 0.0), gusuku::InputError);
}

// ---------------------------------------------------------------------------------------------------------
// Sky importance sampling (CPU)
// ---------------------------------------------------------------------------------------------------------

/// A sky with a gradient, a coloured bright patch and a dark ground.
ImageRGBA patchSky(int width, int height) {
    ImageRGBA sky = uniformMap(width, height, 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* t = sky.texel(x, y);
            const double v = (y + 0.5) / height;
            const double base = v < 0.5 ? 0.5 + 0.5 * (0.5 - v) : 0.1;
            t[0] = float(base * 0.8);
            t[1] = float(base * 0.9);
            t[2] = float(base * 1.2);
            if (x >= width / 5 && x < width / 5 + 8 && y >= height / 4 && y < height / 4 + 5) {
                t[0] = 400.0f;  // bright, warm: radiance / luminance differs from the rest of the sky
                t[1] = 300.0f;
                t[2] = 150.0f;
            }
        }
    return sky;
}

TEST(SkySampling, PdfIntegratesToOneOverTheSphere) {
    const SkySamplingTables tables = buildSkySamplingTables(patchSky(256, 128), 45.0);
    double integral = 0.0;
    for (int y = 0; y < tables.height; ++y)
        for (int x = 0; x < tables.width; ++x) {
            const glm::dvec3 d = gusuku::equirectDirection((x + 0.5) / tables.width, (y + 0.5) / tables.height, 45.0);
            integral += skyPdfCpu(tables, d) * gusuku::equirectTexelSolidAngle(y, tables.width, tables.height);
        }
    EXPECT_NEAR(integral, 1.0, 1e-4);
}

TEST(SkySampling, MonteCarloIrradianceMatchesQuadrature) {
    const ImageRGBA sky = patchSky(256, 128);
    const double north_deg = 45.0;
    const SkySamplingTables tables = buildSkySamplingTables(sky, north_deg);
    // Irradiance on a horizontal plane by quadrature over texels.
    glm::dvec3 quadrature(0.0);
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const glm::dvec3 d = gusuku::equirectDirection((x + 0.5) / sky.width, (y + 0.5) / sky.height, north_deg);
            const float* t = sky.texel(x, y);
            quadrature += glm::dvec3(t[0], t[1], t[2]) * std::max(0.0, d.z) *
                          gusuku::equirectTexelSolidAngle(y, sky.width, sky.height);
        }
    // The same by importance sampling: stratified jittered xi, fixed seed.
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    constexpr int kStrata = 400;
    glm::dvec3 estimate(0.0);
    for (int j = 0; j < kStrata; ++j)
        for (int i = 0; i < kStrata; ++i) {
            const float xi1 = (float(i) + jitter(rng)) / kStrata, xi2 = (float(j) + jitter(rng)) / kStrata;
            const SkySample s = sampleSkyCpu(tables, xi1, xi2);
            ASSERT_TRUE(std::isfinite(s.pdf_solid_angle));
            ASSERT_GT(s.pdf_solid_angle, 0.0);
            estimate += skyRadianceCpu(tables, s.direction_enu) * std::max(0.0, s.direction_enu.z) / s.pdf_solid_angle;
        }
    estimate /= double(kStrata) * kStrata;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c], quadrature[c], 0.01 * quadrature[c]) << "channel " << c;
}

TEST(SkySampling, SampledPdfAgreesWithPdfLookupAndTexelConvention) {
    const SkySamplingTables tables = buildSkySamplingTables(patchSky(64, 32), 120.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < 2000; ++k) {
        const SkySample s = sampleSkyCpu(tables, uniform(rng), uniform(rng));
        EXPECT_NEAR(glm::length(s.direction_enu), 1.0, 1e-12);
        EXPECT_NEAR(skyPdfCpu(tables, s.direction_enu), s.pdf_solid_angle, 1e-6 * s.pdf_solid_angle);
    }
    // skyRadianceCpu reads the texel whose centre direction it is given (equirect.h's convention).
    for (int y = 0; y < tables.height; y += 5)
        for (int x = 0; x < tables.width; x += 7) {
            const glm::dvec3 d = gusuku::equirectDirection((x + 0.5) / tables.width, (y + 0.5) / tables.height, 120.0);
            const float* expected = tables.radiance_rgba.data() + (size_t(y) * tables.width + x) * 4;
            EXPECT_EQ(skyRadianceCpu(tables, d), glm::dvec3(expected[0], expected[1], expected[2]));
        }
}

/// The row a direction lies in, as the lookups find it (theta = atan2(|xy|, z), row = int(theta / pi * height)).
int rowOfDirection(const SkySamplingTables& tables, const glm::dvec3& d) {
    const double theta = std::atan2(std::hypot(d.x, d.y), d.z);
    return std::clamp(int(theta / pi * tables.height), 0, tables.height - 1);
}

// The rows a surface's next-event draw is confined to (skyRowsFacingCpu) hold every direction above its plane,
// and drop the other half of the sphere's rows for a level surface: the ground's for a floor, the sky's for a
// ceiling.
TEST(SkySampling, RowsFacingANormalHoldEveryDirectionAboveItsPlane) {
    const SkySamplingTables tables = buildSkySamplingTables(patchSky(256, 128), 45.0);
    std::mt19937 rng(21);
    std::normal_distribution<double> gaussian(0.0, 1.0);
    std::vector<glm::dvec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0},
                                       glm::normalize(glm::dvec3(1, 2, 1e-9))};
    for (int k = 0; k < 200; ++k)
        normals.push_back(glm::normalize(glm::dvec3(gaussian(rng), gaussian(rng), gaussian(rng))));
    for (const glm::dvec3& normal : normals) {
        const SkyRows rows = skyRowsFacingCpu(tables, normal);
        SCOPED_TRACE(::testing::Message() << "normal (" << normal.x << ", " << normal.y << ", " << normal.z << ")");
        ASSERT_LE(rows.first, rows.last);
        for (int k = 0; k < 500; ++k) {
            glm::dvec3 d = glm::normalize(glm::dvec3(gaussian(rng), gaussian(rng), gaussian(rng)));
            if (glm::dot(d, normal) < 0.0) d = -d;
            if (k == 0) d = glm::normalize(glm::cross(normal, glm::dvec3(0.3, 0.5, 0.8)) + 1e-9 * normal);  // grazing
            const int row = rowOfDirection(tables, d);
            EXPECT_GE(row, rows.first);
            EXPECT_LE(row, rows.last);
        }
    }
    EXPECT_EQ(skyRowsFacingCpu(tables, {0, 0, 1}).first, 0);
    EXPECT_EQ(skyRowsFacingCpu(tables, {0, 0, 1}).last, 65);  // the row below the horizon, and one more
    EXPECT_EQ(skyRowsFacingCpu(tables, {0, 0, -1}).first, 63);
    EXPECT_EQ(skyRowsFacingCpu(tables, {0, 0, -1}).last, 127);
}

// The draw conditioned on those rows is the map's density renormalised over them: every sample inside, its pdf
// the whole map's over the rows' probability, and an unbiased irradiance on each plane (against quadrature).
TEST(SkySampling, RowConditionedSamplingIsTheMapRenormalisedOverTheRows) {
    const ImageRGBA sky = patchSky(256, 128);
    const double north_deg = 45.0;
    const SkySamplingTables tables = buildSkySamplingTables(sky, north_deg);
    const glm::dvec3 normals[] = {{0, 0, 1}, {0, 0, -1}, glm::normalize(glm::dvec3(0.3, -0.5, 0.8)), {0, 1, 0}};
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    for (const glm::dvec3& normal : normals) {
        SCOPED_TRACE(::testing::Message() << "normal (" << normal.x << ", " << normal.y << ", " << normal.z << ")");
        const SkyRows rows = skyRowsFacingCpu(tables, normal);
        const float probability = skyRowsProbabilityCpu(tables, rows);
        ASSERT_GT(probability, 0.0f);
        glm::dvec3 quadrature(0.0);
        for (int y = 0; y < sky.height; ++y)
            for (int x = 0; x < sky.width; ++x) {
                const glm::dvec3 d =
                    gusuku::equirectDirection((x + 0.5) / sky.width, (y + 0.5) / sky.height, north_deg);
                const float* t = sky.texel(x, y);
                quadrature += glm::dvec3(t[0], t[1], t[2]) * std::max(0.0, glm::dot(normal, d)) *
                              gusuku::equirectTexelSolidAngle(y, sky.width, sky.height);
            }
        constexpr int kStrata = 300;
        glm::dvec3 estimate(0.0);
        for (int j = 0; j < kStrata; ++j)
            for (int i = 0; i < kStrata; ++i) {
                const float xi1 = (float(i) + jitter(rng)) / kStrata, xi2 = (float(j) + jitter(rng)) / kStrata;
                const SkySample s = sampleSkyInRowsCpu(tables, rows, xi1, xi2);
                ASSERT_GT(s.pdf_solid_angle, 0.0);
                const int row = rowOfDirection(tables, s.direction_enu);
                ASSERT_GE(row, rows.first);
                ASSERT_LE(row, rows.last);
                if ((i + j) % 97 == 0)
                    EXPECT_NEAR(s.pdf_solid_angle, skyPdfCpu(tables, s.direction_enu) / probability,
                                1e-6 * s.pdf_solid_angle);
                estimate += skyRadianceCpu(tables, s.direction_enu) *
                            std::max(0.0, glm::dot(normal, s.direction_enu)) / s.pdf_solid_angle;
            }
        estimate /= double(kStrata) * kStrata;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c], quadrature[c], 0.01 * quadrature[c]) << "channel " << c;
    }
    // Rows that hold no light, or none at all: no draw (pdf 0), never a NaN.
    ImageRGBA dark_top = patchSky(64, 32);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 64; ++x) std::fill(dark_top.texel(x, y), dark_top.texel(x, y) + 3, 0.0f);
    const SkySamplingTables dark_tables = buildSkySamplingTables(dark_top, 0.0);
    EXPECT_EQ(skyRowsProbabilityCpu(dark_tables, {0, 9}), 0.0f);
    EXPECT_EQ(sampleSkyInRowsCpu(dark_tables, {0, 9}, 0.5f, 0.5f).pdf_solid_angle, 0.0);
    EXPECT_EQ(sampleSkyInRowsCpu(dark_tables, {5, 4}, 0.5f, 0.5f).pdf_solid_angle, 0.0);
    // xi at the top end stays in the last row with light, not the dark row after it.
    const SkySample top = sampleSkyInRowsCpu(dark_tables, {10, 12}, 1.0f, 0.5f);
    EXPECT_EQ(rowOfDirection(dark_tables, top.direction_enu), 12);
}

// The guide tables (sky_light.h) narrow each CDF search without changing its answer: on a map of dark runs and
// one bright texel (long stretches of nearly equal CDF entries, then one jump), every guide entry is the largest
// interval whose CDF start is <= k / cells, and every sample lands in the texel a search of the whole CDF picks,
// at random xi and at xi exactly on each CDF entry and one float below it.
TEST(SkySampling, GuidedSearchFindsTheWholeSearchsInterval) {
    constexpr int kWidth = 48, kHeight = 20;  // not powers of two: the guides have spare cells
    ImageRGBA sky = patchSky(kWidth, kHeight);
    for (int x = 5; x < 40; ++x) std::fill(sky.texel(x, 3), sky.texel(x, 3) + 3, 0.0f);  // a dark run
    std::fill(sky.texel(17, 6), sky.texel(17, 6) + 3, 5e4f);                              // one bright texel
    const SkySamplingTables tables = buildSkySamplingTables(sky, 30.0);
    const int row_cells = skyGuideCells(kHeight), column_cells = skyGuideCells(kWidth);
    ASSERT_EQ(row_cells, 32);
    ASSERT_EQ(column_cells, 64);
    const float* marginal = tables.table.data() + kSkyTableHeaderFloats;
    auto conditional = [&](int y) { return marginal + (kHeight + 1) + size_t(y) * (kWidth + 1); };
    const float* marginal_guide = conditional(kHeight);
    auto conditional_guide = [&](int y) { return marginal_guide + (row_cells + 1) + size_t(y) * (column_cells + 1); };
    // The whole search: the largest i in [0, n-1] with cdf[i] <= xi.
    auto wholeSearch = [](const float* cdf, int n, float xi) {
        int found = 0;
        for (int i = 0; i < n; ++i)
            if (cdf[i] <= xi) found = i;
        return found;
    };
    for (int k = 0; k <= row_cells; ++k)
        EXPECT_EQ(marginal_guide[k], float(wholeSearch(marginal, kHeight, float(k) / float(row_cells)))) << k;
    for (int y = 0; y < kHeight; ++y)
        for (int k = 0; k <= column_cells; ++k)
            EXPECT_EQ(conditional_guide(y)[k], float(wholeSearch(conditional(y), kWidth, float(k) / column_cells)));

    std::vector<float> xis;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (int k = 0; k < 4000; ++k) xis.push_back(uniform(rng));
    for (int y = 0; y <= kHeight; ++y) {
        xis.push_back(marginal[y]);
        xis.push_back(std::nextafter(marginal[y], 0.0f));
    }
    for (size_t a = 0; a < xis.size(); ++a) {
        const float xi1 = std::min(xis[a], 0x1.fffffep-1f);
        const int y = wholeSearch(marginal, kHeight, xi1);
        // Second coordinate: random, and every entry of the chosen row's CDF.
        std::vector<float> xi2s = {uniform(rng)};
        for (int x = 0; x <= kWidth; x += 3) xi2s.push_back(std::min(conditional(y)[x], 0x1.fffffep-1f));
        for (float xi2 : xi2s) {
            const int x = wholeSearch(conditional(y), kWidth, xi2);
            const glm::dvec2 uv = gusuku::equirectCoordinates(sampleSkyCpu(tables, xi1, xi2).direction_enu, 30.0);
            SCOPED_TRACE(::testing::Message() << "xi (" << xi1 << ", " << xi2 << ") texel " << x << ", " << y);
            EXPECT_GE(uv.y * kHeight, y - 1e-6);
            EXPECT_LE(uv.y * kHeight, y + 1 + 1e-6);
            // The column, unless the sample sits at a pole, where the azimuth means nothing.
            if (uv.y > 1e-6 && uv.y < 1.0 - 1e-6) {
                const double column = uv.x * kWidth;
                const double distance = std::min(std::abs(column - (x + 0.5)), kWidth - std::abs(column - (x + 0.5)));
                EXPECT_LE(distance, 0.5 + 1e-4);
            }
        }
    }
}

TEST(SkySampling, BlackMapFallsBackToUniformAndDarkRowsAreNeverChosen) {
    const SkySamplingTables black = buildSkySamplingTables(uniformMap(64, 32, 0.0f), 0.0);
    EXPECT_EQ(black.table[3], 0.0f);
    for (float xi : {0.0f, 0.3f, 0.999f, 1.0f}) {
        const SkySample s = sampleSkyCpu(black, xi, 0.5f);
        EXPECT_TRUE(std::isfinite(s.pdf_solid_angle));
        EXPECT_GT(s.pdf_solid_angle, 0.0);
    }
    for (int y = 0; y < 32; y += 3) {  // uniform over the sphere (at texel centres, where sin theta is exact)
        const glm::dvec3 d = gusuku::equirectDirection(0.3, (y + 0.5) / 32.0, 0.0);
        EXPECT_NEAR(skyPdfCpu(black, d), 1.0 / (4.0 * pi), 1e-3 / (4.0 * pi));
    }
    // Upper half black: every sample goes below the horizon, the pdf up there is 0 (never NaN).
    ImageRGBA ground_only = uniformMap(64, 32, 0.0f);
    for (int y = 16; y < 32; ++y)
        for (int x = 0; x < 64; ++x) std::fill(ground_only.texel(x, y), ground_only.texel(x, y) + 3, 1.0f);
    const SkySamplingTables tables = buildSkySamplingTables(ground_only, 0.0);
    for (float xi : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) EXPECT_LE(sampleSkyCpu(tables, xi, xi).direction_enu.z, 0.0);
    EXPECT_EQ(skyPdfCpu(tables, {0.0, 0.0, 1.0}), 0.0);
    EXPECT_EQ(skyPdfCpu(tables, {0.3, 0.2, 0.5}), 0.0);
    // Table layout: header then CDFs ending exactly at 1.
    EXPECT_EQ(tables.table[0], 64.0f);
    EXPECT_EQ(tables.table[1], 32.0f);
    EXPECT_EQ(tables.table[kSkyTableHeaderFloats + 32], 1.0f);
    // then the guides: the marginal's (32 cells + 1) and each row's (64 cells + 1).
    EXPECT_EQ(tables.table.size(), kSkyTableHeaderFloats + 33 + 32 * 65 + 33 + 32 * 65);
    EXPECT_NEAR(tables.table[3], 2.0 * pi, 0.01);  // luminance 1 over the lower hemisphere
}

// ---------------------------------------------------------------------------------------------------------
// GLSL twin (shaders/include/sky_sampling.glsl through shaders/tests/sky_probe.comp)
// ---------------------------------------------------------------------------------------------------------

class SkySamplingGpu : public gusuku::testing::GpuTest {};

TEST_F(SkySamplingGpu, ProbeMatchesCpuTwins) {
    const double north_deg = 200.0;
    const SkySamplingTables tables = buildSkySamplingTables(patchSky(128, 64), north_deg);
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::normal_distribution<float> gaussian(0.0f, 1.0f);
    std::vector<glm::vec2> xi;
    std::vector<glm::vec3> directions;
    // Edge cases first: the poles, the seam, xi at the ends of [0, 1].
    xi.push_back({0.0f, 0.0f});
    directions.push_back({0.0f, 0.0f, 1.0f});
    xi.push_back({1.0f, 1.0f});
    directions.push_back({0.0f, 0.0f, -1.0f});
    xi.push_back({0.5f, 0.999999f});
    directions.push_back(glm::vec3(gusuku::equirectDirection(1e-4, 0.3, north_deg)));
    for (int k = 0; k < 1000; ++k) {
        xi.push_back({uniform(rng), uniform(rng)});
        glm::vec3 d(gaussian(rng), gaussian(rng), gaussian(rng));
        directions.push_back(glm::normalize(d));
    }
    const std::vector<SkyProbeResult> gpu = runSkyProbeGpu(context(), tables, xi, directions);
    ASSERT_EQ(gpu.size(), xi.size());
    for (size_t i = 0; i < xi.size(); ++i) {
        SCOPED_TRACE(::testing::Message() << "probe " << i << " xi (" << xi[i].x << ", " << xi[i].y << ")");
        const SkySample cpu = sampleSkyCpu(tables, xi[i].x, xi[i].y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(gpu[i].sampled_direction_enu[c], cpu.direction_enu[c], 1e-5);
        EXPECT_NEAR(gpu[i].sampled_pdf, cpu.pdf_solid_angle, 1e-4 * cpu.pdf_solid_angle);
        const glm::dvec3 direction(directions[i]);
        const glm::dvec3 radiance = skyRadianceCpu(tables, direction);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(gpu[i].radiance_at_direction[c], float(radiance[c]));
        const double pdf = skyPdfCpu(tables, direction);
        EXPECT_NEAR(gpu[i].pdf_at_direction, pdf, 1e-4 * pdf);
        const glm::dvec3 radiance_at_sample = skyRadianceCpu(tables, cpu.direction_enu);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(gpu[i].radiance_at_sample[c], float(radiance_at_sample[c]));
        EXPECT_NEAR(gpu[i].pdf_at_sample, skyPdfCpu(tables, cpu.direction_enu), 1e-4 * cpu.pdf_solid_angle);
        // The one-load lookup is the pair of lookups, bit for bit (the texel's density is stored as computed).
        EXPECT_EQ(gpu[i].combined_radiance, gpu[i].radiance_at_direction);
        EXPECT_EQ(gpu[i].combined_pdf, gpu[i].pdf_at_direction);
        // The direction as a normal: its rows (float acos on the GPU: a row's give at a band's edge), their
        // probability and the draw in them.
        const SkyRows rows = skyRowsFacingCpu(tables, direction);
        EXPECT_NEAR(gpu[i].rows.first, rows.first, 1);
        EXPECT_NEAR(gpu[i].rows.last, rows.last, 1);
        EXPECT_EQ(gpu[i].rows_probability, skyRowsProbabilityCpu(tables, gpu[i].rows));
        const SkySample in_rows = sampleSkyInRowsCpu(tables, gpu[i].rows, xi[i].x, xi[i].y);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(gpu[i].rows_sampled_direction_enu[c], in_rows.direction_enu[c], 1e-5);
        EXPECT_NEAR(gpu[i].rows_sampled_pdf, in_rows.pdf_solid_angle, 1e-4 * in_rows.pdf_solid_angle);
    }
}

}  // namespace
