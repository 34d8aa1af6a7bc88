// Ground grid addressing and the shadow-catcher ratio (gusuku/formats/ground_grid.h): the C++ against values worked
// out by hand from docs/bakeset.md and docs/design.md 3, the baker's grid builder against the shared addressing, and
// the GLSL twin (shaders/include/ground_ratio.glsl, through shaders/tests/ground_ratio_probe.comp) against the
// C++ on a spread of inputs.

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "ground_ratio_probe_comp_spv.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/formats/ground_grid.h"
#include "gusuku_bake/ground_grid.h"

namespace {

using gusuku::GroundCellAddress;
using gusuku::GroundGrid;

// 8 x 6 cells of 0.5 m, south-west corner at ENU (-3, 2): x in [-3, 1), y in [2, 5).
GroundGrid smallGrid() {
    GroundGrid grid;
    grid.origin_enu_m = {-3.0, 2.0};
    grid.cell_m = 0.5;
    grid.columns = 8;
    grid.rows = 6;
    return grid;
}

TEST(GroundGrid, CellCentresByHand) {
    const GroundGrid grid = smallGrid();
    // Row 0 is the north edge: cell (0, 0) is the north-west corner cell, (7, 5) the south-east one.
    EXPECT_EQ(gusuku::groundCellCentreEnu(grid, {0, 0}), glm::dvec2(-2.75, 4.75));
    EXPECT_EQ(gusuku::groundCellCentreEnu(grid, {7, 5}), glm::dvec2(0.75, 2.25));
    EXPECT_EQ(gusuku::groundCellCentreEnu(grid, {3, 2}), glm::dvec2(-1.25, 3.75));
    EXPECT_EQ(gusuku::groundCellIndex(grid, {0, 0}), 0u);
    EXPECT_EQ(gusuku::groundCellIndex(grid, {7, 0}), 7u);
    EXPECT_EQ(gusuku::groundCellIndex(grid, {0, 1}), 8u);
    EXPECT_EQ(gusuku::groundCellIndex(grid, {7, 5}), 47u);
    EXPECT_EQ(gusuku::groundCellFromIndex(grid, 47), (GroundCellAddress{7, 5}));
    EXPECT_EQ(gusuku::groundCellFromIndex(grid, 19), (GroundCellAddress{3, 2}));
    EXPECT_EQ(grid.cellCount(), 48u);
    EXPECT_EQ(GroundGrid{}.cellCount(), 0u);
}

TEST(GroundGrid, EveryCellCentreMapsToItsCellAndIndexAndBack) {
    const GroundGrid grid = smallGrid();
    std::set<size_t> indices;
    for (int row = 0; row < grid.rows; ++row)
        for (int column = 0; column < grid.columns; ++column) {
            const GroundCellAddress cell{column, row};
            const glm::dvec2 centre = gusuku::groundCellCentreEnu(grid, cell);
            const auto found = gusuku::groundCellAt(grid, centre);
            ASSERT_TRUE(found.has_value()) << column << ", " << row;
            EXPECT_EQ(*found, cell);
            const size_t index = gusuku::groundCellIndex(grid, cell);
            EXPECT_EQ(gusuku::groundCellFromIndex(grid, index), cell);
            indices.insert(index);
            // The centre is the texel centre of the ground images.
            const glm::dvec2 uv = gusuku::groundGridUv(grid, centre);
            EXPECT_NEAR(uv.x, (column + 0.5) / grid.columns, 1e-12);
            EXPECT_NEAR(uv.y, (row + 0.5) / grid.rows, 1e-12);
        }
    EXPECT_EQ(indices.size(), grid.cellCount());
    EXPECT_EQ(*indices.rbegin(), grid.cellCount() - 1);
}

TEST(GroundGrid, CellsAreHalfOpenAndOutsideIsNothing) {
    const GroundGrid grid = smallGrid();
    // The south-west corner belongs to the south-west cell (column 0, last row); the east and north edges
    // belong to no cell.
    EXPECT_EQ(gusuku::groundCellAt(grid, {-3.0, 2.0}), (GroundCellAddress{0, 5}));
    EXPECT_EQ(gusuku::groundCellAt(grid, {-2.5, 2.5}), (GroundCellAddress{1, 4}));
    EXPECT_EQ(gusuku::groundCellAt(grid, {0.999, 4.999}), (GroundCellAddress{7, 0}));
    EXPECT_FALSE(gusuku::groundCellAt(grid, {1.0, 3.0}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(grid, {0.0, 5.0}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(grid, {-3.001, 3.0}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(grid, {0.0, 1.999}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(grid, {1e300, 3.0}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(grid, {std::nan(""), 3.0}).has_value());
    EXPECT_FALSE(gusuku::groundCellAt(GroundGrid{}, {0.0, 0.0}).has_value());
    EXPECT_TRUE(gusuku::groundCellInside(grid, {7, 5}));
    EXPECT_FALSE(gusuku::groundCellInside(grid, {8, 0}));
    EXPECT_FALSE(gusuku::groundCellInside(grid, {0, -1}));
    // The grid's corners in texture coordinates: north-west (0, 0), south-east (1, 1).
    EXPECT_EQ(gusuku::groundGridUv(grid, {-3.0, 5.0}), glm::dvec2(0.0, 0.0));
    EXPECT_EQ(gusuku::groundGridUv(grid, {1.0, 2.0}), glm::dvec2(1.0, 1.0));
}

TEST(GroundGrid, BakerGridBuilderUsesTheSharedAddressing) {
    gusuku::Bounds3 building;
    building.min = {-2.0f, -1.0f, 0.0f};
    building.max = {2.0f, 1.5f, 3.0f};
    const gusuku::bake::GroundRegion region = gusuku::bake::chooseGroundRegion(building, 30.0, 0.25);
    const GroundGrid& grid = region;  // the baker's region is the shared grid, not a copy of its layout
    ASSERT_GT(grid.cellCount(), 0u);
    // Its builder's cell centres are the shared ones, and they cover the building's footprint.
    for (const GroundCellAddress cell : {GroundCellAddress{0, 0}, GroundCellAddress{grid.columns - 1, grid.rows - 1},
                                         GroundCellAddress{grid.columns / 2, grid.rows / 3}})
        EXPECT_EQ(gusuku::bake::groundCellCentre(region, cell.column, cell.row),
                  gusuku::groundCellCentreEnu(grid, cell));
    EXPECT_TRUE(gusuku::groundCellAt(grid, {-2.0, -1.0}).has_value());
    EXPECT_TRUE(gusuku::groundCellAt(grid, {1.99, 1.49}).has_value());
}

// ------------------------------------------------------------------------------------------------------------
// The ratio, by hand
// ------------------------------------------------------------------------------------------------------------

TEST(GroundRatio, SunIrradianceIsVisibilityTimesCosine) {
    const glm::vec3 sun(6.0f, 5.0f, 4.0f);
    const glm::vec3 up(0.0f, 0.0f, 1.0f);
    const glm::vec3 sun_direction(0.0f, 0.6f, 0.8f);  // elevation asin(0.8), in the north
    EXPECT_EQ(gusuku::groundSunIrradiance(sun, up, sun_direction, 1.0f), glm::vec3(4.8f, 4.0f, 3.2f));
    EXPECT_EQ(gusuku::groundSunIrradiance(sun, up, sun_direction, 0.0f), glm::vec3(0.0f));  // real scene's shadow
    EXPECT_EQ(gusuku::groundSunIrradiance(sun, up, {0.0f, 0.6f, -0.8f}, 1.0f), glm::vec3(0.0f));  // sun below
    // A slope facing the sun squarely gets all of I_sun.
    EXPECT_EQ(gusuku::groundSunIrradiance(sun, sun_direction, sun_direction, 1.0f), sun);
}

TEST(GroundRatio, HandComputedValues) {
    const glm::vec3 e(0.3f, 0.5f, 0.7f);
    const glm::vec3 e_sun(2.0f, 3.0f, 4.0f);
    // Where the building changes nothing, the photo passes through: exactly 1.
    EXPECT_EQ(gusuku::groundShadowRatio(e, e, e_sun, 1.0f), glm::vec3(1.0f));
    EXPECT_EQ(gusuku::groundShadowRatio(e, e, glm::vec3(0.0f), 0.0f), glm::vec3(1.0f));
    // In the building's shadow with unchanged sky light: E_without / (E_without + E_sun).
    const glm::vec3 shadowed = gusuku::groundShadowRatio(e, e, e_sun, 0.0f);
    EXPECT_FLOAT_EQ(shadowed.x, 0.3f / 2.3f);
    EXPECT_FLOAT_EQ(shadowed.y, 0.5f / 3.5f);
    EXPECT_FLOAT_EQ(shadowed.z, 0.7f / 4.7f);
    // Half shadow, less sky under the eaves: E_with 0.4, E_without 0.5, E_sun 4.8 (I_sun 6 at sin e = 0.8),
    // V_bld 0.25: (0.4 + 1.2) / 5.3.
    const glm::vec3 e_sun_flat =
        gusuku::groundSunIrradiance(glm::vec3(6.0f), {0.0f, 0.0f, 1.0f}, {0.0f, 0.6f, 0.8f}, 1.0f);
    const glm::vec3 half = gusuku::groundShadowRatio(glm::vec3(0.4f), glm::vec3(0.5f), e_sun_flat, 0.25f);
    EXPECT_NEAR(half.x, 1.6 / 5.3, 1e-6);
    EXPECT_EQ(half.x, half.y);
    EXPECT_EQ(half.y, half.z);
    // In the real scene's own shadow there is no new sun term: the ratio is E_with / E_without whatever V_bld.
    const glm::vec3 no_sun =
        gusuku::groundSunIrradiance(glm::vec3(6.0f), {0.0f, 0.0f, 1.0f}, {0.0f, 0.6f, 0.8f}, 0.0f);
    EXPECT_FLOAT_EQ(gusuku::groundShadowRatio(glm::vec3(0.4f), glm::vec3(0.5f), no_sun, 0.0f).x, 0.8f);
    EXPECT_FLOAT_EQ(gusuku::groundShadowRatio(glm::vec3(0.4f), glm::vec3(0.5f), no_sun, 1.0f).x, 0.8f);
    // Light the building bounces onto the ground brightens it.
    EXPECT_FLOAT_EQ(gusuku::groundShadowRatio(glm::vec3(0.6f), glm::vec3(0.5f), glm::vec3(1.0f), 1.0f).x,
                    1.6f / 1.5f);
}

TEST(GroundRatio, ZeroDenominatorGivesOnePerChannel) {
    // Green has light without the building, red and blue have none: those two pass the photo through.
    const glm::vec3 ratio =
        gusuku::groundShadowRatio({0.2f, 0.3f, 0.4f}, {0.0f, 0.6f, 0.0f}, glm::vec3(0.0f), 0.0f);
    EXPECT_EQ(ratio, glm::vec3(1.0f, 0.5f, 1.0f));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(gusuku::groundShadowRatio(glm::vec3(0.2f), glm::vec3(nan), glm::vec3(1.0f), 1.0f), glm::vec3(1.0f));
}

// ------------------------------------------------------------------------------------------------------------
// The GLSL twin against the C++
// ------------------------------------------------------------------------------------------------------------

struct Probe {
    glm::vec2 point{0.0f};
    GroundCellAddress cell;
    int index = 0;
    glm::vec3 e_with{0.0f}, e_without{0.0f}, sun_irradiance{0.0f}, normal{0.0f, 0.0f, 1.0f},
        sun_direction{0.0f, 0.0f, 1.0f};
    float building_visibility = 1.0f, scene_visibility = 1.0f;
};

struct ProbeOutput {
    glm::vec2 centre{0.0f}, uv{0.0f};
    bool found = false;
    GroundCellAddress found_cell;
    int index = 0;
    GroundCellAddress from_index;
    bool inside = false;
    glm::vec3 e_sun{0.0f}, ratio{0.0f};
};

struct ProbePushConstants {
    float origin_enu_m[2];
    float cell_m;
    int32_t columns;
    int32_t rows;
    uint32_t probe_count;
};
static_assert(sizeof(ProbePushConstants) == 24);

std::vector<ProbeOutput> runGroundRatioProbe(gusuku::VulkanContext& context, const GroundGrid& grid,
                                             const std::vector<Probe>& probes) {
    std::vector<float> float_inputs;
    std::vector<int32_t> int_inputs;
    for (const Probe& p : probes) {
        float_inputs.insert(float_inputs.end(), {p.point.x, p.point.y, 0.0f, 0.0f});
        float_inputs.insert(float_inputs.end(), {p.e_with.x, p.e_with.y, p.e_with.z, p.building_visibility});
        float_inputs.insert(float_inputs.end(), {p.e_without.x, p.e_without.y, p.e_without.z, p.scene_visibility});
        float_inputs.insert(float_inputs.end(), {p.sun_irradiance.x, p.sun_irradiance.y, p.sun_irradiance.z, 0.0f});
        float_inputs.insert(float_inputs.end(), {p.normal.x, p.normal.y, p.normal.z, 0.0f});
        float_inputs.insert(float_inputs.end(), {p.sun_direction.x, p.sun_direction.y, p.sun_direction.z, 0.0f});
        int_inputs.insert(int_inputs.end(), {p.cell.column, p.cell.row, p.index, 0});
    }
    gusuku::GpuBuffer float_buffer(context, float_inputs.size() * sizeof(float));
    gusuku::GpuBuffer int_buffer(context, int_inputs.size() * sizeof(int32_t));
    gusuku::GpuBuffer output_buffer(context, probes.size() * 20 * sizeof(float));
    float_buffer.uploadVector(float_inputs);
    int_buffer.uploadVector(int_inputs);
    gusuku::ComputePipeline pipeline(context, kGroundRatioProbeCompSpirv, sizeof(kGroundRatioProbeCompSpirv), 3,
                                     sizeof(ProbePushConstants));
    pipeline.bindBuffers({&float_buffer, &int_buffer, &output_buffer});
    const ProbePushConstants push{{float(grid.origin_enu_m.x), float(grid.origin_enu_m.y)},
                                  float(grid.cell_m), grid.columns, grid.rows, uint32_t(probes.size())};
    constexpr uint32_t kLocalSize = 64;  // local_size_x in ground_ratio_probe.comp
    pipeline.dispatchAndWait(&push, (uint32_t(probes.size()) + kLocalSize - 1) / kLocalSize);
    const std::vector<float> o = output_buffer.downloadVector<float>(probes.size() * 20);
    std::vector<ProbeOutput> outputs(probes.size());
    for (size_t i = 0; i < probes.size(); ++i) {
        const float* v = o.data() + 20 * i;
        ProbeOutput& out = outputs[i];
        out.centre = {v[0], v[1]};
        out.uv = {v[2], v[3]};
        out.found = v[4] != 0.0f;
        out.found_cell = {int(v[5]), int(v[6])};
        out.index = int(v[7]);
        out.from_index = {int(v[8]), int(v[9])};
        out.inside = v[10] != 0.0f;
        out.e_sun = {v[12], v[13], v[14]};
        out.ratio = {v[16], v[17], v[18]};
    }
    return outputs;
}

/// Probes over a grid that is not aligned to anything: cells inside and just outside, points near cell centres
/// (never within 5 % of a cell edge, where float and double may round to different cells) and outside the
/// grid, irradiance with zero channels (the guard), visibilities of 0, 1 and between, suns above and below.
std::vector<Probe> spreadOfProbes(const GroundGrid& grid, size_t count) {
    std::mt19937 random(20260621u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> column(-2, grid.columns + 1), row(-2, grid.rows + 1);
    std::uniform_int_distribution<int> index(0, int(grid.cellCount()) - 1);
    const auto irradiance = [&](float scale) {
        glm::vec3 e(unit(random), unit(random), unit(random));
        for (int c = 0; c < 3; ++c)
            if (unit(random) < 0.15f) e[c] = 0.0f;
        return e * scale;
    };
    const auto visibility = [&] {
        const float u = unit(random);
        return u < 0.3f ? 0.0f : u < 0.6f ? 1.0f : unit(random);
    };
    std::vector<Probe> probes(count);
    for (Probe& p : probes) {
        p.cell = {column(random), row(random)};
        p.index = index(random);
        const glm::dvec2 centre = gusuku::groundCellCentreEnu(grid, {column(random), row(random)});
        const glm::dvec2 offset(unit(random) * 0.9 - 0.45, unit(random) * 0.9 - 0.45);
        p.point = glm::vec2(centre + offset * grid.cell_m);
        p.e_with = irradiance(3.0f);
        p.e_without = irradiance(3.0f);
        p.sun_irradiance = irradiance(20.0f);
        p.normal = glm::normalize(glm::vec3(unit(random) - 0.5f, unit(random) - 0.5f, 1.0f));
        const float elevation = (unit(random) * 100.0f - 10.0f) * std::numbers::pi_v<float> / 180.0f;
        const float azimuth = unit(random) * (2.0f * std::numbers::pi_v<float>);
        p.sun_direction = {std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                           std::sin(elevation)};
        p.building_visibility = visibility();
        p.scene_visibility = visibility();
    }
    return probes;
}

class GroundRatioGpu : public gusuku::testing::GpuTest {};

TEST_F(GroundRatioGpu, GlslTwinMatchesTheCpp) {
    GroundGrid grid;
    grid.origin_enu_m = {-12.3, 4.7};
    grid.cell_m = 0.37;
    grid.columns = 41;
    grid.rows = 29;
    const std::vector<Probe> probes = spreadOfProbes(grid, 2000);
    const std::vector<ProbeOutput> gpu = runGroundRatioProbe(context(), grid, probes);
    size_t found = 0, outside = 0, guarded = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
        const Probe& p = probes[i];
        const ProbeOutput& g = gpu[i];
        SCOPED_TRACE("probe " + std::to_string(i));
        const glm::dvec2 centre = gusuku::groundCellCentreEnu(grid, p.cell);
        EXPECT_NEAR(g.centre.x, centre.x, 1e-5);
        EXPECT_NEAR(g.centre.y, centre.y, 1e-5);
        const glm::dvec2 uv = gusuku::groundGridUv(grid, glm::dvec2(p.point));
        EXPECT_NEAR(g.uv.x, uv.x, 1e-6);
        EXPECT_NEAR(g.uv.y, uv.y, 1e-6);
        const auto cell = gusuku::groundCellAt(grid, glm::dvec2(p.point));
        EXPECT_EQ(g.found, cell.has_value());
        if (cell) {
            EXPECT_EQ(g.found_cell, *cell);
            ++found;
        } else {
            EXPECT_EQ(g.found_cell, (GroundCellAddress{-1, -1}));
            ++outside;
        }
        EXPECT_EQ(g.inside, gusuku::groundCellInside(grid, p.cell));
        if (gusuku::groundCellInside(grid, p.cell)) {
            EXPECT_EQ(size_t(g.index), gusuku::groundCellIndex(grid, p.cell));
        }
        EXPECT_EQ(g.from_index, gusuku::groundCellFromIndex(grid, size_t(p.index)));
        const glm::vec3 e_sun = gusuku::groundSunIrradiance(p.sun_irradiance, p.normal, p.sun_direction,
                                                             p.scene_visibility);
        const glm::vec3 ratio = gusuku::groundShadowRatio(p.e_with, p.e_without, e_sun, p.building_visibility);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(g.e_sun[c], e_sun[c], 1e-6f * (1.0f + e_sun[c]));
            EXPECT_NEAR(g.ratio[c], ratio[c], 1e-5f * (1.0f + ratio[c]));
            if (!(p.e_without[c] + e_sun[c] > 0.0f)) ++guarded;
        }
    }
    // The spread reached every branch.
    EXPECT_GT(found, probes.size() / 2);
    EXPECT_GT(outside, 50u);
    EXPECT_GT(guarded, 20u);
}

}  // namespace
