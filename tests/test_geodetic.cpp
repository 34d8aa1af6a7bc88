// geodeticToEnu against an independent closed-form WGS84 geodetic -> ECEF -> ENU computation, and against
// textbook lengths of a degree.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gusuku/assets/geodetic.h"

namespace {

// WGS84 defining constants (NIMA TR8350.2): semi-major axis and flattening.
constexpr double kSemiMajorAxis_m = 6378137.0;
constexpr double kFlattening = 1.0 / 298.257223563;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

glm::dvec3 ecefFromGeodetic(const gusuku::GeodeticPoint& point) {
    const double e2 = kFlattening * (2.0 - kFlattening);
    const double phi = radians(point.latitude_deg);
    const double lambda = radians(point.longitude_deg);
    const double prime_vertical_radius = kSemiMajorAxis_m / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
    return {(prime_vertical_radius + point.height_m) * std::cos(phi) * std::cos(lambda),
            (prime_vertical_radius + point.height_m) * std::cos(phi) * std::sin(lambda),
            (prime_vertical_radius * (1.0 - e2) + point.height_m) * std::sin(phi)};
}

/// The textbook ECEF -> ENU rotation at the origin's latitude and longitude.
glm::dvec3 closedFormEnu(const gusuku::GeodeticPoint& origin, const gusuku::GeodeticPoint& point) {
    const glm::dvec3 d = ecefFromGeodetic(point) - ecefFromGeodetic(origin);
    const double phi = radians(origin.latitude_deg);
    const double lambda = radians(origin.longitude_deg);
    const double east = -std::sin(lambda) * d.x + std::cos(lambda) * d.y;
    const double north = -std::sin(phi) * std::cos(lambda) * d.x - std::sin(phi) * std::sin(lambda) * d.y +
                         std::cos(phi) * d.z;
    const double up = std::cos(phi) * std::cos(lambda) * d.x + std::cos(phi) * std::sin(lambda) * d.y +
                      std::sin(phi) * d.z;
    return {east, north, up};
}

TEST(Geodetic, OriginMapsToZero) {
    const gusuku::GeodeticPoint origin{26.2170, 127.7195, 120.0};
    const glm::dvec3 enu = gusuku::geodeticToEnu(origin, origin);
    EXPECT_NEAR(enu.x, 0.0, 1e-9);
    EXPECT_NEAR(enu.y, 0.0, 1e-9);
    EXPECT_NEAR(enu.z, 0.0, 1e-9);
}

TEST(Geodetic, PointStraightAboveIsUp) {
    const gusuku::GeodeticPoint origin{35.0, 135.0, 50.0};
    const glm::dvec3 enu = gusuku::geodeticToEnu(origin, {35.0, 135.0, 150.0});
    EXPECT_NEAR(enu.x, 0.0, 1e-6);
    EXPECT_NEAR(enu.y, 0.0, 1e-6);
    EXPECT_NEAR(enu.z, 100.0, 1e-6);
}

TEST(Geodetic, ThousandthOfADegreeAtTheEquator) {
    const gusuku::GeodeticPoint origin{0.0, 0.0, 0.0};
    // Meridian arc of one degree at the equator: a (1 - e^2) * pi / 180 = 110574.27 m.
    const glm::dvec3 north = gusuku::geodeticToEnu(origin, {0.001, 0.0, 0.0});
    EXPECT_NEAR(north.x, 0.0, 1e-6);
    EXPECT_NEAR(north.y, 110.574, 0.002);
    EXPECT_LT(north.z, 0.0);  // the ellipsoid curves away below the tangent plane
    EXPECT_GT(north.z, -0.002);
    // Equatorial arc of one degree of longitude: a * pi / 180 = 111319.49 m.
    const glm::dvec3 east = gusuku::geodeticToEnu(origin, {0.0, 0.001, 0.0});
    EXPECT_NEAR(east.x, 111.3195, 0.002);
    EXPECT_NEAR(east.y, 0.0, 1e-6);
}

TEST(Geodetic, MatchesClosedFormEcefToEnu) {
    const gusuku::GeodeticPoint origins[] = {{26.2170, 127.7195, 120.0}, {-33.8568, 151.2153, 5.0},
                                             {64.1466, -21.9426, 30.0}, {0.0, 179.9995, -20.0}};
    const glm::dvec3 offsets_deg_deg_m[] = {{0.002, 0.0, 0.0}, {0.0, -0.003, 15.0}, {-0.01, 0.01, -40.0},
                                            {0.0005, 0.0009, 300.0}};
    for (const gusuku::GeodeticPoint& origin : origins) {
        for (const glm::dvec3& offset : offsets_deg_deg_m) {
            const gusuku::GeodeticPoint point{origin.latitude_deg + offset.x, origin.longitude_deg + offset.y,
                                              origin.height_m + offset.z};
            const glm::dvec3 expected = closedFormEnu(origin, point);
            const glm::dvec3 actual = gusuku::geodeticToEnu(origin, point);
            EXPECT_NEAR(actual.x, expected.x, 1e-6) << origin.latitude_deg << " " << origin.longitude_deg;
            EXPECT_NEAR(actual.y, expected.y, 1e-6) << origin.latitude_deg << " " << origin.longitude_deg;
            EXPECT_NEAR(actual.z, expected.z, 1e-6) << origin.latitude_deg << " " << origin.longitude_deg;
        }
    }
}

TEST(Geodetic, CrossesTheAntimeridian) {
    // 0.001 deg east of 179.9995 is -179.9995 + 0.0005: the east offset must stay small and positive.
    const gusuku::GeodeticPoint origin{0.0, 179.9995, 0.0};
    const glm::dvec3 enu = gusuku::geodeticToEnu(origin, {0.0, -179.9995, 0.0});
    EXPECT_NEAR(enu.x, 111.3195, 0.002);
}

}  // namespace
