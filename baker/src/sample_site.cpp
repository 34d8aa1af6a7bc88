#include "gusuku_bake/sample_site.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <nlohmann/json.hpp>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku_bake/sky_model.h"
#include "sample_geometry.h"

namespace gusuku::bake::sample_site {

namespace {

constexpr int kTextureSize = 128;  // small: the bake needs albedo, not detail

// The staircase climbs the terrace's south face, centred on the path to the house's doorway.
constexpr double kStepMinEastM = 0.0;
constexpr double kStepMaxEastM = kStepMinEastM + kStepWidthM;
constexpr double kStepFrontNorthM = kTerraceMinNorthM - (kStepRisers - 1) * kStepTreadM;

// The low wall: an L along the terrace's north edge and the north part of its west edge.
constexpr double kNorthWallMaxEastM = 6.0;
constexpr double kWestWallMinNorthM = 4.0;

bool insideTerrace(double east_m, double north_m) {
    return east_m >= kTerraceMinEastM && east_m <= kTerraceMaxEastM && north_m >= kTerraceMinNorthM &&
           north_m <= kTerraceMaxNorthM;
}

void addTerrain(sample::MeshBuilder& builder, uint32_t grass) {
    const int cells = int(std::lround(2.0 * kTerrainHalfSizeM / kTerrainCellM));
    auto vertex = [](int i, int j) {
        const double east = -kTerrainHalfSizeM + i * kTerrainCellM;
        const double north = -kTerrainHalfSizeM + j * kTerrainCellM;
        return glm::dvec3(east, north, naturalGroundHeight(east, north));
    };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            const glm::dvec3 p00 = vertex(i, j), p10 = vertex(i + 1, j), p11 = vertex(i + 1, j + 1),
                             p01 = vertex(i, j + 1);
            // Cells under the terrace are hidden by it: leave them out (the terrace edges lie on cell edges).
            const glm::dvec3 centre = 0.5 * (p00 + p11);
            if (insideTerrace(centre.x, centre.y)) continue;
            builder.triangle(p00, p10, p11, grass);
            builder.triangle(p00, p11, p01, grass);
        }
}

// One side of the terrace, a retaining wall from the natural ground up to the terrace top, split at the
// terrain's grid lines so that its foot follows the terrain's edge exactly (no gap, no overlap). `along` runs
// with the outside on the right, so the face's normal cross(along, up) points out. Parts of the edge inside
// [skip_from, skip_to] (in the running coordinate) are left out.
void addTerraceSide(sample::MeshBuilder& builder, const glm::dvec2& start, const glm::dvec2& end,
                    uint32_t limestone, double skip_from = 1.0, double skip_to = 0.0) {
    const double length = glm::length(end - start);
    const int segments = int(std::lround(length / kTerrainCellM));
    for (int s = 0; s < segments; ++s) {
        double t0 = double(s) / segments, t1 = double(s + 1) / segments;
        const double a0 = t0 * length, a1 = t1 * length;
        // Clip [a0, a1] against the skipped interval: keep at most the parts on either side.
        std::vector<std::pair<double, double>> kept;
        if (skip_from >= skip_to || a1 <= skip_from || a0 >= skip_to) {
            kept.push_back({a0, a1});
        } else {
            if (a0 < skip_from) kept.push_back({a0, skip_from});
            if (a1 > skip_to) kept.push_back({skip_to, a1});
        }
        const glm::dvec2 g0 = start + (end - start) * t0, g1 = start + (end - start) * t1;
        const double h0 = naturalGroundHeight(g0.x, g0.y), h1 = naturalGroundHeight(g1.x, g1.y);
        for (const auto& [b0, b1] : kept) {
            // The terrain edge between grid vertices is straight: interpolate its height linearly.
            const double f0 = (b0 - a0) / (a1 - a0), f1 = (b1 - a0) / (a1 - a0);
            const glm::dvec2 q0 = g0 + (g1 - g0) * f0, q1 = g0 + (g1 - g0) * f1;
            const double z0 = h0 + (h1 - h0) * f0, z1 = h0 + (h1 - h0) * f1;
            builder.quad({q0.x, q0.y, z0}, {q1.x, q1.y, z1}, {q1.x, q1.y, kTerraceTopM},
                         {q0.x, q0.y, kTerraceTopM}, limestone);
        }
    }
}

void addTerrace(sample::MeshBuilder& builder, uint32_t grass, uint32_t limestone) {
    // The flat top, in 2 m cells.
    constexpr double kTopCellM = 2.0;
    for (double north = kTerraceMinNorthM; north < kTerraceMaxNorthM - 1e-9; north += kTopCellM)
        for (double east = kTerraceMinEastM; east < kTerraceMaxEastM - 1e-9; east += kTopCellM)
            builder.rectZ(kTerraceTopM, east, std::min(east + kTopCellM, kTerraceMaxEastM), north,
                          std::min(north + kTopCellM, kTerraceMaxNorthM), true, grass);
    // South side, with the staircase's span left to the steps; then north, west and east.
    addTerraceSide(builder, {kTerraceMinEastM, kTerraceMinNorthM}, {kTerraceMaxEastM, kTerraceMinNorthM},
                   limestone, kStepMinEastM - kTerraceMinEastM, kStepMaxEastM - kTerraceMinEastM);
    addTerraceSide(builder, {kTerraceMaxEastM, kTerraceMaxNorthM}, {kTerraceMinEastM, kTerraceMaxNorthM},
                   limestone);
    addTerraceSide(builder, {kTerraceMinEastM, kTerraceMaxNorthM}, {kTerraceMinEastM, kTerraceMinNorthM},
                   limestone);
    addTerraceSide(builder, {kTerraceMaxEastM, kTerraceMinNorthM}, {kTerraceMaxEastM, kTerraceMaxNorthM},
                   limestone);
}

void addSteps(sample::MeshBuilder& builder, uint32_t limestone) {
    // Equal risers from the ground in front of the steps to the terrace top; the solid reaches 0.3 m below the
    // lowest ground under it, so the terrain meets its sides with no gap.
    const double centre_east = 0.5 * (kStepMinEastM + kStepMaxEastM);
    const double ground = naturalGroundHeight(centre_east, kStepFrontNorthM);
    double lowest = ground;
    for (double east = kStepMinEastM; east <= kStepMaxEastM + 1e-9; east += 0.5)
        for (double north = kStepFrontNorthM; north <= kTerraceMinNorthM + 1e-9; north += 0.35)
            lowest = std::min(lowest, naturalGroundHeight(east, north));
    const double bottom = lowest - 0.3;
    const double rise = (kTerraceTopM - ground) / kStepRisers;
    auto riser_north = [](int k) { return kTerraceMinNorthM - (kStepRisers - k) * kStepTreadM; };  // k = 1..N
    auto tread_height = [&](int k) { return k >= kStepRisers ? kTerraceTopM : ground + k * rise; };
    for (int k = 1; k <= kStepRisers; ++k) {
        const double riser_bottom = k == 1 ? bottom : tread_height(k - 1);
        builder.rectY(riser_north(k), kStepMinEastM, kStepMaxEastM, riser_bottom, tread_height(k), false,
                      limestone);
        if (k < kStepRisers) {
            builder.rectZ(tread_height(k), kStepMinEastM, kStepMaxEastM, riser_north(k), riser_north(k + 1), true,
                          limestone);
            // The staircase's two sides, one column per tread.
            builder.rectX(kStepMinEastM, riser_north(k), riser_north(k + 1), bottom, tread_height(k), false,
                          limestone);
            builder.rectX(kStepMaxEastM, riser_north(k), riser_north(k + 1), bottom, tread_height(k), true,
                          limestone);
        }
    }
}

void addLowWall(sample::MeshBuilder& builder, uint32_t limestone) {
    const double base = kTerraceTopM, top = kTerraceTopM + kLowWallHeightM;
    const double inner_north = kTerraceMaxNorthM - kLowWallThicknessM;
    const double inner_east = kTerraceMinEastM + kLowWallThicknessM;
    // North arm: x from the terrace's west edge to kNorthWallMaxEastM, y from inner_north to the edge.
    builder.rectZ(top, kTerraceMinEastM, kNorthWallMaxEastM, inner_north, kTerraceMaxNorthM, true, limestone);
    builder.rectY(kTerraceMaxNorthM, kTerraceMinEastM, kNorthWallMaxEastM, base, top, true, limestone);
    builder.rectY(inner_north, inner_east, kNorthWallMaxEastM, base, top, false, limestone);
    builder.rectX(kTerraceMinEastM, inner_north, kTerraceMaxNorthM, base, top, false, limestone);
    builder.rectX(kNorthWallMaxEastM, inner_north, kTerraceMaxNorthM, base, top, true, limestone);
    // West arm, joined to the north arm (no faces between them).
    builder.rectZ(top, kTerraceMinEastM, inner_east, kWestWallMinNorthM, inner_north, true, limestone);
    builder.rectX(kTerraceMinEastM, kWestWallMinNorthM, inner_north, base, top, false, limestone);
    builder.rectX(inner_east, kWestWallMinNorthM, inner_north, base, top, true, limestone);
    builder.rectY(kWestWallMinNorthM, kTerraceMinEastM, inner_east, base, top, false, limestone);
}

// ---- the house ----

// A wall ring of thickness kWallThicknessM: exterior faces from the base to kWallHeightM, interior faces
// from the floor to where the roof's underside meets them, the doorway cut through the front (-y) wall with
// its jambs, lintel and threshold closed. The wall's top is closed by the roof's underside.
void addHouseWalls(sample::MeshBuilder& builder, uint32_t plaster, uint32_t wood) {
    const double xe = kHouseHalfWidthM, ye = kHouseHalfDepthM;
    const double xi = xe - kWallThicknessM, yi = ye - kWallThicknessM;
    const double interior_top = kWallHeightM + kWallThicknessM * std::tan(kRoofPitchDeg * std::numbers::pi / 180.0);
    const double door = 0.5 * kDoorWidthM;
    // Front (-y), exterior and interior, around the doorway.
    builder.rectY(-ye, -xe, -door, 0.0, kWallHeightM, false, plaster);
    builder.rectY(-ye, door, xe, 0.0, kWallHeightM, false, plaster);
    builder.rectY(-ye, -door, door, 0.0, kFloorHeightM, false, plaster);
    builder.rectY(-ye, -door, door, kDoorTopM, kWallHeightM, false, plaster);
    builder.rectY(-yi, -xi, -door, kFloorHeightM, interior_top, true, plaster);
    builder.rectY(-yi, door, xi, kFloorHeightM, interior_top, true, plaster);
    builder.rectY(-yi, -door, door, kDoorTopM, interior_top, true, plaster);
    // The doorway's reveals: jambs face into the opening, the lintel down, the threshold up.
    builder.rectX(-door, -ye, -yi, kFloorHeightM, kDoorTopM, true, wood);
    builder.rectX(door, -ye, -yi, kFloorHeightM, kDoorTopM, false, wood);
    builder.rectZ(kDoorTopM, -door, door, -ye, -yi, false, wood);
    builder.rectZ(kFloorHeightM, -door, door, -ye, -yi, true, wood);
    // Back (+y) and the two sides.
    builder.rectY(ye, -xe, xe, 0.0, kWallHeightM, true, plaster);
    builder.rectY(yi, -xi, xi, kFloorHeightM, interior_top, false, plaster);
    builder.rectX(xe, -ye, ye, 0.0, kWallHeightM, true, plaster);
    builder.rectX(xi, -yi, yi, kFloorHeightM, interior_top, false, plaster);
    builder.rectX(-xe, -ye, ye, 0.0, kWallHeightM, false, plaster);
    builder.rectX(-xi, -yi, yi, kFloorHeightM, interior_top, true, plaster);
    // The raised floor, in 1 m strips so that no triangle is much longer than the room is wide.
    for (double y = -yi; y < yi - 1e-9; y += 1.0)
        builder.rectZ(kFloorHeightM, -xi, xi, y, std::min(y + 1.0, yi), true, wood);
}

// A hip roof of thatch with thickness: an outer surface, an inner one kThatchThicknessM lower, and fascia
// strips closing the eaves. Its underside meets the walls' tops exactly (see addHouseWalls).
void addHouseRoof(sample::MeshBuilder& builder, uint32_t thatch) {
    const double slope = std::tan(kRoofPitchDeg * std::numbers::pi / 180.0);
    const double xr = kHouseHalfWidthM + kEaveOverhangM, yr = kHouseHalfDepthM + kEaveOverhangM;
    // The underside passes through the exterior wall top (kWallHeightM at kEaveOverhangM in from the eave).
    const double eave_top = kWallHeightM + kThatchThicknessM - kEaveOverhangM * slope;
    const double ridge_half = xr - yr;  // a hip roof over a rectangle: ridge along x
    const double ridge_rise = yr * slope;
    for (int layer = 0; layer < 2; ++layer) {
        const bool outer = layer == 0;
        const double z_eave = outer ? eave_top : eave_top - kThatchThicknessM;
        const double z_ridge = z_eave + ridge_rise;
        const glm::dvec3 front_left{-xr, -yr, z_eave}, front_right{xr, -yr, z_eave}, back_right{xr, yr, z_eave},
            back_left{-xr, yr, z_eave}, ridge_left{-ridge_half, 0.0, z_ridge}, ridge_right{ridge_half, 0.0, z_ridge};
        if (outer) {
            builder.quad(front_left, front_right, ridge_right, ridge_left, thatch);
            builder.quad(back_right, back_left, ridge_left, ridge_right, thatch);
            builder.triangle(front_right, back_right, ridge_right, thatch);
            builder.triangle(back_left, front_left, ridge_left, thatch);
        } else {  // the same faces seen from below: reversed winding
            builder.quad(ridge_left, ridge_right, front_right, front_left, thatch);
            builder.quad(ridge_right, ridge_left, back_left, back_right, thatch);
            builder.triangle(ridge_right, back_right, front_right, thatch);
            builder.triangle(ridge_left, front_left, back_left, thatch);
        }
    }
    const double z0 = eave_top - kThatchThicknessM, z1 = eave_top;
    builder.rectY(-yr, -xr, xr, z0, z1, false, thatch);
    builder.rectY(yr, -xr, xr, z0, z1, true, thatch);
    builder.rectX(xr, -yr, yr, z0, z1, true, thatch);
    builder.rectX(-xr, -yr, yr, z0, z1, false, thatch);
}

std::string joinPath(const std::string& directory, const std::string& name) {
    return (std::filesystem::path(directory) / name).string();
}

std::string sunnyPhotoIsoTime() {
    return std::string(kBakeDate) + "T" + kSunnyPhotoLocalTime + ":00" + kUtcOffset;
}

nlohmann::ordered_json siteJson() {
    using nlohmann::ordered_json;
    // The SfM mesh is stored Y-up like any glTF; its transform says so explicitly: a +90 deg turn about east
    // takes glTF (x, y, z) to ENU (x, -z, y).
    const double half_turn = std::sqrt(0.5);
    ordered_json site;
    site["format"] = "gusuku-site/1";
    site["site"] = {{"name", kSiteName},
                    {"latitude_deg", kLatitudeDeg},
                    {"longitude_deg", kLongitudeDeg},
                    {"height_m", kHeightM},
                    {"utc_offset", kUtcOffset}};
    site["sfm_mesh"] = {{"path", "site.glb"},
                        {"scale", 1.0},
                        {"rotation_wxyz", {half_turn, half_turn, 0.0, 0.0}},
                        {"translation_enu_m", {0.0, 0.0, 0.0}}};
    const glm::dvec3 house = houseOriginEnu();
    site["building"] = {{"path", "building.glb"},
                        {"enu_offset_m", {house.x, house.y, house.z}},
                        {"heading_deg", kHouseHeadingDeg},
                        {"scale", 1.0}};
    site["skies"] = {
        {"sunny", {{"path", "sky_sunny.hdr"}, {"north_azimuth_in_image_deg", kSunnyNorthAzimuthInImageDeg}}},
        {"overcast", {{"path", "sky_overcast.hdr"}, {"north_azimuth_in_image_deg", kOvercastNorthAzimuthInImageDeg}}}};
    site["bake"] = {{"date", kBakeDate},
                    {"texels_per_metre", kTexelsPerMetre},
                    {"samples_per_texel", kSamplesPerTexel},
                    {"max_bounces", kMaxBounces},
                    {"seed", kSeed},
                    {"ground_cell_m", kGroundCellM}};
    return site;
}

}  // namespace

