// The frame on the CPU without a GPU (engine/src/runtime/frame_preparation.h, ground_quads.h): the ground quads
// a frame draws against a brute-force search along each cell's sun ray, and the uniforms, push constants and
// colour-match source against analytic cases (the camera's projection, the slot weights' sums, the rounded sun).

#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <gtest/gtest.h>

#include "frame_preparation.h"
#include "ground_quads.h"

namespace gusuku::runtime_detail {
namespace {

// ---------------------------------------------------------------------------------------------------------------
// Ground quads

// A deterministic pseudo-random sequence (a 64-bit LCG), so the grid is the same on every run.
struct Lcg {
    uint64_t state = 0x9E3779B97F4A7C15ull;
    double next() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) / double(1ull << 53);
    }
};

struct TestGrid {
    GroundGrid grid;
    std::vector<uint8_t> state;
    std::vector<float> height;
};

TestGrid randomGrid(int columns, int rows) {
    TestGrid test;
    test.grid.origin_enu_m = {-4.0, -3.5};
    test.grid.cell_m = 0.5;
    test.grid.columns = columns;
    test.grid.rows = rows;
    Lcg random;
    for (int cell = 0; cell < columns * rows; ++cell) {
        const double draw = random.next();
        test.state.push_back(draw < 0.15 ? kCellNoGround : draw < 0.8 ? kCellGround : kCellGroundChangedByBuilding);
        test.height.push_back(float(0.3 * random.next() - 0.1));
    }
    return test;
}

// Whether the sun ray from `origin` passes through the box, by walking along it in small steps (independent of
// the slab test: no division, no special case for a direction parallel to an axis).
bool rayWalkMeetsBox(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& low,
                     const glm::dvec3& high) {
    constexpr double kStepM = 1e-3, kLengthM = 40.0;
    for (double t = 0.0; t <= kLengthM; t += kStepM) {
        const glm::dvec3 point = origin + t * direction;
        if (point.x >= low.x && point.x <= high.x && point.y >= low.y && point.y <= high.y && point.z >= low.z &&
            point.z <= high.z)
            return true;
    }
    return false;
}

struct Expected {
    std::vector<float> candidate;
    // Triangles by 2 x the quad's first cell (its north-west corner) + 0 for a c b, 1 for b c d.
    std::set<uint32_t> shadow_triangles, other_triangles;
    size_t quads = 0;  // with at least one triangle
};

Expected bruteForce(const TestGrid& test, const glm::dvec3& building_min, const glm::dvec3& building_max,
                    bool include_baked_changes, bool sun_shines, const glm::dvec3& sun) {
    const int columns = test.grid.columns, rows = test.grid.rows;
    const double margin = 2.0 * test.grid.cell_m + 0.25;  // the stated margin: two cells and a quarter metre
    Expected expected;
    std::vector<bool> marked(size_t(columns) * rows);
    for (int row = 0; row < rows; ++row)
        for (int column = 0; column < columns; ++column) {
            const size_t cell = size_t(row) * columns + column;
            // Row 0 is the north edge: its centre is half a cell below the grid's north edge.
            const glm::dvec3 centre(test.grid.origin_enu_m.x + test.grid.cell_m * (column + 0.5),
                                    test.grid.origin_enu_m.y + test.grid.cell_m * rows - test.grid.cell_m * (row + 0.5),
                                    test.height[cell]);
            const bool candidate = sun_shines && test.state[cell] != kCellNoGround &&
                                   rayWalkMeetsBox(centre, sun, building_min - margin, building_max + margin);
            expected.candidate.push_back(candidate ? 1.0f : 0.0f);
            marked[cell] = candidate || (include_baked_changes && test.state[cell] == kCellGroundChangedByBuilding);
        }
    for (int row = 0; row + 1 < rows; ++row)
        for (int column = 0; column + 1 < columns; ++column) {
            const uint32_t a = uint32_t(row * columns + column);
            const uint32_t corners[4] = {a, a + 1, a + uint32_t(columns), a + uint32_t(columns) + 1};
            bool any_candidate = false;
            for (uint32_t corner : corners) any_candidate = any_candidate || expected.candidate[corner] > 0.0f;
            // A triangle is drawn when one of its own three corners is marked; its quad's kind is the quad's.
            const bool first = marked[corners[0]] || marked[corners[1]] || marked[corners[2]];
            const bool second = marked[corners[1]] || marked[corners[2]] || marked[corners[3]];
            std::set<uint32_t>& kind = any_candidate ? expected.shadow_triangles : expected.other_triangles;
            if (first) kind.insert(2 * a);
            if (second) kind.insert(2 * a + 1);
            expected.quads += (first || second) ? 1 : 0;
        }
    return expected;
}

