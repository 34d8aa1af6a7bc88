// The building's sun horizons at run time (gusuku/formats/sun_horizon.h, issue 44 item 1) on a roof of round tiles
// a few centimetres deep, on lavapipe with validation on, against a CPU ray tracer of the runtime's light model with
// the exact sun visibility over the sun's disc (the scene's own geometry, the baker's BVH):
//   - a mono-pitch roof (30 degrees, 3 m along the slope, 4 m wide) of rows of round tiles running down the slope,
//     a sine profile 5 cm deep every 25 cm across it, over a ground grid 50 m wide (the shadow map's texels 5 cm),
//     under a morning sun 10 to 25 degrees high, the roof turned so the sun comes from several azimuths against
//     the tile rows: the mean over the roof's flat pixels within 5 % of the truth with the horizons (up to 15 %
//     too bright without them, as the shadow map alone drew it);
//   - the same roof without tiles and with its horizons: no acne (every pixel the same code but for rounding).
// With GUSUKU_SUN_HORIZON_SWEEP=1: every elevation and azimuth, and the proposed frame's time with and without
// horizons (the frame's cost: two gathers a sunlit fragment). With GUSUKU_SUN_HORIZON_FRAME_BAKESET=DIR: that bake
// set's proposed frame at the runtime's defaults (1280x720) with its horizons against the same set with a 1 x 1
// open horizon (the path before horizons: no gathers, no shifted shadow test), fenced frames interleaved.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/formats/sun_horizon.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/mesh.h"
#include "gusuku/maths/sun.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/sun_horizon_bake.h"

