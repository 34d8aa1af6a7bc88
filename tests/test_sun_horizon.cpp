// The sun horizons (gusuku/formats/sun_horizon.h, gusuku_bake/sun_horizon_bake.h) on a V-groove corrugation whose
// horizons are known in closed form (issue 44 item 1: a ribbed roof's grooves under a low sun). Ridges 5 cm high
// every 20 cm run north-south (along y); a point at x0 on a wall rising eastwards from the trough at x = 0 to the
// crest at x = P/2 has height z0 = 2 H x0 / P and sees
//   - to the east, its own wall: horizon atan(2 H / P) (26.57 degrees);
//   - at azimuth phi west of the ridge's normal, the crest at x = -P/2: tan h = (H - z0) |sin phi| / (x0 + P/2);
//   - along the groove (north, south): an open horizon.
// The baked horizons against them, the encoding's layout, and the sun's visibility evaluated from them against
// the closed form's lit share of the wall at suns 10 to 25 degrees high, from the west and 30 degrees off it.

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/formats/sun_horizon.h"
#include "gusuku/maths/mesh.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/sun_horizon_bake.h"

namespace gusuku::bake {
namespace {

constexpr double kHeightM = 0.05, kPeriodM = 0.2, kHalfSideM = 1.0;
constexpr double kDegPerRad = 57.29577951308232;
// The bisection's half interval (0.19 degrees) and the ray's 0.2 mm start off the wall (up to 0.23 degrees at
// 5 cm from the crest it sees).
constexpr double kTraceToleranceDeg = 0.6;

// The corrugation over [-1, 1]^2 m, lightmap uv1 the plan view (a height field: no overlap).
TriangleMesh vGrooveRoof() {
    TriangleMesh mesh;
    mesh.materials.resize(1);
    mesh.has_uv1 = true;
    const int lines = int(std::lround(2.0 * kHalfSideM / (0.5 * kPeriodM)));
    for (int line = 0; line <= lines; ++line) {
        const double x = -kHalfSideM + line * 0.5 * kPeriodM;
        const double z = (line % 2 == 0) ? 0.0 : kHeightM;  // x = -1 is a trough (1 / 0.1 is even)
        for (double y : {-kHalfSideM, kHalfSideM}) {
            mesh.positions.emplace_back(float(x), float(y), float(z));
            mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
            mesh.uv0.emplace_back(0.0f);
            mesh.uv1.emplace_back(float((x + kHalfSideM) / (2 * kHalfSideM)),
                                  float((kHalfSideM - y) / (2 * kHalfSideM)));
        }
    }
    for (int line = 0; line < lines; ++line) {
        const uint32_t a = 2 * line, b = a + 1, c = a + 2, d = a + 3;  // a, c at y = -1; b, d at y = +1
        for (uint32_t index : {a, c, d, a, d, b}) mesh.indices.push_back(index);
        mesh.triangle_material.push_back(0);
        mesh.triangle_material.push_back(0);
    }
    return mesh;
}

double wallHeight(double x0) { return 2.0 * kHeightM * x0 / kPeriodM; }

// The closed form at azimuth `azimuth_deg` (180 to 360) from the wall point x0 in (0, P/2).
double closedFormWestHorizonDeg(double x0, double azimuth_deg) {
    const double sine = std::abs(std::sin(azimuth_deg / kDegPerRad));
    return std::atan((kHeightM - wallHeight(x0)) * sine / (x0 + 0.5 * kPeriodM)) * kDegPerRad;
}

const glm::vec3 kWallNormal = glm::normalize(glm::vec3(-2.0 * kHeightM / kPeriodM, 0.0, 1.0));

TEST(SunHorizon, TracedHorizonsMatchTheVGroovesClosedForm) {
    const TriangleMesh mesh = vGrooveRoof();
    const Bvh bvh = buildBvh(mesh, {});
    const double own_wall_deg = std::atan(2.0 * kHeightM / kPeriodM) * kDegPerRad;
    double worst = 0.0;
    for (double x0 = 0.01; x0 < 0.095; x0 += 0.01) {
        const glm::vec3 point(float(x0), 0.1f, float(wallHeight(x0)));
        for (double azimuth : {225.0, 270.0, 315.0}) {
            const double traced = traceSunHorizonDeg(bvh, point, kWallNormal, azimuth);
            const double truth = closedFormWestHorizonDeg(x0, azimuth);
            EXPECT_NEAR(traced, truth, kTraceToleranceDeg) << "x0 " << x0 << " azimuth " << azimuth;
            worst = std::max(worst, std::abs(traced - truth));
        }
        if (x0 < 0.051) {  // 5 cm or more below its own crest (nearer, the ray's start off the wall shows)
            EXPECT_NEAR(traceSunHorizonDeg(bvh, point, kWallNormal, 90.0), own_wall_deg, kTraceToleranceDeg);
        }
        EXPECT_EQ(traceSunHorizonDeg(bvh, point, kWallNormal, 0.0), 0.0);
        EXPECT_EQ(traceSunHorizonDeg(bvh, point, kWallNormal, 180.0), 0.0);
        // Beyond the radius the crest is not seen: the short radius leaves what is larger to the shadow map. (The
        // horizontal ray meets the western wall at z0, 2 x0 away.)
        EXPECT_EQ(traceSunHorizonDeg(bvh, point, kWallNormal, 270.0, x0), 0.0);
    }
    std::printf("traced horizons against the closed form: worst %.3f degrees\n", worst);
}

// The wall's lit share at a sun of `elevation_deg` from `azimuth_deg`: the closed form's (the crest's shadow
// ends where tan h = tan e) and the visibility evaluated from the baked, encoded horizons of the texels on the
// wall (the middle 1 x 1 m, away from the mesh's ends).
TEST(SunHorizon, BakedVisibilityMatchesTheLitShareOfTheWall) {
    const TriangleMesh mesh = vGrooveRoof();
    const Bvh bvh = buildBvh(mesh, {});
    constexpr int kResolution = 96;  // 2.1 cm texels: 4.7 texels a wall
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, kResolution);
    const BakeSetSunHorizon horizon = bakeSunHorizons(bvh, texels, kResolution, {});
    ASSERT_EQ(horizon.rgba8.size(), size_t(2) * kResolution * kResolution * 4);
    const size_t layer_bytes = size_t(kResolution) * kResolution * 4;