void expectSelectionMatchesBruteForce(const glm::dvec3& sun, bool include_baked_changes, bool sun_shines) {
    const TestGrid test = randomGrid(17, 13);
    const glm::dvec3 building_min(-1.0, -0.7, 0.0), building_max(0.6, 0.9, 3.0);
    const size_t cells = test.state.size();
    const size_t quads = size_t(test.grid.columns - 1) * size_t(test.grid.rows - 1);
    std::vector<uint8_t> marked(cells, 7);
    std::vector<float> candidate(cells, -1.0f);
    std::vector<uint32_t> indices(quads * 6, 0xFFFFFFFFu);
    const GroundQuadSelection selection =
        selectGroundQuads({test.grid, test.state, test.height}, building_min, building_max, include_baked_changes,
                          sun_shines, sun, marked, candidate, indices);
    const Expected expected = bruteForce(test, building_min, building_max, include_baked_changes, sun_shines, sun);
    // The case must exercise both kinds: quads the shadow may reach (with sun), and the others.
    EXPECT_EQ(expected.shadow_triangles.empty(), !sun_shines);
    if (include_baked_changes) {
        EXPECT_FALSE(expected.other_triangles.empty());
    }
    // ... and quads drawn whole beside quads of which one triangle is left out.
    if (sun_shines || include_baked_changes) {
        EXPECT_LT(expected.shadow_triangles.size() + expected.other_triangles.size(), 2 * expected.quads);
    }

    EXPECT_EQ(candidate, expected.candidate);
    ASSERT_EQ(selection.shadow_index_count, 3 * expected.shadow_triangles.size());
    ASSERT_EQ(selection.index_count, 3 * (expected.shadow_triangles.size() + expected.other_triangles.size()));
    EXPECT_EQ(selection.quads, expected.quads);
    std::set<uint32_t> shadow_triangles, other_triangles;
    const uint32_t columns = uint32_t(test.grid.columns);
    for (uint32_t index = 0; index < selection.index_count; index += 3) {
        // Each a triangle of a quad between four neighbouring cell centres a b / c d: a c b, or b c d.
        const bool second = indices[index + 2] == indices[index + 1] + 1;
        const uint32_t a = second ? indices[index] - 1 : indices[index], b = a + 1, c = a + columns, d = c + 1;
        const uint32_t expected_triangle[2][3] = {{a, c, b}, {b, c, d}};
        for (int corner = 0; corner < 3; ++corner)
            EXPECT_EQ(indices[index + corner], expected_triangle[second][corner]);
        EXPECT_TRUE((index < selection.shadow_index_count ? shadow_triangles : other_triangles)
                        .insert(2 * a + (second ? 1 : 0))
                        .second)
            << "triangle " << index / 3 << " drawn twice";
    }
    EXPECT_EQ(shadow_triangles, expected.shadow_triangles);
    EXPECT_EQ(other_triangles, expected.other_triangles);
    for (size_t index = selection.index_count; index < indices.size(); ++index)
        EXPECT_EQ(indices[index], 0xFFFFFFFFu) << "written past the quads drawn";
}

TEST(GroundQuadSelection, MatchesABruteForceWalkAlongEachCellsSunRay) {
    const double elevations_deg[] = {12.0, 35.0, 70.0};
    const double azimuths_deg[] = {0.0, 90.0, 127.0, 250.0};  // 0 and 90: a direction with a zero component
    for (double elevation_deg : elevations_deg)
        for (double azimuth_deg : azimuths_deg) {
            const double e = elevation_deg * std::numbers::pi / 180.0, a = azimuth_deg * std::numbers::pi / 180.0;
            const glm::dvec3 sun(std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e));
            SCOPED_TRACE(testing::Message() << "elevation " << elevation_deg << ", azimuth " << azimuth_deg);
            expectSelectionMatchesBruteForce(sun, true, true);
            expectSelectionMatchesBruteForce(sun, false, true);
        }
}