namespace gusuku {
namespace {

using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr double kFocal = 300.0;
constexpr float kExposure = 0.5f;
constexpr uint8_t kCameraCode = 150;
constexpr int kSunDiscSamples = 8;
constexpr double kPitchDeg = 30.0, kSlopeM = 3.0, kRoofWidthM = 4.0, kEaveHeightM = 2.0, kSlabM = 0.05;
constexpr int kSegmentsPerPeriod = 16;
constexpr int kHorizonResolution = 128;  // 2.3 cm along the slope, 3.0 cm across: 8 texels a tile row

testing::SyntheticBakeSetOptions sceneOptions() {
    testing::SyntheticBakeSetOptions options;
    // A 50 m ground grid: the shadow map's texels about 5 cm at 1024, as over a site whose grid the low sun's
    // shadow sizes (on a 30 m grid, 3 cm texels, the map alone is 3-4 % too bright here; the horizons as close).
    options.grid_half_m = 25.0;
    return options;
}

struct TileRoof {
    double depth_m = 0.05;    // crest over groove
    double period_m = 0.25;   // one round tile and its groove
    double rotation_deg = 0;  // about the vertical through the origin, counter-clockwise seen from above
};

// The roof as a mesh: the tiles' surface first (flat-shaded strips down the slope, lightmap uv1 the roof's plane),
// then a slab under it (uv1 in a corner no texel covers: open horizons). tile_triangles: how many come first.
struct RoofMesh {
    TriangleMesh mesh;
    size_t tile_triangles = 0;
};

RoofMesh tileRoof(const TileRoof& roof) {
    const double pitch = glm::radians(kPitchDeg), turn = glm::radians(roof.rotation_deg);
    auto place = [&](const glm::dvec3& p) {
        return glm::vec3(float(std::cos(turn) * p.x - std::sin(turn) * p.y),
                         float(std::sin(turn) * p.x + std::cos(turn) * p.y), float(p.z));
    };
    const glm::dvec3 down(std::cos(pitch), 0.0, -std::sin(pitch)), across(0.0, 1.0, 0.0);
    const glm::dvec3 normal = glm::cross(down, across);
    const glm::dvec3 ridge(-0.5 * kSlopeM * std::cos(pitch), -0.5 * kRoofWidthM,
                           kEaveHeightM + kSlopeM * std::sin(pitch));
    RoofMesh out;
    TriangleMesh& mesh = out.mesh;
    mesh.materials.resize(1);
    mesh.has_uv1 = true;
    auto triangle = [&](const glm::dvec3 (&corners)[3], const glm::vec2 (&uv)[3]) {
        const glm::vec3 a = place(corners[0]), b = place(corners[1]), c = place(corners[2]);
        const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            mesh.indices.push_back(uint32_t(mesh.positions.size()));
            mesh.positions.push_back(k == 0 ? a : k == 1 ? b : c);
            mesh.normals.push_back(face);
            mesh.uv0.emplace_back(0.0f);
            mesh.uv1.push_back(uv[k]);
        }
        mesh.triangle_material.push_back(0);
    };
    const double pi = 3.14159265358979323846;
    const int columns = int(std::lround(kRoofWidthM / roof.period_m)) * kSegmentsPerPeriod;
    auto surface = [&](double s, double w) {
        const double height = 0.5 * roof.depth_m * (1.0 - std::cos(2.0 * pi * w / roof.period_m));
        return ridge + s * down + w * across + height * normal;
    };
    auto uv = [&](double s, double w) {
        return glm::vec2(float(0.02 + 0.96 * s / kSlopeM), float(0.02 + 0.96 * w / kRoofWidthM));
    };
    for (int column = 0; column < columns; ++column) {
        const double w0 = kRoofWidthM * column / columns, w1 = kRoofWidthM * (column + 1) / columns;
        triangle({surface(0, w0), surface(kSlopeM, w0), surface(kSlopeM, w1)},
                 {uv(0, w0), uv(kSlopeM, w0), uv(kSlopeM, w1)});
        triangle({surface(0, w0), surface(kSlopeM, w1), surface(0, w1)}, {uv(0, w0), uv(kSlopeM, w1), uv(0, w1)});
    }
    out.tile_triangles = mesh.triangleCount();
    // The slab: a closed box 1 mm under the roof's plane (so that a flat roof's surface never ties with it), so the
    // roof casts a proper shadow.
    const glm::dvec3 origin = ridge - (kSlabM + 0.001) * normal, a = kSlopeM * down, b = kRoofWidthM * across;
    const glm::dvec3 c = kSlabM * normal;
    auto corner = [&](int i) { return origin + ((i & 1) ? a : glm::dvec3(0)) + ((i & 2) ? b : glm::dvec3(0)) +
                                      ((i & 4) ? c : glm::dvec3(0)); };
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    const glm::vec2 unused(0.999f);
    for (const auto& face : faces) {
        triangle({corner(face[0]), corner(face[1]), corner(face[2])}, {unused, unused, unused});
        triangle({corner(face[0]), corner(face[2]), corner(face[3])}, {unused, unused, unused});
    }
    return out;
}

// The synthetic bake set (constant E_ind, flat lit ground) with this roof as its building, and its horizons
// baked as gusuku-bake bakes them, or none.
BakeSetData bakeSetWithRoof(const RoofMesh& roof, const bake::Bvh& bvh, bool horizons) {
    BakeSetData data = testing::makeSyntheticBakeSet(sceneOptions());
    BakeSetMesh mesh;
    mesh.positions = roof.mesh.positions;
    mesh.normals = roof.mesh.normals;
    mesh.uv0 = roof.mesh.uv0;
    mesh.uv1 = roof.mesh.uv1;
    mesh.indices = roof.mesh.indices;
    mesh.triangle_material = roof.mesh.triangle_material;
    mesh.materials = data.building.materials;
    data.building = std::move(mesh);
    if (horizons) {
        TriangleMesh tiles = roof.mesh;  // the tiles' surface alone holds lightmap texels
        tiles.indices.resize(3 * roof.tile_triangles);
        tiles.triangle_material.resize(roof.tile_triangles);
        const std::vector<bake::LightmapTexel> texels = bake::rasterizeLightmapTexels(tiles, kHorizonResolution);
        data.building_sun_horizon = bake::bakeSunHorizons(bvh, texels, kHorizonResolution, {});
        data.manifest.building.sun_horizon = kSunHorizonFile;
    }
    return data;
}

double utcAtElevation(const BakeSetData& bake_set, double elevation_deg) {
    SunObserver observer;
    observer.latitude_deg = bake_set.manifest.site.latitude_deg;
    observer.longitude_deg = bake_set.manifest.site.longitude_deg;
    observer.height_m = bake_set.manifest.site.height_m;
    for (double utc = syntheticLocalTime(4, 0);; utc += 30.0)
        if (computeSunPosition(observer, utc).apparent_elevation_deg >= elevation_deg) return utc;
}

struct Rendered {
    std::vector<uint8_t> pixels;
    FrameInfo info;
    double seconds = 0.0;
};

std::unique_ptr<Runtime> openRuntime(const GpuDevice& device, const BakeSetData& bake_set) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    return Runtime::open(device, bake_set, options);
}

