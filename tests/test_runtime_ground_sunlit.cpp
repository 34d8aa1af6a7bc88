// The ground cells whose baked change the frame's light leaves at a ratio of exactly 1 (engine/src/runtime/
// ground_sunlit.h): every quad left undrawn because all four corners pass is checked against a brute-force
// reference (the shader's ratio at many points inside the quad, from the slots' interpolated light and a sun ray
// walked against the occluder's triangles), and a wall between a cell and the sun keeps it drawn.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "ground_sunlit.h"

namespace gusuku::runtime_detail {
namespace {

constexpr float kThreshold = 0.5f / 255.0f;  // the shader's pass-through threshold (frame_preparation.h)

struct Lcg {
    uint64_t state = 0x2545F4914F6CDD1Dull;
    double next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) / double(1ull << 53);
    }
};

struct Site {
    GroundGrid grid;
    std::vector<uint8_t> state;
    std::vector<float> height;
    std::vector<glm::vec3> normal;
    std::vector<glm::vec3> positions;  // the occluder: the flat ground and a wall
    std::vector<uint32_t> indices;
    std::vector<float> slot_light;     // 2 slots x cells x 6
    GroundCells cells() const { return {grid, state, height, normal}; }
};

void addQuad(Site& site, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const uint32_t first = uint32_t(site.positions.size());
    site.positions.insert(site.positions.end(), {a, b, c, d});
    site.indices.insert(site.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

// A flat 24 x 20 grid of 0.5 m cells at z = 0, a 3 m wall along x = 2 from y = -2 to 2, and per cell two slots
// whose sky-only change is 0 to 3 % of E_without: from far below the threshold to far above it.
Site makeSite() {
    Site site;
    site.grid.origin_enu_m = {-6.0, -5.0};
    site.grid.cell_m = 0.5;
    site.grid.columns = 24;
    site.grid.rows = 20;
    const size_t cells = 24 * 20;
    Lcg random;
    site.slot_light.assign(2 * cells * 6, 0.0f);
    for (size_t cell = 0; cell < cells; ++cell) {
        site.state.push_back(random.next() < 0.9 ? kCellGroundChangedByBuilding : kCellGround);
        site.height.push_back(0.0f);
        site.normal.push_back(glm::vec3(0.0f, 0.0f, 1.0f));
        for (size_t slot = 0; slot < 2; ++slot)
            for (int channel = 0; channel < 3; ++channel) {
                const float without = float(20.0 + 40.0 * random.next());
                const float change = float((random.next() - 0.3) * 0.03);
                site.slot_light[(slot * cells + cell) * 6 + size_t(channel)] = without * (1.0f + change);
                site.slot_light[(slot * cells + cell) * 6 + 3 + size_t(channel)] = without;
            }
    }
    addQuad(site, {-7, -6, 0}, {7, -6, 0}, {7, 6, 0}, {-7, 6, 0});
    addQuad(site, {2, -2, 0}, {2, 2, 0}, {2, 2, 3}, {2, -2, 3});
    return site;
}

// Möller-Trumbore: whether the ray origin + t direction, t > 1e-4, meets the triangle.
bool rayHitsTriangle(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& a,
                     const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, p = glm::cross(direction, ac);
    const double determinant = glm::dot(ab, p);
    if (std::abs(determinant) < 1e-12) return false;
    const glm::dvec3 s = origin - a;
    const double u = glm::dot(s, p) / determinant;
    if (u < 0.0 || u > 1.0) return false;
    const glm::dvec3 q = glm::cross(s, ab);
    const double v = glm::dot(direction, q) / determinant;
    if (v < 0.0 || u + v > 1.0) return false;
    return glm::dot(ac, q) / determinant > 1e-4;
}

// The site's shadow map: 3.5 cm texels, a bias of 1.5 of them (the runtime's default); on flat ground the slope's
// share of the bias is tan(zenith angle).
constexpr SiteShadowTest kSiteTest{0.035, 1.5};
double flatGroundBiasM(const glm::dvec3& sun) {
    return kSiteTest.bias_texels * kSiteTest.texel_m * (1.0 + std::min(std::hypot(sun.x, sun.y) / sun.z, 10.0));
}

// Lit when the rays towards the sun from the point and from four points at the tap's reach across its ray, each
// started the bias nearer the sun, meet no triangle of the occluder.
bool inSunByRays(const Site& site, const glm::dvec3& point, const glm::dvec3& sun) {
    const glm::dvec3 across = glm::normalize(glm::cross(sun, glm::dvec3(0, 0, 1)));
    const glm::dvec3 up = glm::cross(across, sun);
    const glm::dvec3 offsets[5] = {glm::dvec3(0.0), across, -across, up, -up};
    for (const glm::dvec3& offset : offsets) {
        const glm::dvec3 origin = point + kSiteTapReachTexels * kSiteTest.texel_m * offset + flatGroundBiasM(sun) * sun;
        for (size_t first = 0; first < site.indices.size(); first += 3)
            if (rayHitsTriangle(origin, sun, glm::dvec3(site.positions[site.indices[first]]),
                                glm::dvec3(site.positions[site.indices[first + 1]]),
                                glm::dvec3(site.positions[site.indices[first + 2]])))
                return false;
    }
    return true;
}

glm::dvec3 sunAt(double azimuth_deg, double elevation_deg) {
    const double az = azimuth_deg * std::numbers::pi / 180.0, el = elevation_deg * std::numbers::pi / 180.0;
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
}

// The shader's ratio (ground.frag's baked variant, building visibility 1) at a point of a quad, from the four
// corners' light bilinearly interpolated, in float as the GPU computes it.
float worstRatioError(const Site& site, const PassThroughLight& light, const double sun_scale[3], size_t corners[4],
                      double fx, double fy, double sun_cosine, bool sunlit) {
    const size_t cells = site.state.size();
    const double weights_xy[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    float worst = 0.0f;
    for (int channel = 0; channel < 3; ++channel) {
        float with = 0.0f, without = 0.0f;
        for (int blend = 0; blend < 3; ++blend) {
            if (light.slots[blend] < 0) continue;
            for (int corner = 0; corner < 4; ++corner) {
                const float* values = &site.slot_light[(size_t(light.slots[blend]) * cells + corners[corner]) * 6];
                with += float(weights_xy[corner]) * light.weights[blend] * values[channel];
                without += float(weights_xy[corner]) * light.weights[blend] * values[3 + channel];
            }
        }
        const float e_sun = sunlit ? float(sun_scale[channel] * sun_cosine) : 0.0f;
        worst = std::max(worst, std::abs((with + e_sun) / (without + e_sun) - 1.0f));
    }
    return worst;
}

TEST(GroundSunlit, EveryUndrawnQuadKeepsTheRatioAtOneUnderTheFramesLight) {
    const Site site = makeSite();
    const SiteHeightTiles tiles = siteHeightTiles(site.grid, site.positions, site.indices);
    const size_t columns = 24, rows = 20;
    size_t undrawn_total = 0, passing_total = 0;
    const double suns[][2] = {{90, 25}, {180, 60}, {250, 40}, {0, 89}};
    const double sun_strength[] = {0.0, 200.0, 900.0};  // no sun, weak, strong (E_without is 20-60)
    for (const auto& sun_angles : suns)
        for (double strength : sun_strength) {
            PassThroughLight light;
            light.slots[0] = 0, light.slots[1] = 1;
            light.weights[0] = 0.3f, light.weights[1] = 0.7f;
            light.sun_shines = strength > 0.0;
            light.shadow_sun = sunAt(sun_angles[0], sun_angles[1]);
            light.sun_irradiance_floor = glm::dvec3(strength, 0.9 * strength, 0.8 * strength);
            light.cosine_slack = 0.5 * std::numbers::pi / 180.0 + 0.001;
            light.pass_through_threshold = kThreshold;
            light.site_shadow = kSiteTest;
            std::vector<uint8_t> pass(columns * rows, 0);
            markPassThroughCells(site.cells(), site.slot_light, tiles, light, pass);
            // The frame's own sun: within the half-degree step of the rounded one, and at least as strong.
            const glm::dvec3 frame_sun = sunAt(sun_angles[0] + 0.35, sun_angles[1] - 0.35);
            const double frame_scale[3] = {strength, 0.9 * strength, 0.8 * strength};
            for (size_t cell = 0; cell < pass.size(); ++cell) {
                if (pass[cell]) ++passing_total;
                if (pass[cell]) {
                    EXPECT_EQ(site.state[cell], kCellGroundChangedByBuilding);
                }
            }
            for (size_t row = 0; row + 1 < rows; ++row)
                for (size_t column = 0; column + 1 < columns; ++column) {
                    size_t corners[4] = {row * columns + column, row * columns + column + 1,
                                         (row + 1) * columns + column, (row + 1) * columns + column + 1};
                    bool undrawn = true;
                    for (size_t corner : corners) undrawn = undrawn && pass[corner];
                    if (!undrawn) continue;
                    ++undrawn_total;
                    const glm::dvec3 west_north = groundCellCentre(site.grid, column, row, 0.0);
                    for (int iy = 0; iy <= 4; ++iy)
                        for (int ix = 0; ix <= 4; ++ix) {
                            const double fx = ix / 4.0, fy = iy / 4.0;
                            const glm::dvec3 point = west_north + glm::dvec3(fx * 0.5, -fy * 0.5, 0.001);
                            const bool sunlit = light.sun_shines && inSunByRays(site, point, frame_sun);
                            if (light.sun_shines) {
                                EXPECT_TRUE(sunlit) << "cell " << corners[0] << " is shaded";
                            }
                            const float error = worstRatioError(site, light, frame_scale, corners, fx, fy,
                                                                frame_sun.z, sunlit);
                            EXPECT_LT(error, kThreshold) << "quad at " << column << "," << row;
                        }
                }
        }
    // The check is not vacuous: strong sun frees most marked cells.
    EXPECT_GT(undrawn_total, 500u);
    EXPECT_GT(passing_total, 800u);
}

TEST(GroundSunlit, AWallBetweenTheCellAndTheSunKeepsItDrawn) {
    Site site = makeSite();
    const size_t columns = 24;
    // Every cell marked, changed by 2 % (four times the threshold): only the sun can hide that.
    for (size_t cell = 0; cell < site.state.size(); ++cell) {
        site.state[cell] = kCellGroundChangedByBuilding;
        for (size_t slot = 0; slot < 2; ++slot)
            for (int channel = 0; channel < 3; ++channel)
                site.slot_light[(slot * site.state.size() + cell) * 6 + size_t(channel)] =
                    1.02f * site.slot_light[(slot * site.state.size() + cell) * 6 + 3 + size_t(channel)];
    }
    const SiteHeightTiles tiles = siteHeightTiles(site.grid, site.positions, site.indices);
    PassThroughLight light;
    light.slots[0] = 0, light.weights[0] = 1.0f;
    light.sun_shines = true;
    light.shadow_sun = sunAt(90.0, 30.0);  // from the east, low: the wall at x = 2 shades x in (-3.2, 2)
    light.sun_irradiance_floor = glm::dvec3(900.0);
    light.pass_through_threshold = kThreshold;
    light.site_shadow = kSiteTest;
    std::vector<uint8_t> pass(site.state.size(), 0);
    markPassThroughCells(site.cells(), site.slot_light, tiles, light, pass);
    // Row 10 is at y = -0.25 (behind the wall's middle); column c's centre x = -6 + 0.5 c + 0.25.
    const size_t row = 10;
    EXPECT_FALSE(pass[row * columns + 12]) << "x = 0.25, in the wall's shadow";
    EXPECT_FALSE(pass[row * columns + 8]) << "x = -1.75, in the wall's shadow";
    EXPECT_TRUE(pass[row * columns + 22]) << "x = 5.25, east of the wall: in sun";
    EXPECT_TRUE(pass[2 * columns + 12]) << "y = 3.75, north of the wall's end: in sun";
    // Weights that sum above 1 would break the blend's bound: nothing passes.
    light.weights[0] = 1.0f, light.slots[1] = 1, light.weights[1] = 0.01f;
    markPassThroughCells(site.cells(), site.slot_light, tiles, light, pass);
    for (uint8_t cell : pass) ASSERT_EQ(cell, 0);
    // Without sun a 2 % change is never within the threshold.
    light.weights[1] = 0.0f, light.sun_shines = false;
    markPassThroughCells(site.cells(), site.slot_light, tiles, light, pass);
    for (uint8_t cell : pass) ASSERT_EQ(cell, 0);
}

}  // namespace
}  // namespace gusuku::runtime_detail