TEST(GroundQuadSelection, WithoutSunDrawsOnlyTheBakedChanges) {
    expectSelectionMatchesBruteForce(glm::dvec3(0.0, 0.0, 1.0), true, false);
    expectSelectionMatchesBruteForce(glm::dvec3(0.0, 0.0, 1.0), false, false);  // nothing at all
}

TEST(GroundQuadSelection, DrawsNothingForAGridWithoutQuadsOrMismatchedCells) {
    const TestGrid test = randomGrid(5, 4);
    std::vector<uint8_t> marked(test.state.size());
    std::vector<float> candidate(test.state.size());
    std::vector<uint32_t> indices(4 * 3 * 6);
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.2, 0.3, 1.0));
    GroundQuadSelection selection = selectGroundQuads({test.grid, test.state, test.height}, glm::dvec3(-1.0),
                                                      glm::dvec3(1.0), true, true, sun, marked, candidate, {});
    EXPECT_EQ(selection.index_count, 0u);
    const std::vector<uint8_t> too_few(test.state.begin(), test.state.end() - 1);
    selection = selectGroundQuads({test.grid, too_few, test.height}, glm::dvec3(-1.0), glm::dvec3(1.0), true, true,
                                  sun, marked, candidate, indices);
    EXPECT_EQ(selection.index_count, 0u);
}

TEST(GroundQuadSelection, RayMeetsBoxInAnalyticCases) {
    const glm::dvec3 low(0.0), high(1.0);
    EXPECT_TRUE(rayMeetsBox(glm::dvec3(0.5), glm::dvec3(0.0, 0.0, 1.0), low, high));            // starts inside
    EXPECT_TRUE(rayMeetsBox(glm::dvec3(0.5, 0.5, -2.0), glm::dvec3(0.0, 0.0, 1.0), low, high));  // straight up into it
    EXPECT_FALSE(rayMeetsBox(glm::dvec3(0.5, 0.5, 2.0), glm::dvec3(0.0, 0.0, 1.0), low, high));  // behind the ray
    EXPECT_FALSE(rayMeetsBox(glm::dvec3(1.5, 0.5, -2.0), glm::dvec3(0.0, 0.0, 1.0), low, high));  // parallel, beside
    // Diagonal through a corner region: from (-1, -1, -1) along (1, 1, 1) passes the box's diagonal.
    EXPECT_TRUE(rayMeetsBox(glm::dvec3(-1.0), glm::normalize(glm::dvec3(1.0)), low, high));
    // The same line shifted by 1.2 along x misses: at every t one coordinate is outside [0, 1].
    EXPECT_FALSE(rayMeetsBox(glm::dvec3(0.2, -1.0, -1.0), glm::normalize(glm::dvec3(1.0)), low, high));
}

// ---------------------------------------------------------------------------------------------------------------
// The frame's light, uniforms and push constants

FrameLighting sunnyLighting() {
    FrameLighting lighting;
    lighting.sun.azimuth_deg = 47.4;
    lighting.sun.apparent_elevation_deg = 32.6;
    const double e = 32.6 * std::numbers::pi / 180.0, a = 47.4 * std::numbers::pi / 180.0;
    lighting.sun.direction_enu = glm::dvec3(std::cos(e) * std::sin(a), std::cos(e) * std::cos(a), std::sin(e));
    lighting.sun.above_horizon = true;
    lighting.sun_irradiance_rgb = glm::dvec3(700.0, 680.0, 650.0);
    lighting.slot_a = 2;
    lighting.slot_b = 0;
    lighting.slot_b_weight = 0.25f;
    lighting.sunny_weight = 0.8f;
    lighting.overcast_slot = 3;
    lighting.overcast_weight = 0.2f;
    return lighting;
}

