// The bake's ground region (gusuku_bake/ground_grid.h, chooseSiteGroundRegion): it covers the site mesh's own
// relief near the building and that relief's shadows at the lowest baked sun, not only the building's (issue 41:
// the runtime reads the sun from the site's shadows in the camera frame, over the grid's cells only). Checked on
// hand-built meshes against positions worked out by hand.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gusuku/formats/ground_grid.h"
#include "gusuku_bake/ground_grid.h"

namespace {

using gusuku::Bounds3;
using gusuku::GroundGrid;
using gusuku::TriangleMesh;

void addQuad(TriangleMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const auto first = uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
    mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

// A flat terrace 40 m square at z = 0.
TriangleMesh flatSite() {
    TriangleMesh site;
    addQuad(site, {-20.0f, -20.0f, 0.0f}, {20.0f, -20.0f, 0.0f}, {20.0f, 20.0f, 0.0f}, {-20.0f, 20.0f, 0.0f});
    return site;
}

// A wall along ENU y = wall_y from x = -6 to 6, `height` tall, standing on the terrace.
void addWall(TriangleMesh& site, float wall_y, float height) {
    addQuad(site, {-6.0f, wall_y, 0.0f}, {6.0f, wall_y, 0.0f}, {6.0f, wall_y, height}, {-6.0f, wall_y, height});
}

// A 4 m square building 3 m tall about the origin.
Bounds3 building() {
    Bounds3 bounds;
    bounds.min = {-2.0f, -2.0f, 0.0f};
    bounds.max = {2.0f, 2.0f, 3.0f};
    return bounds;
}

bool covers(const GroundGrid& grid, double east_m, double north_m) {
    return gusuku::groundCellAt(grid, {east_m, north_m}).has_value();
}

constexpr double kLowestSunDeg = 30.0;
constexpr double kCellM = 0.5;

TEST(GroundRegion, CoversASiteWallAndItsShadowsBesideTheBuilding) {
    TriangleMesh site = flatSite();
    const float wall_y = -12.0f, wall_height = 2.5f;
    addWall(site, wall_y, wall_height);
    // The building's own region ends 3 / tan 30 + 1.5 = 6.7 m from it (y = -8.7): the wall is outside it.
    const GroundGrid building_only = gusuku::bake::chooseGroundRegion(building(), kLowestSunDeg, kCellM);
    ASSERT_FALSE(covers(building_only, 0.0, wall_y));
    const GroundGrid region = gusuku::bake::chooseSiteGroundRegion(building(), site, kLowestSunDeg, kCellM);
    // The wall's shadow at the lowest sun reaches wall_height / tan 30 = 4.33 m from its foot, on either side
    // (a sun from the south or the north), along its whole length.
    const double reach = wall_height / std::tan(kLowestSunDeg * std::numbers::pi / 180.0);
    for (double east : {-6.0, 0.0, 5.9})
        for (double north : {double(wall_y) - reach, double(wall_y), double(wall_y) + reach})
            EXPECT_TRUE(covers(region, east, north)) << "(" << east << ", " << north << ")";
    // The building's region is still inside it, at the same cell size.
    EXPECT_EQ(region.cell_m, building_only.cell_m);
    EXPECT_TRUE(covers(region, building_only.origin_enu_m.x + 0.01, building_only.origin_enu_m.y + 0.01));
    EXPECT_TRUE(covers(region, building_only.origin_enu_m.x + building_only.cell_m * building_only.columns - 0.01,
                       building_only.origin_enu_m.y + building_only.cell_m * building_only.rows - 0.01));
}

TEST(GroundRegion, FlatGroundRipplesAndFarReliefLeaveTheBuildingsRegion) {
    const GroundGrid building_only = gusuku::bake::chooseGroundRegion(building(), kLowestSunDeg, kCellM);
    auto expectBuildingOnly = [&](const TriangleMesh& site, const char* what) {
        const GroundGrid region = gusuku::bake::chooseSiteGroundRegion(building(), site, kLowestSunDeg, kCellM);
        EXPECT_EQ(region.origin_enu_m, building_only.origin_enu_m) << what;
        EXPECT_EQ(region.columns, building_only.columns) << what;
        EXPECT_EQ(region.rows, building_only.rows) << what;
    };
    expectBuildingOnly(flatSite(), "a flat terrace");
    TriangleMesh ripple = flatSite();
    addWall(ripple, -12.0f, 0.1f);  // under kSiteReliefMinHeightM: its shadow is no boundary
    expectBuildingOnly(ripple, "a 0.1 m step");
    TriangleMesh far_wall = flatSite();
    addWall(far_wall, -2.0f - float(gusuku::bake::kSiteReliefSearchM) - 5.0f, 2.5f);  // beyond the search
    expectBuildingOnly(far_wall, "a wall 25 m from the building");
}

}  // namespace