    const double own_wall_deg = std::atan(2.0 * kHeightM / kPeriodM) * kDegPerRad;
    size_t wall_texels = 0;
    double worst_decoded = 0.0;
    for (double azimuth : {270.0, 300.0}) {
        for (double elevation : {10.0, 15.0, 20.0, 25.0}) {
            const glm::dvec3 sun = sunHorizonDirection(azimuth, elevation);
            double lit_baked = 0.0, lit_truth = 0.0;
            wall_texels = 0;
            for (const LightmapTexel& texel : texels) {
                const double x = texel.position.x, y = texel.position.y;
                const double x0 = x - kPeriodM * std::floor(x / kPeriodM);  // within its period
                if (std::abs(x) > 0.5 || std::abs(y) > 0.5 || x0 <= 0.002 || x0 >= 0.5 * kPeriodM - 0.002) continue;
                ++wall_texels;
                const size_t index = (size_t(texel.y) * kResolution + size_t(texel.x)) * 4;
                double horizons[kSunHorizonAzimuths];
                for (int k = 0; k < kSunHorizonAzimuths; ++k)
                    horizons[k] = decodeSunHorizonDeg(horizon.rgba8[size_t(k / 4) * layer_bytes + index + k % 4]);
                worst_decoded = std::max(worst_decoded, std::abs(horizons[6] - closedFormWestHorizonDeg(x0, 270.0)));
                if (x0 < 0.05) worst_decoded = std::max(worst_decoded, std::abs(horizons[2] - own_wall_deg));
                lit_baked += sunHorizonVisibility(horizons, sun);
                lit_truth += std::tan(closedFormWestHorizonDeg(x0, azimuth) / kDegPerRad) <
                                     std::tan(elevation / kDegPerRad)
                                 ? 1.0
                                 : 0.0;
            }
            lit_baked /= double(wall_texels);
            lit_truth /= double(wall_texels);
            std::printf("sun %.0f deg high at azimuth %.0f: wall lit share baked %.3f, closed form %.3f\n", elevation,
                        azimuth, lit_baked, lit_truth);
            // At 300 degrees the horizon is interpolated between 270 and 315 (2 degrees low at worst here).
            EXPECT_NEAR(lit_baked, lit_truth, azimuth == 270.0 ? 0.04 : 0.08);
        }
    }
    ASSERT_GT(wall_texels, 500u);
    // Decoding adds half a code (0.18 degrees) to the trace's tolerance.
    EXPECT_LT(worst_decoded, kTraceToleranceDeg + 0.5 * kSunHorizonDegPerCode);
}

// A plain wall 2 m square facing 20 degrees east of north, nothing else: no sun in front of it is hidden. Stored
// as absolute elevations, its horizon at the stored azimuth 135 (behind the wall) was 90 degrees and at 90 (in
// front) 0, and interpolated between them a sun at azimuth 100, grazing the wall from in front, read a horizon of
// 20 degrees and was hidden below that; what rises above the wall's own horizon is 0 at both, and the wall's own
// plane is added back at the sun's azimuth exactly.
TEST(SunHorizon, AWallFacingBetweenTheStoredAzimuthsIsLitByEverySunInFrontOfIt) {
    const double facing = 20.0 / kDegPerRad;
    const glm::vec3 normal(float(std::sin(facing)), float(std::cos(facing)), 0.0f);
    const glm::vec3 along(float(std::cos(facing)), float(-std::sin(facing)), 0.0f);
    TriangleMesh mesh;
    mesh.materials.resize(1);
    mesh.has_uv1 = true;
    for (int corner = 0; corner < 4; ++corner) {
        const float s = (corner & 1) ? 1.0f : -1.0f, height = (corner & 2) ? 2.0f : 0.0f;
        mesh.positions.push_back(s * along + glm::vec3(0.0f, 0.0f, height));
        mesh.normals.push_back(normal);
        mesh.uv0.emplace_back(0.0f);
        mesh.uv1.emplace_back(0.5f * (s + 1.0f), 1.0f - 0.5f * height);
    }
    for (uint32_t index : {0u, 3u, 1u, 0u, 2u, 3u}) mesh.indices.push_back(index);
    mesh.triangle_material = {0, 0};
    const Bvh bvh = buildBvh(mesh, {});
    constexpr int kResolution = 16;
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(mesh, kResolution);
    ASSERT_GT(texels.size(), 100u);
    ASSERT_GT(glm::dot(texels.front().geometric_normal, normal), 0.999f);  // the winding faces the normal
    const BakeSetSunHorizon horizon = bakeSunHorizons(bvh, texels, kResolution, {});
    const size_t layer_bytes = size_t(kResolution) * kResolution * 4;
    double darkest = 1.0;
    for (const LightmapTexel& texel : texels) {
        const size_t index = (size_t(texel.y) * kResolution + size_t(texel.x)) * 4;
        double horizons[kSunHorizonAzimuths];
        for (int k = 0; k < kSunHorizonAzimuths; ++k)
            horizons[k] = decodeSunHorizonDeg(horizon.rgba8[size_t(k / 4) * layer_bytes + index + k % 4]);
        for (double off_normal : {-85.0, -60.0, -30.0, 0.0, 30.0, 60.0, 80.0, 85.0})
            for (double elevation : {10.0, 15.0, 20.0, 25.0})
                darkest = std::min(darkest, sunHorizonVisibility(horizons, sunHorizonDirection(20.0 + off_normal,
                                                                                                elevation),
                                                                 glm::dvec3(normal)));
    }
    EXPECT_EQ(darkest, 1.0);
}

TEST(SunHorizon, OpenHorizonIsFullyVisibleAndTheTransitionIsCentredOnTheHorizon) {
    const double open[kSunHorizonAzimuths] = {};
    EXPECT_EQ(sunHorizonVisibility(open, sunHorizonDirection(123.0, 0.5)), 1.0);
    double horizons[kSunHorizonAzimuths] = {};
    horizons[2] = 20.0;  // east
    horizons[3] = 10.0;  // south-east
    EXPECT_NEAR(sunHorizonVisibility(horizons, sunHorizonDirection(90.0, 20.0)), 0.5, 1e-9);
    EXPECT_NEAR(sunHorizonVisibility(horizons, sunHorizonDirection(112.5, 15.0)), 0.5, 1e-9);  // halfway: 15
    EXPECT_EQ(sunHorizonVisibility(horizons, sunHorizonDirection(90.0, 19.4)), 0.0);
    EXPECT_EQ(sunHorizonVisibility(horizons, sunHorizonDirection(90.0, 20.6)), 1.0);
    EXPECT_EQ(encodeSunHorizonDeg(90.0), 255);
    EXPECT_EQ(encodeSunHorizonDeg(-3.0), 0);
    EXPECT_NEAR(decodeSunHorizonDeg(encodeSunHorizonDeg(17.3)), 17.3, 0.5 * kSunHorizonDegPerCode);
}

}  // namespace
}  // namespace gusuku::bake