TEST(FramePreparation, ShadowSunIsTheSunRoundedToWholeSteps) {
    const FrameLighting lighting = sunnyLighting();
    EXPECT_EQ(shadowSunDirectionFor(lighting.sun, 0.0f), lighting.sun.direction_enu);  // no step: the sun itself
    // 5 degree steps: azimuth 47.4 -> 45, elevation 32.6 -> 35.
    const glm::dvec3 rounded = shadowSunDirectionFor(lighting.sun, 5.0f);
    const double e = 35.0 * std::numbers::pi / 180.0, a = 45.0 * std::numbers::pi / 180.0;
    EXPECT_NEAR(rounded.x, std::cos(e) * std::sin(a), 1e-12);
    EXPECT_NEAR(rounded.y, std::cos(e) * std::cos(a), 1e-12);
    EXPECT_NEAR(rounded.z, std::sin(e), 1e-12);
    EXPECT_NEAR(glm::length(rounded), 1.0, 1e-12);
}

TEST(FramePreparation, SlotWeightsSplitTheSunnyWeightAndKeepTheOvercastOne) {
    const SlotBlend blend = slotBlendFor(sunnyLighting());
    EXPECT_EQ(blend.slots[0], 2);
    EXPECT_EQ(blend.slots[1], 0);
    EXPECT_EQ(blend.slots[2], 3);
    EXPECT_FLOAT_EQ(blend.weights[0], 0.8f * 0.75f);
    EXPECT_FLOAT_EQ(blend.weights[1], 0.8f * 0.25f);
    EXPECT_FLOAT_EQ(blend.weights[0] + blend.weights[1], 0.8f);  // the sunny blend's weight, split
    EXPECT_FLOAT_EQ(blend.weights[2], 0.2f);
    FrameLighting night;  // no slot at all: every weight 0
    const SlotBlend none = slotBlendFor(night);
    EXPECT_EQ(none.weights[0] + none.weights[1] + none.weights[2], 0.0f);
}

TEST(FramePreparation, DirectOnlyAmbientIsTheWeightedMeanIndirect) {
    const std::vector<glm::vec3> means = {{1.0f, 2.0f, 3.0f}, {10.0f, 10.0f, 10.0f}, glm::vec3(0.0f), {4.0f, 0.0f, 8.0f}};
    const SlotBlend blend = slotBlendFor(sunnyLighting());  // slots 2, 0, 3 at 0.6, 0.2, 0.2
    const glm::dvec3 ambient = blendedMeanIndirect(blend, means);
    EXPECT_NEAR(ambient.x, 0.6 * 0.0 + 0.2 * 1.0 + 0.2 * 4.0, 1e-6);
    EXPECT_NEAR(ambient.y, 0.2 * 2.0, 1e-6);
    EXPECT_NEAR(ambient.z, 0.2 * 3.0 + 0.2 * 8.0, 1e-6);
}

TEST(FramePreparation, FlagsFollowTheModeTheSunAndTheOccluder) {
    const FrameLighting sunny = sunnyLighting();
    FrameFlags flags = frameFlagsFor(RenderMode::kProposed, sunny, true);
    EXPECT_TRUE(flags.sun_shines && flags.site_shadows && !flags.direct_only);
    EXPECT_FALSE(frameFlagsFor(RenderMode::kProposed, sunny, false).site_shadows);  // no occluder
    flags = frameFlagsFor(RenderMode::kDirectOnly, sunny, true);
    EXPECT_TRUE(flags.direct_only && flags.sun_shines && !flags.site_shadows);
    FrameLighting below = sunny;
    below.sun.above_horizon = false;
    EXPECT_FALSE(frameFlagsFor(RenderMode::kProposed, below, true).sun_shines);
    FrameLighting dark = sunny;  // above the horizon, but no irradiance (full cloud)
    dark.sun_irradiance_rgb = glm::dvec3(0.0);
    EXPECT_FALSE(frameFlagsFor(RenderMode::kProposed, dark, true).sun_shines);

    FrameInput frame;
    frame.ground_ratio = false;
    EXPECT_FALSE(groundQuadsWanted(frame, frameFlagsFor(RenderMode::kProposed, sunny, true)));
    EXPECT_TRUE(groundQuadsWanted(frame, frameFlagsFor(RenderMode::kDirectOnly, sunny, true)));  // its darkening
    EXPECT_FALSE(groundQuadsWanted(frame, frameFlagsFor(RenderMode::kDirectOnly, below, true)));
}