Rendered render(Runtime& runtime, const CameraPose& pose, double utc, int frames = 1) {
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, kCameraCode);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {kFocal, kFocal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = pose;
    frame.utc_unix_seconds = utc;
    frame.weather = Weather::sunny();
    frame.exposure = kExposure;
    frame.colour_match = ColourMatch::kOff;
    frame.mode = RenderMode::kProposed;
    Rendered rendered;
    rendered.pixels.resize(camera.size());
    rendered.info = runtime.renderFrame(frame, rendered.pixels.data());
    const auto start = std::chrono::steady_clock::now();
    for (int repeat = 1; repeat < frames; ++repeat) runtime.renderFrame(frame, rendered.pixels.data());
    rendered.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                       std::max(frames - 1, 1);
    return rendered;
}

double linearAt(const std::vector<uint8_t>& pixels, uint32_t x, uint32_t y) {
    return srgbDecode(pixels[(size_t(y) * kWidth + x) * 4 + 1] / 255.0);
}

// The camera looks at the roof's face from the east, above, turned with it.
CameraPose roofPose(double rotation_deg) {
    const double turn = glm::radians(rotation_deg);
    const glm::dvec3 eye(6.0, -1.5, 6.5);
    return CameraPose::lookingAt({std::cos(turn) * eye.x - std::sin(turn) * eye.y,
                                  std::sin(turn) * eye.x + std::cos(turn) * eye.y, eye.z},
                                 {0.0, 0.0, 2.75});
}

