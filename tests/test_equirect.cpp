// Pins the equirectangular sky-map convention (docs/design.md 2, gusuku/maths/equirect.h): row 0 is the zenith,
// u = north_azimuth / 360 faces north, azimuth east of north grows with u, and texel solid angles sum to 4 pi.
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "gusuku/maths/equirect.h"

namespace {


void expectDirectionNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-12) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(Equirect, NorthColumnAtTheHorizonFacesNorth) {
    for (const double north : {0.0, 90.0, 180.0, 271.5}) {
        SCOPED_TRACE(north);
        expectDirectionNear(gusuku::equirectDirection(north / 360.0, 0.5, north), {0.0, 1.0, 0.0});
    }
}

TEST(Equirect, AzimuthGrowsEastOfNorthWithU) {
    const double north = 180.0;
    // A quarter turn to the right of north is east, half a turn is south, three quarters west.
    expectDirectionNear(gusuku::equirectDirection((north + 90.0) / 360.0, 0.5, north), {1.0, 0.0, 0.0});
    expectDirectionNear(gusuku::equirectDirection(0.0, 0.5, north), {0.0, -1.0, 0.0});
    expectDirectionNear(gusuku::equirectDirection((north - 90.0) / 360.0, 0.5, north), {-1.0, 0.0, 0.0});
}

TEST(Equirect, MatchesTheSunVectorConvention) {
    // docs/design.md 2: towards azimuth A (east of north) at elevation e is (cos e sin A, cos e cos A, sin e).
    const double north = 37.0, azimuth_deg = 123.0, elevation_deg = 28.0;
    const double a = azimuth_deg * std::numbers::pi / 180.0, e = elevation_deg * std::numbers::pi / 180.0;
    const glm::dvec3 expected{std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e)};
    expectDirectionNear(
        gusuku::equirectDirection((azimuth_deg + north) / 360.0, 0.5 - elevation_deg / 180.0, north), expected);
}

TEST(Equirect, RowZeroIsTheZenithAndTheLastRowTheNadir) {
    for (const double u : {0.0, 0.3, 0.77}) {
        expectDirectionNear(gusuku::equirectDirection(u, 0.0, 0.0), {0.0, 0.0, 1.0});
        expectDirectionNear(gusuku::equirectDirection(u, 1.0, 0.0), {0.0, 0.0, -1.0});
    }
    // The centre of row 0 of a 1024 x 512 map is half a row (90 / 512 deg) below the zenith.
    const int height = 512;
    const glm::dvec3 row0 = gusuku::equirectDirection(0.25, 0.5 / height, 0.0);
    EXPECT_NEAR(std::asin(row0.z) * 180.0 / std::numbers::pi, 90.0 - 90.0 / height, 1e-9);
}

TEST(Equirect, CoordinatesAndDirectionsRoundTrip) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
        const double north = 360.0 * unit(random);
        // Direction -> coordinates -> direction.
        const double z = 2.0 * unit(random) - 1.0, phi = 2.0 * std::numbers::pi * unit(random);
        const double r = std::sqrt(1.0 - z * z);
        const glm::dvec3 direction{r * std::cos(phi), r * std::sin(phi), z};
        const glm::dvec2 uv = gusuku::equirectCoordinates(direction, north);
        EXPECT_GE(uv.x, 0.0);
        EXPECT_LT(uv.x, 1.0);
        expectDirectionNear(gusuku::equirectDirection(uv.x, uv.y, north), direction, 1e-9);
        // Coordinates -> direction -> coordinates (away from the poles, where u is undefined).
        const double u = unit(random), v = 0.01 + 0.98 * unit(random);
        const glm::dvec2 back = gusuku::equirectCoordinates(gusuku::equirectDirection(u, v, north), north);
        EXPECT_NEAR(std::remainder(back.x - u, 1.0), 0.0, 1e-9);
        EXPECT_NEAR(back.y, v, 1e-9);
    }
}

TEST(Equirect, TexelSolidAnglesSumToTheSphere) {
    // Midpoint sum of sin over h rows: sum_y sin((y + 1/2) d) = 1 / sin(d / 2) with d = pi / h, so the map
    // totals 2 pi d / sin(d / 2), which tends to 4 pi (exact closed form for a coarse map, near 4 pi for 512).
    for (const int height : {8, 512}) {
        const int width = 2 * height;
        double total = 0.0;
        for (int y = 0; y < height; ++y) total += width * gusuku::equirectTexelSolidAngle(y, width, height);
        const double d = std::numbers::pi / height;
        EXPECT_NEAR(total, 2.0 * std::numbers::pi * d / std::sin(d / 2.0), 1e-9);
        if (height == 512) {
            EXPECT_NEAR(total, 4.0 * std::numbers::pi, 4.0 * std::numbers::pi * 1e-5);
        }
    }
    // Rows near the horizon hold the most solid angle, rows at the poles the least; north-south symmetric.
    EXPECT_GT(gusuku::equirectTexelSolidAngle(255, 1024, 512), gusuku::equirectTexelSolidAngle(0, 1024, 512));
    EXPECT_NEAR(gusuku::equirectTexelSolidAngle(10, 1024, 512), gusuku::equirectTexelSolidAngle(501, 1024, 512),
                1e-15);
}

}  // namespace