TEST(FramePreparation, ObserverIsTheFixOrElseTheSite) {
    BakeSetSite site;
    site.latitude_deg = 35.0;
    site.longitude_deg = 139.0;
    site.height_m = 40.0;
    FrameInput frame;
    SunObserver observer = frameObserverFor(frame, site);
    EXPECT_EQ(observer.latitude_deg, 35.0);
    EXPECT_EQ(observer.longitude_deg, 139.0);
    EXPECT_EQ(observer.height_m, 40.0);
    frame.position = GeoPosition{-33.9, 151.2, 5.0};
    observer = frameObserverFor(frame, site);
    EXPECT_EQ(observer.latitude_deg, -33.9);
    EXPECT_EQ(observer.longitude_deg, 151.2);
    EXPECT_EQ(observer.height_m, 5.0);
}

struct UniformsCase {
    FrameInput frame;
    FrameLighting lighting = sunnyLighting();
    ShadowFit fit;
    RuntimeOptions options;
    std::vector<glm::vec3> means = {{1.0f, 1.0f, 1.0f}, glm::vec3(0.0f), {2.0f, 2.0f, 2.0f}, {3.0f, 3.0f, 3.0f}};
    FrameScene scene;

    UniformsCase() {
        frame.intrinsics = CameraIntrinsics::fromFieldOfView(640, 480, 60.0);
        frame.pose = CameraPose::lookingAt(glm::dvec3(3.0, -12.0, 1.6), glm::dvec3(0.0, 0.0, 1.0));
        frame.exposure = 0.0125f;
        fit.texel_size_m = 0.02;
        fit.depth_range_m = 40.0;
        fit.enu_to_clip = glm::dmat4(0.5);
        options.shadow_map_size = 2048;
        options.shadow_bias_texels = 1.5f;
        options.shadow_pcf_radius = 2;
        options.direct_only_ambient_fraction = 0.5f;
        options.direct_only_shadow_darkening = 0.7f;
        scene.scene_radius_m = 30.0;  // far plane 4 x 30 m + the camera's distance, above the floor
        scene.irradiance_scale = 2.5f;
        scene.slot_mean_indirect = means;
        scene.ground_grid.origin_enu_m = {-8.0, -6.0};
        scene.ground_grid.cell_m = 0.25;
        scene.ground_grid.columns = 64;
        scene.ground_grid.rows = 48;
    }
    shader_interface::FrameUniforms uniforms(RenderMode mode) const {
        const FrameFlags flags = frameFlagsFor(mode, lighting, true);
        return frameUniformsFor(frame, lighting, flags, slotBlendFor(lighting), fit, options, scene);
    }
};