// Per pixel (centre ray): -1 where the ray meets no tile, else the truth's linear display value.
std::vector<double> truthImage(const RoofMesh& roof, const bake::Bvh& bvh, const CameraPose& pose,
                               const FrameInfo& info, const BakeSetSunHorizon* horizon = nullptr,
                               std::vector<double>* horizon_only = nullptr) {
    if (horizon_only != nullptr) horizon_only->assign(size_t(kWidth) * kHeight, 0.0);
    const testing::SyntheticBakeSetOptions scene = sceneOptions();
    const glm::dvec3 sun = glm::normalize(info.sun_direction_enu);
    const glm::dvec3 helper = std::abs(sun.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(helper, sun)), e2 = glm::cross(sun, e1);
    const double disc_radius = std::tan(glm::radians(0.2675));
    std::vector<double> truth(size_t(kWidth) * kHeight, -1.0);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::dvec3 ray = glm::normalize(
                pose.camera_to_enu *
                glm::dvec3((x + 0.5 - kWidth / 2.0) / kFocal, (y + 0.5 - kHeight / 2.0) / kFocal, 1.0));
            const std::optional<bake::BvhHit> hit =
                bake::traceClosestCpu(bvh, glm::vec3(pose.position_enu), glm::vec3(ray), 1e4f);
            if (!hit || hit->triangle_index >= roof.tile_triangles) continue;
            const glm::dvec3 normal = roof.mesh.normals[roof.mesh.indices[3 * hit->triangle_index]];
            const glm::dvec3 point = pose.position_enu + ray * double(hit->t);
            const double cosine = std::max(0.0, glm::dot(normal, sun));
            int seen = 0;
            for (int sample = 0; sample < kSunDiscSamples && cosine > 0.0; ++sample) {
                const double r = disc_radius * std::sqrt((sample + 0.5) / kSunDiscSamples), angle = sample * 2.39996323;
                const glm::dvec3 direction = glm::normalize(sun + r * (std::cos(angle) * e1 + std::sin(angle) * e2));
                seen += bake::occludedCpu(bvh, glm::vec3(point + 1e-4 * normal), glm::vec3(direction), 1e4f) ? 0 : 1;
            }
            const double v = double(seen) / kSunDiscSamples;
            if (horizon_only != nullptr && !horizon->empty()) {
                // The CPU twin of the runtime's horizon term alone, bilinear at the hit's uv1.
                const bake::BvhHit& h = *hit;
                const uint32_t* corner = &roof.mesh.indices[3 * h.triangle_index];
                const glm::vec2 uv = (1.0f - h.barycentric_u - h.barycentric_v) * roof.mesh.uv1[corner[0]] +
                                     h.barycentric_u * roof.mesh.uv1[corner[1]] +
                                     h.barycentric_v * roof.mesh.uv1[corner[2]];
                const double vh = cosine > 0.0 ? sunHorizonVisibilityAt(*horizon, uv.x, uv.y, sun) : 0.0;
                (*horizon_only)[size_t(y) * kWidth + x] = std::min(1.0, scene.albedo / M_PI *
                    (scene.indirect_irradiance + vh * info.sun_irradiance_rgb.y * cosine) * kExposure);
            }
            const double radiance = scene.albedo / M_PI *
                                    (scene.indirect_irradiance + v * info.sun_irradiance_rgb.y * cosine);
            truth[size_t(y) * kWidth + x] = std::min(1.0, radiance * kExposure);
        }
    return truth;
}

// The roof's flat pixels: every pixel whose 3 x 3 neighbourhood's centre rays all meet tiles (no silhouette, no
// slab edge). Returns runtime / truth over their means, and counts them.
struct RoofMean {
    double runtime = 0.0, truth = 0.0, runtime_sigma = 0.0;
    size_t pixels = 0;
};
RoofMean roofMean(const std::vector<uint8_t>& pixels, const std::vector<double>& truth) {
    RoofMean mean;
    double squares = 0.0;
    for (uint32_t y = 1; y + 1 < kHeight; ++y)
        for (uint32_t x = 1; x + 1 < kWidth; ++x) {
            bool flat = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    flat &= truth[size_t(int(y) + dy) * kWidth + size_t(int(x) + dx)] >= 0.0;
            if (!flat) continue;
            const double value = linearAt(pixels, x, y);
            mean.runtime += value;
            squares += value * value;
            mean.truth += truth[size_t(y) * kWidth + x];
            ++mean.pixels;
        }
    const double n = double(std::max<size_t>(mean.pixels, 1));
    mean.runtime /= n;
    mean.truth /= n;
    mean.runtime_sigma = std::sqrt(std::max(0.0, squares / n - mean.runtime * mean.runtime));
    return mean;
}

class RuntimeSunHorizon : public testing::GpuTest {};

// The roof's turn that makes it face `across_deg` from the sun's azimuth, so the sun comes across its tile rows
// at that angle (90: straight across; the roof faces east, azimuth 90, unturned, and a turn counter-clockwise
// seen from above lowers its azimuth).
double turnFacing(double sun_azimuth_deg, double across_deg) { return 90.0 - (sun_azimuth_deg + across_deg); }