double naturalGroundHeight(double east_m, double north_m) {
    return 0.30 * std::sin(0.17 * east_m + 0.5) * std::cos(0.13 * north_m - 0.3) +
           0.22 * std::sin(0.09 * east_m - 0.12 * north_m + 1.1) + 0.08 * std::sin(0.41 * east_m + 0.37 * north_m);
}

TriangleMesh buildSiteMesh() {
    TriangleMesh mesh;
    sample::MeshBuilder builder(mesh);
    builder.setTileSize(2.0);
    const uint32_t grass = builder.addTexturedMaterial("grass", sample::grassTexture(kTextureSize));
    const uint32_t limestone = builder.addTexturedMaterial("limestone", sample::limestoneTexture(kTextureSize));
    addTerrain(builder, grass);
    addTerrace(builder, grass, limestone);
    addSteps(builder, limestone);
    addLowWall(builder, limestone);
    return mesh;
}

TriangleMesh buildHouseMesh() {
    TriangleMesh mesh;
    sample::MeshBuilder builder(mesh);
    builder.setTileSize(1.5);
    const uint32_t plaster = builder.addTexturedMaterial("plaster", sample::plasterTexture(kTextureSize));
    const uint32_t wood = builder.addTexturedMaterial("wood", sample::woodTexture(kTextureSize));
    const uint32_t thatch = builder.addTexturedMaterial("thatch", sample::thatchTexture(kTextureSize));
    addHouseWalls(builder, plaster, wood);
    addHouseRoof(builder, thatch);
    return mesh;
}