TEST(FramePreparation, UniformsCarryEachNamedQuantity) {
    const UniformsCase c;
    const shader_interface::FrameUniforms u = c.uniforms(RenderMode::kProposed);
    EXPECT_EQ(u.exposure, 0.0125f);
    EXPECT_EQ(u.sun_shines, 1u);
    EXPECT_EQ(u.site_shadows, 1u);
    EXPECT_EQ(u.render_mode, RUNTIME_RENDER_MODE_PROPOSED);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(u.camera_position[axis], float(c.frame.pose.position_enu[axis]));
        EXPECT_EQ(u.sun_direction[axis], float(c.lighting.sun.direction_enu[axis]));
        EXPECT_EQ(u.sun_irradiance[axis], float(c.lighting.sun_irradiance_rgb[axis]));
    }
    EXPECT_EQ(u.slot_layers[0], 2.0f);
    EXPECT_EQ(u.slot_layers[1], 0.0f);
    EXPECT_EQ(u.slot_layers[2], 3.0f);
    EXPECT_FLOAT_EQ(u.slot_weights[0] + u.slot_weights[1] + u.slot_weights[2], 1.0f);
    EXPECT_EQ(u.irradiance_scale, 2.5f);
    // Ambient: (0.6 x 2 + 0.2 x 1 + 0.2 x 3) x the fraction 0.5, grey.
    EXPECT_NEAR(u.direct_only_ambient[0], (0.6 * 2.0 + 0.2 * 1.0 + 0.2 * 3.0) * 0.5, 1e-6);
    EXPECT_EQ(u.direct_only_shadow_darkening, 0.7f);
    EXPECT_EQ(u.shadow_texel_uv, 1.0f / 2048.0f);
    EXPECT_NEAR(u.shadow_depth_bias, 1.5 * 0.02 / 40.0, 1e-9);  // 1.5 texels of 2 cm over a 40 m depth range
    EXPECT_EQ(u.shadow_pcf_radius, 2.0f);
    EXPECT_EQ(u.enu_to_shadow_clip.columns[0][0], 0.5f);
    EXPECT_EQ(u.enu_to_shadow_clip.columns[3][3], 0.5f);
    EXPECT_EQ(u.pass_through_threshold, 0.5f / 255.0f);
    EXPECT_EQ(u.ground_origin_east_m, -8.0f);
    EXPECT_EQ(u.ground_origin_north_m, -6.0f);
    EXPECT_EQ(u.ground_cell_m, 0.25f);
    EXPECT_EQ(u.ground_columns, 64);
    EXPECT_EQ(u.ground_rows, 48);
    EXPECT_GT(u.ground_pull_m, 0.0f);

    const shader_interface::FrameUniforms direct = c.uniforms(RenderMode::kDirectOnly);
    EXPECT_EQ(direct.render_mode, RUNTIME_RENDER_MODE_DIRECT_ONLY);
    EXPECT_EQ(direct.site_shadows, 0u);
    UniformsCase no_grid;
    no_grid.scene.ground_grid.columns = no_grid.scene.ground_grid.rows = 0;  // the shader divides by columns
    const shader_interface::FrameUniforms empty = no_grid.uniforms(RenderMode::kProposed);
    EXPECT_EQ(empty.ground_columns, 1);
    EXPECT_EQ(empty.ground_rows, 1);
}

// The uniforms' camera matrix maps a point to the pixel Runtime::projectToPixel gives (x_ndc = 2 u / width - 1,
// y_ndc = 2 v / height - 1), with depth 0 at the near plane and 1 at the far plane.
TEST(FramePreparation, CameraMatrixProjectsLikeTheCameraConvention) {
    const UniformsCase c;
    const shader_interface::FrameUniforms u = c.uniforms(RenderMode::kProposed);
    glm::mat4 clip_from_enu;
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) clip_from_enu[column][row] = u.enu_to_clip.columns[column][row];
    const glm::dvec3 points[] = {{0.0, 0.0, 1.0}, {2.0, 1.0, 3.0}, {-1.5, 2.0, 0.2}};
    for (const glm::dvec3& point : points) {
        const std::optional<glm::dvec2> pixel = Runtime::projectToPixel(c.frame.intrinsics, c.frame.pose, point);
        ASSERT_TRUE(pixel.has_value());
        const glm::vec4 clip = clip_from_enu * glm::vec4(glm::vec3(point), 1.0f);
        EXPECT_NEAR((clip.x / clip.w + 1.0) * 0.5 * 640.0, pixel->x, 1e-2);
        EXPECT_NEAR((clip.y / clip.w + 1.0) * 0.5 * 480.0, pixel->y, 1e-2);
        EXPECT_GT(clip.z / clip.w, 0.0f);
        EXPECT_LT(clip.z / clip.w, 1.0f);
    }
    const glm::dvec3 forward = c.frame.pose.camera_to_enu[2];
    const double far_m = cameraFarPlaneM(30.0, c.frame.pose.position_enu);
    EXPECT_NEAR(far_m, 4.0 * 30.0 + glm::length(c.frame.pose.position_enu), 1e-12);
    EXPECT_EQ(cameraFarPlaneM(0.1, glm::dvec3(1.0, 0.0, 0.0)), 100.0);  // the floor for a tiny scene
    auto depthAt = [&](double distance_m) {
        const glm::vec4 clip =
            clip_from_enu * glm::vec4(glm::vec3(c.frame.pose.position_enu + distance_m * forward), 1.0f);
        return clip.z / clip.w;
    };
    EXPECT_NEAR(depthAt(kNearPlaneM), 0.0, 1e-4);
    EXPECT_NEAR(depthAt(far_m), 1.0, 1e-4);
}