// Every case: the roof's flat pixels with and without horizons against the truth. The ctest runs the sun 10
// degrees high straight across the rows (the shadow map alone 15 % too bright there); with
// GUSUKU_SUN_HORIZON_SWEEP=1 it runs 10, 15, 20 and 25 degrees, across the rows from either side and 55 and 35
// degrees off them (the 10-25 degrees from several azimuths; about a minute on lavapipe).
TEST_F(RuntimeSunHorizon, RoundTileRoofUnderALowSunMatchesTheTruth) {
    const bool sweep = std::getenv("GUSUKU_SUN_HORIZON_SWEEP") != nullptr;
    const std::vector<double> elevations = sweep ? std::vector<double>{10, 15, 20, 25} : std::vector<double>{10};
    const std::vector<double> acrosses = sweep ? std::vector<double>{90, 55, 35, -90} : std::vector<double>{90};
    // The sun's azimuth at the middle of the elevations (the morning's sun moves 6 degrees over them).
    const double sun_azimuth_deg = 72.0;
    double worst_with = 0.0, worst_without = 0.0, sum_with = 0.0, sum_without = 0.0;
    int cases = 0;
    for (double across : acrosses) {
        TileRoof options;
        options.rotation_deg = turnFacing(sun_azimuth_deg, across);
        const RoofMesh roof = tileRoof(options);
        const bake::Bvh bvh = bake::buildBvh(roof.mesh, {});
        const BakeSetData with = bakeSetWithRoof(roof, bvh, true), without = bakeSetWithRoof(roof, bvh, false);
        const std::unique_ptr<Runtime> runtime_with = openRuntime(context(), with);
        const std::unique_ptr<Runtime> runtime_without = openRuntime(context(), without);
        const CameraPose pose = roofPose(options.rotation_deg);
        for (double elevation : elevations) {
            const double utc = utcAtElevation(with, elevation);
            const Rendered lit = render(*runtime_with, pose, utc), before = render(*runtime_without, pose, utc);
            std::vector<double> horizon_only;
            const std::vector<double> truth =
                truthImage(roof, bvh, pose, lit.info, &with.building_sun_horizon, &horizon_only);
            double horizon_model = 0.0, truth_sum = 0.0;  // the CPU twin of the horizons alone, every roof pixel
            for (size_t i = 0; i < truth.size(); ++i)
                if (truth[i] >= 0.0) horizon_model += horizon_only[i], truth_sum += truth[i];
            const RoofMean after_mean = roofMean(lit.pixels, truth), before_mean = roofMean(before.pixels, truth);
            const double after_ratio = after_mean.runtime / after_mean.truth;
            const double before_ratio = before_mean.runtime / before_mean.truth;
            std::printf("sun %.1f deg high at azimuth %.1f, %+.0f deg across the tile rows: %zu flat pixels, "
                        "runtime / truth %.4f with horizons, %.4f without (the horizons' CPU twin alone %.4f)\n",
                        lit.info.sun_apparent_elevation_deg, lit.info.sun_azimuth_deg,
                        90.0 - options.rotation_deg - lit.info.sun_azimuth_deg, after_mean.pixels, after_ratio,
                        before_ratio, horizon_model / truth_sum);
            ASSERT_GT(after_mean.pixels, 4000u);
            EXPECT_NEAR(after_ratio, 1.0, 0.05);
            worst_with = std::max(worst_with, std::abs(after_ratio - 1.0));
            worst_without = std::max(worst_without, std::abs(before_ratio - 1.0));
            sum_with += std::abs(after_ratio - 1.0);
            sum_without += std::abs(before_ratio - 1.0);
            ++cases;
        }
    }
    std::printf("|runtime / truth - 1| over the roof's flat pixels, %d cases: mean %.4f, worst %.4f with horizons; "
                "mean %.4f, worst %.4f without\n",
                cases, sum_with / cases, worst_with, sum_without / cases, worst_without);
    // The scene is one the shadow map alone cannot draw (the test would pass without horizons otherwise).
    EXPECT_GT(worst_without, 0.10);
    EXPECT_LT(sum_with, sum_without);
}