glm::dvec3 houseOriginEnu() {
    // The terrace top is flat, so the house's base stands exactly on it.
    return {kHouseEastM, kHouseNorthM, kTerraceTopM};
}

glm::dvec3 sunnyPhotoSunDirection() {
    SunObserver observer;
    observer.latitude_deg = kLatitudeDeg;
    observer.longitude_deg = kLongitudeDeg;
    observer.height_m = kHeightM;
    return computeSunPosition(observer, parseIso8601Utc(sunnyPhotoIsoTime())).direction_enu;
}

std::vector<std::string> writeSampleSite(const std::string& directory) {
    std::filesystem::create_directories(directory);
    std::vector<std::string> written;
    // Both meshes are stored as glTF Y-up; the loaders undo it (site.json's rotation, the building's axis
    // change).
    const glm::dmat4 gltf_from_enu = glm::inverse(enuFromGltfYUp());

    const std::string site_path = joinPath(directory, "site.glb");
    writeGlb(site_path, buildSiteMesh(), gltf_from_enu);
    written.push_back(site_path);

    const std::string building_path = joinPath(directory, "building.glb");
    writeGlb(building_path, buildHouseMesh(), gltf_from_enu);
    written.push_back(building_path);

    ClearSkySpec clear;
    clear.sun_direction = sunnyPhotoSunDirection();
    const std::string sunny_path = joinPath(directory, "sky_sunny.hdr");
    writeHdr(sunny_path, renderClearSky(clear, kSkyWidth, kSkyHeight, kSunnyNorthAzimuthInImageDeg));
    written.push_back(sunny_path);

    const std::string overcast_path = joinPath(directory, "sky_overcast.hdr");
    writeHdr(overcast_path, renderOvercastSky(OvercastSkySpec{}, kSkyWidth, kSkyHeight,
                                              kOvercastNorthAzimuthInImageDeg));
    written.push_back(overcast_path);

    // Last, so that an interrupted run never leaves a site.json naming files that are not there.
    const std::string json_path = joinPath(directory, "site.json");
    const std::string text = siteJson().dump(2) + "\n";
    writeBytesAtomically(json_path, text.data(), text.size());
    written.push_back(json_path);
    return written;
}

}  // namespace gusuku::bake::sample_site