TEST(FramePreparation, DepthPushesCarryTheirViewsAndPull) {
    const UniformsCase c;
    const shader_interface::FrameUniforms u = c.uniforms(RenderMode::kProposed);
    const shader_interface::DepthOnlyPushConstants shadow = shadowPushFor(c.fit);
    EXPECT_EQ(shadow.pull_m, 0.0f);  // the shadow maps are not pulled
    EXPECT_EQ(shadow.enu_to_clip.columns[1][1], 0.5f);
    EXPECT_EQ(shadow.enu_to_clip.columns[1][0], 0.0f);
    const shader_interface::DepthOnlyPushConstants occluder = occluderPushFor(u);
    EXPECT_LT(occluder.pull_m, 0.0f);  // away from the camera
    EXPECT_EQ(occluder.pull_m, -kOccluderPushM);
    for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(occluder.pull_origin[axis], u.camera_position[axis]);
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row)
            EXPECT_EQ(occluder.enu_to_clip.columns[column][row], u.enu_to_clip.columns[column][row]);
}

TEST(FramePreparation, ColourSourceIsOffInDirectOnlyAndAtNight) {
    LabStatistics same;
    same.mean = {55.0f, 3.0f, -7.0f};
    same.standard_deviation = {12.0f, 4.0f, 5.0f};
    const std::vector<LabStatistics> slots(4, same);
    const SlotBlend blend = slotBlendFor(sunnyLighting());

    ColourSource source = colourSourceFor(ColourMatchMode::kPaper, false, blend, slots);
    EXPECT_EQ(source.mode, ColourMatchMode::kPaper);
    ASSERT_TRUE(source.statistics.has_value());
    for (int channel = 0; channel < 3; ++channel) {  // a blend of equal statistics is those statistics
        EXPECT_NEAR(source.statistics->mean[channel], same.mean[channel], 1e-4);
        EXPECT_NEAR(source.statistics->standard_deviation[channel], same.standard_deviation[channel], 1e-4);
    }
    EXPECT_EQ(colourSourceFor(ColourMatchMode::kPreserve, true, blend, slots).mode, ColourMatchMode::kOff);

    const ColourSource night = colourSourceFor(ColourMatchMode::kPaper, false, SlotBlend{}, slots);
    EXPECT_EQ(night.mode, ColourMatchMode::kOff);
    EXPECT_FALSE(night.statistics.has_value());  // the caller keeps its last statistics
}

TEST(FramePreparation, GroundMatchViewIsTheFramesCameraAndLight) {
    const UniformsCase c;
    const SlotBlend blend = slotBlendFor(c.lighting);
    const GroundMatchView view = groundMatchViewFor(c.frame, c.lighting, true, blend);
    EXPECT_EQ(view.fx, c.frame.intrinsics.fx);
    EXPECT_EQ(view.cy, c.frame.intrinsics.cy);
    EXPECT_EQ(view.camera_position_enu, c.frame.pose.position_enu);
    EXPECT_EQ(view.camera_to_enu, c.frame.pose.camera_to_enu);
    EXPECT_EQ(view.sun_direction_enu, c.lighting.sun.direction_enu);
    EXPECT_TRUE(view.sun_shines);
    EXPECT_EQ(view.exposure, double(c.frame.exposure));
    for (int index = 0; index < 3; ++index) {
        EXPECT_EQ(view.slots[index], blend.slots[index]);
        EXPECT_EQ(view.weights[index], blend.weights[index]);
    }
}

TEST(FramePreparation, FrameInfoReportsTheSunAndSlots) {
    const FrameLighting lighting = sunnyLighting();
    const FrameInfo info = frameInfoFor(lighting);
    EXPECT_EQ(info.sun_azimuth_deg, 47.4);
    EXPECT_EQ(info.sun_apparent_elevation_deg, 32.6);
    EXPECT_TRUE(info.sun_above_horizon);
    EXPECT_EQ(info.slot_a, 2);
    EXPECT_EQ(info.slot_b, 0);
    EXPECT_EQ(info.slot_b_weight, 0.25f);
    EXPECT_EQ(info.overcast_slot, 3);
    EXPECT_EQ(info.overcast_weight, 0.2f);
    EXPECT_EQ(info.ground_quads_drawn, 0u);  // the caller's to fill
}

}  // namespace
}  // namespace gusuku::runtime_detail