// A roof without tiles, its horizons baked: the horizons of a plane are its own tangent plane and open sky, so
// every pixel is the lit truth's, with no texel of acne (the flat roof's pixels all one code but for rounding).
TEST_F(RuntimeSunHorizon, FlatRoofWithHorizonsHasNoAcne) {
    TileRoof options;
    options.depth_m = 0.0;
    options.rotation_deg = turnFacing(72.0, 55.0);
    const RoofMesh roof = tileRoof(options);
    const bake::Bvh bvh = bake::buildBvh(roof.mesh, {});
    const BakeSetData with = bakeSetWithRoof(roof, bvh, true);
    const std::unique_ptr<Runtime> runtime = openRuntime(context(), with);
    const CameraPose pose = roofPose(options.rotation_deg);
    const Rendered lit = render(*runtime, pose, utcAtElevation(with, 10.0));
    const RoofMean mean = roofMean(lit.pixels, truthImage(roof, bvh, pose, lit.info));
    std::printf("flat roof, sun %.1f deg high: %zu pixels, runtime / truth %.4f, runtime sigma %.5f\n",
                lit.info.sun_apparent_elevation_deg, mean.pixels, mean.runtime / mean.truth, mean.runtime_sigma);
    ASSERT_GT(mean.pixels, 4000u);
    EXPECT_NEAR(mean.runtime / mean.truth, 1.0, 0.01);
    EXPECT_LT(mean.runtime_sigma, 0.002 * mean.runtime + 1e-4);
}

// The frame's cost with horizons over without, in one run (printed: lavapipe on a shared machine, so no bound is
// pinned here; with the sweep only).
TEST_F(RuntimeSunHorizon, FrameCostIsPrinted) {
    if (std::getenv("GUSUKU_SUN_HORIZON_SWEEP") == nullptr) GTEST_SKIP() << "GUSUKU_SUN_HORIZON_SWEEP=1 runs it";
    TileRoof options;
    options.rotation_deg = turnFacing(72.0, 90.0);
    const RoofMesh roof = tileRoof(options);
    const bake::Bvh bvh = bake::buildBvh(roof.mesh, {});
    const BakeSetData without = bakeSetWithRoof(roof, bvh, false), with = bakeSetWithRoof(roof, bvh, true);
    const double utc = utcAtElevation(without, 20.0);
    const CameraPose pose = roofPose(options.rotation_deg);
    const std::unique_ptr<Runtime> runtime_without = openRuntime(context(), without);
    const std::unique_ptr<Runtime> runtime_with = openRuntime(context(), with);
    double seconds_without = 0.0, seconds_with = 0.0;
    for (int round = 0; round < 3; ++round) {  // interleaved, so the shared machine's load falls on both
        seconds_without += render(*runtime_without, pose, utc, 4).seconds;
        seconds_with += render(*runtime_with, pose, utc, 4).seconds;
    }
    std::printf("proposed frame %ux%u: %.2f ms with horizons, %.2f ms without (ratio %.3f)\n", kWidth, kHeight,
                1e3 * seconds_with, 1e3 * seconds_without, seconds_with / seconds_without);
}

// The frame's cost of the horizons on a real bake set (a benchmark, not a check: skipped unless
// GUSUKU_SUN_HORIZON_FRAME_BAKESET names one). The bench's front view (eye 2,-5,3.2 m looking at 2,3.5,3 m, 60
// degrees across) into a grey camera frame, 1.5 h after the last sunny slot (a low sun: the horizons' case); the
// same bake set opened twice, once with its horizons and once with them dropped (a 1 x 1 open horizon, as an older
// bake set loads), and direct-only beside them; fenced frames (read back) one of each in turn, the order reversed
// every round so that the shared machine's load falls on all alike; medians.
TEST_F(RuntimeSunHorizon, FrameCostOnABakeSetIsPrinted) {
    const char* folder = std::getenv("GUSUKU_SUN_HORIZON_FRAME_BAKESET");
    if (folder == nullptr) GTEST_SKIP() << "GUSUKU_SUN_HORIZON_FRAME_BAKESET=DIR runs it";
    const char* frames_text = std::getenv("GUSUKU_SUN_HORIZON_FRAMES");
    const int frames = frames_text != nullptr ? std::max(1, std::atoi(frames_text)) : 60;
    const BakeSetData with = loadBakeSet(folder);
    ASSERT_FALSE(with.building_sun_horizon.empty()) << folder << ": the bake set has no sun horizons";
    BakeSetData without = with;
    without.building_sun_horizon = {};
    without.manifest.building.sun_horizon.clear();
    double last_slot_utc = 0.0;
    for (const BakeSetSlot& slot : with.manifest.slots)
        if (slot.sun.present) last_slot_utc = std::max(last_slot_utc, parseIso8601Utc(slot.utc));
    ASSERT_GT(last_slot_utc, 0.0);
    const RuntimeOptions options;  // the runtime's defaults: 1280x720, msaa 4, anisotropy 1
    const std::unique_ptr<Runtime> runtime_with = Runtime::open(context(), with, options);
    const std::unique_ptr<Runtime> runtime_without = Runtime::open(context(), without, options);
    const std::vector<uint8_t> camera(size_t(options.frame_width) * options.frame_height * 4, 128);
    std::vector<uint8_t> pixels(camera.size());
    const double focal = options.frame_width / 2.0 / std::tan(glm::radians(30.0));
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {focal, focal, options.frame_width / 2.0, options.frame_height / 2.0, options.frame_width,
                        options.frame_height};
    frame.pose = CameraPose::lookingAt({2.0, -5.0, 3.2}, {2.0, 3.5, 3.0});
    frame.utc_unix_seconds = last_slot_utc + 5400.0;
    frame.weather = Weather::sunny();
    frame.exposure = 1.0f;
    frame.colour_match = ColourMatch::kOff;
    struct Variant {
        const char* name;
        Runtime* runtime;
        RenderMode mode;
        std::vector<double> ms;
    };
    std::vector<Variant> variants = {{"proposed with horizons", runtime_with.get(), RenderMode::kProposed, {}},
                                     {"proposed, 1x1 open horizon", runtime_without.get(), RenderMode::kProposed, {}},
                                     {"direct-only", runtime_with.get(), RenderMode::kDirectOnly, {}}};
    FrameInfo info;
    for (int round = -2; round < frames; ++round)  // two rounds of warm-up, not counted
        for (size_t k = 0; k < variants.size(); ++k) {
            Variant& variant = variants[round % 2 == 0 ? k : variants.size() - 1 - k];
            frame.mode = variant.mode;
            const auto start = std::chrono::steady_clock::now();
            info = variant.runtime->renderFrame(frame, pixels.data());
            const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (round >= 0) variant.ms.push_back(ms);
        }
    auto median = [](std::vector<double> values) {
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    std::printf("%s, sun %.1f deg high at azimuth %.1f, %ux%u msaa %u, %d fenced frames each, interleaved:\n", folder,
                info.sun_apparent_elevation_deg, info.sun_azimuth_deg, options.frame_width, options.frame_height,
                options.msaa_samples, frames);
    for (const Variant& variant : variants)
        std::printf("  %-28s median %8.2f ms\n", variant.name, median(variant.ms));
    std::printf("  with horizons / 1x1 open horizon: %.3f; with horizons / direct-only: %.3f; open / direct-only: "
                "%.3f\n",
                median(variants[0].ms) / median(variants[1].ms), median(variants[0].ms) / median(variants[2].ms),
                median(variants[1].ms) / median(variants[2].ms));
}

}  // namespace
}  // namespace gusuku
