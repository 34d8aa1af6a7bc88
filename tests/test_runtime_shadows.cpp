// The building's shadow (runtime_shadow.glsl: the sun's disc as the penumbra, contact shadows) and the
// platform's edge, on lavapipe with validation on, against a CPU ray caster of the same light model with the
// exact sun visibility over the sun's disc (tests/support/shadow_scenes.h), in the closed-form bake set:
//   - a ribbed roof (battens 4 cm tall every 25 cm) at a 20-degree morning sun: the roof's mean luminance
//     within 2 % of the truth (the battens' own shadows kept);
//   - the same roof without battens: no acne, its pixels' spread tiny and its mean the lit truth;
//   - a wall's vertical edge casting on the ground: the penumbra's 10-90 % width at 3 m and at 6 m from the edge
//     against the truth's over the sun's disc (it grows as d x 2 tan(0.2675 deg));
//   - a base platform 2 cm above the ground: no dark rim along its front edge, in the proposed mode and in
//     direct-only, pixel by pixel against the truth.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/shadow_fit.h"
#include "gusuku/maths/sun.h"
#include "gusuku/runtime/runtime.h"
#include "shadow_scenes.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr double kFocal = 300.0;
constexpr float kExposure = 0.5f;
constexpr uint8_t kCameraCode = 150;
constexpr int kSunDiscSamples = 8;  // rays over the sun's disc a truth point: its 0.27-degree penumbra needs few

testing::SyntheticBakeSetOptions sceneOptions() {
    testing::SyntheticBakeSetOptions options;
    options.grid_half_m = 6.0;  // a 12 m ground grid: the shadow map's texels about 1.6 cm at 1024
    return options;
}

// The morning instant of the bake date when the sun stands 20 degrees high (to the minute).
double utcAtTwentyDegrees(const BakeSetData& bake_set) {
    SunObserver observer;
    observer.latitude_deg = bake_set.manifest.site.latitude_deg;
    observer.longitude_deg = bake_set.manifest.site.longitude_deg;
    observer.height_m = bake_set.manifest.site.height_m;
    for (double utc = syntheticLocalTime(5, 0);; utc += 60.0)
        if (computeSunPosition(observer, utc).apparent_elevation_deg >= 20.0) return utc;
}

struct Rendered {
    std::vector<uint8_t> pixels;
    FrameInfo info;
};

Rendered render(const GpuDevice& device, const BakeSetData& bake_set, const CameraPose& pose, double utc,
                RenderMode mode, double focal = kFocal) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    std::unique_ptr<Runtime> runtime = Runtime::open(device, bake_set, options);
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, kCameraCode);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {focal, focal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = pose;
    frame.utc_unix_seconds = utc;
    frame.weather = Weather::sunny();
    frame.exposure = kExposure;
    frame.colour_match = ColourMatch::kOff;
    frame.mode = mode;
    Rendered rendered;
    rendered.pixels.resize(camera.size());
    rendered.info = runtime->renderFrame(frame, rendered.pixels.data());
    return rendered;
}

// The truth of one pixel, linear display value, over 4 x 4 rays; `building_rays` counts those that met the
// building, `side_rays` those that met a face whose normal is `side_normal` below `side_below_m`.
struct TruthPixel {
    double linear = 0.0;
    int building_rays = 0;
    int side_rays = 0;
};

TruthPixel truthPixel(const std::vector<glm::vec3>& building, const CameraPose& pose, const FrameInfo& info,
                      uint32_t x, uint32_t y, RenderMode mode, const glm::dvec3& side_normal,
                      double side_below_m = INFINITY) {
    const testing::SyntheticBakeSetOptions scene = sceneOptions();
    const glm::dvec3 sun = info.sun_direction_enu;
    const double sun_irradiance = info.sun_irradiance_rgb.y, albedo = scene.albedo;
    const double camera_linear = srgbDecode(kCameraCode / 255.0);
    TruthPixel pixel;
    for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
            const glm::dvec3 ray = glm::normalize(pose.camera_to_enu *
                                                  glm::dvec3((x + (sx + 0.5) / 4.0 - kWidth / 2.0) / kFocal,
                                                             (y + (sy + 0.5) / 4.0 - kHeight / 2.0) / kFocal, 1.0));
            const std::optional<testing::RayHit> hit = testing::castRay(building, pose.position_enu, ray);
            const double ground_t = ray.z < 0.0 ? -pose.position_enu.z / ray.z : INFINITY;
            double value = camera_linear;
            if (hit && hit->distance < ground_t) {
                ++pixel.building_rays;
                const glm::dvec3 point = pose.position_enu + ray * hit->distance;
                pixel.side_rays += glm::dot(hit->normal, side_normal) > 0.999 && point.z < side_below_m;
                const double cosine = std::max(0.0, glm::dot(hit->normal, sun));
                const double v = cosine > 0.0 ? testing::sunDiscVisibility(building, point, hit->normal, sun,
                                                                           kSunDiscSamples)
                                              : 0.0;
                const double radiance = albedo / M_PI * (scene.indirect_irradiance + v * sun_irradiance * cosine);
                value = std::min(1.0, radiance * kExposure);
            } else if (std::isfinite(ground_t)) {
                const glm::dvec3 point = pose.position_enu + ray * ground_t;
                const double v = testing::sunDiscVisibility(building, point, {0, 0, 1}, sun, kSunDiscSamples);
                const double e_sun = sun_irradiance * std::max(0.0, sun.z);
                const double ratio = mode == RenderMode::kDirectOnly
                                         ? 0.6 + 0.4 * v
                                         : (scene.ground_irradiance + v * e_sun) / (scene.ground_irradiance + e_sun);
                value = camera_linear * ratio;
            }
            pixel.linear += value / 16.0;
        }
    return pixel;
}

double linearAt(const std::vector<uint8_t>& pixels, uint32_t x, uint32_t y) {
    return srgbDecode(pixels[(size_t(y) * kWidth + x) * 4 + 1] / 255.0);
}

class RuntimeShadows : public testing::GpuTest {};

// The roof's pixels (every truth ray on the building): the runtime's and the truth's mean, and the runtime's
// standard deviation.
struct RoofStatistics {
    double runtime_mean = 0.0, truth_mean = 0.0, runtime_sigma = 0.0;
    size_t pixels = 0;
};

const glm::dvec3 kRoofNormal(0.5, 0.0, std::sqrt(0.75));  // the roof's 30-degree pitch, facing east

RoofStatistics roofStatistics(const GpuDevice& device, bool ribs) {
    testing::RibbedRoofOptions roof;
    roof.ribs = ribs;
    const std::vector<glm::vec3> building = testing::ribbedRoof(roof);
    const BakeSetData bake_set = testing::bakeSetWithBuilding(building, sceneOptions());
    const double utc = utcAtTwentyDegrees(bake_set);
    const CameraPose pose = CameraPose::lookingAt({6.0, -1.5, 6.5}, {0.0, 0.0, 2.75});
    const Rendered rendered = render(device, bake_set, pose, utc, RenderMode::kProposed);
    RoofStatistics statistics;
    double sum_squares = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            // Only pixels whose every ray meets the roof's own plane or the battens' tops.
            const TruthPixel truth = truthPixel(building, pose, rendered.info, x, y, RenderMode::kProposed, kRoofNormal);
            if (truth.side_rays < 16 && !(ribs && truth.building_rays == 16)) continue;
            const double value = linearAt(rendered.pixels, x, y);
            statistics.runtime_mean += value;
            statistics.truth_mean += truth.linear;
            sum_squares += value * value;
            ++statistics.pixels;
        }
    const double n = double(std::max<size_t>(statistics.pixels, 1));
    statistics.runtime_mean /= n;
    statistics.truth_mean /= n;
    statistics.runtime_sigma =
        std::sqrt(std::max(0.0, sum_squares / n - statistics.runtime_mean * statistics.runtime_mean));
    std::printf("roof %s: %zu pixels, sun %.2f deg high at azimuth %.1f; mean linear runtime %.4f truth %.4f "
                "(%+.2f %%), runtime sigma %.5f\n",
                ribs ? "with battens" : "flat", statistics.pixels, rendered.info.sun_apparent_elevation_deg,
                rendered.info.sun_azimuth_deg, statistics.runtime_mean, statistics.truth_mean,
                100.0 * (statistics.runtime_mean / statistics.truth_mean - 1.0), statistics.runtime_sigma);
    return statistics;
}

TEST_F(RuntimeShadows, RibbedRoofAtATwentyDegreeSunKeepsTheBattensShadows) {
    const RoofStatistics roof = roofStatistics(context(), true);
    ASSERT_GT(roof.pixels, 5000u);
    EXPECT_NEAR(roof.runtime_mean / roof.truth_mean, 1.0, 0.02);
}

TEST_F(RuntimeShadows, FlatRoofAtTheSameSunHasNoAcne) {
    const RoofStatistics roof = roofStatistics(context(), false);
    ASSERT_GT(roof.pixels, 5000u);
    EXPECT_NEAR(roof.runtime_mean / roof.truth_mean, 1.0, 0.01);
    // A flat, lit, uniformly shaded plane: every pixel the same code but for rounding (a code is 0.4 % here).
    EXPECT_LT(roof.runtime_sigma, 0.002 * roof.runtime_mean + 1e-4);
}

// The platform's east edge, facing the camera and the sun: every pixel whose truth rays meet its 2 cm face,
// and a pixel either side, against the truth.
void expectNoRim(const GpuDevice& device, RenderMode mode) {
    const std::vector<glm::vec3> building = testing::platformBuilding(0.02);
    const BakeSetData bake_set = testing::bakeSetWithBuilding(building, sceneOptions());
    const double utc = utcAtTwentyDegrees(bake_set);
    const CameraPose pose = CameraPose::lookingAt({8.0, 1.0, 1.6}, {2.5, 0.0, 0.0});
    const Rendered rendered = render(device, bake_set, pose, utc, mode);
    std::vector<int> face(size_t(kWidth) * kHeight, 0);
    std::vector<double> truth(face.size(), 0.0);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const TruthPixel pixel = truthPixel(building, pose, rendered.info, x, y, mode, {1, 0, 0}, 0.021);
            face[size_t(y) * kWidth + x] = pixel.side_rays;
            truth[size_t(y) * kWidth + x] = pixel.linear;
        }
    size_t edge_pixels = 0;
    double worst = 1.0, sum = 0.0;
    uint32_t worst_x = 0, worst_y = 0;
    for (uint32_t y = 1; y + 1 < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            bool near_face = false;
            for (int dy = -1; dy <= 1; ++dy) near_face |= face[size_t(int(y) + dy) * kWidth + x] > 0;
            if (!near_face) continue;
            const double ratio = linearAt(rendered.pixels, x, y) / truth[size_t(y) * kWidth + x];
            if (ratio < worst) worst_x = x, worst_y = y;
            worst = std::min(worst, ratio);
            sum += ratio;
            ++edge_pixels;
        }
    std::printf("%s: %zu pixels along the platform's front edge; runtime / truth mean %.4f, darkest %.4f at %u,%u\n",
                mode == RenderMode::kDirectOnly ? "direct-only" : "proposed", edge_pixels,
                sum / double(std::max<size_t>(edge_pixels, 1)), worst, worst_x, worst_y);
    ASSERT_GT(edge_pixels, 200u);
    EXPECT_NEAR(sum / double(edge_pixels), 1.0, 0.02);
    // The rim was the ground's ratio for ground under the platform on the face's pixels: 0.66 and below. What is
    // left is one edge pixel sampled differently by 4 samples and 16 rays (0.86).
    EXPECT_GT(worst, 0.8);
}

// The rim's cause: the ground ratio is pulled 10 cm towards the camera (so the occluder mesh it was sampled from
// cannot hide it), which put it in front of the platform's whole 2 cm face, and its ratio (the ground under the
// platform's shadow) multiplied building pixels: 0.66 of the truth at worst here, in both modes. The building now
// marks its pixels in the stencil and the ground skips them (runtime_pipelines.h, StencilUse): 0.86 at worst, one
// edge pixel where 4 samples and the truth's 16 rays split the face's edge differently; the mean 0.998.
TEST_F(RuntimeShadows, PlatformTwoCentimetresAboveTheGroundHasNoDarkRim) {
    expectNoRim(context(), RenderMode::kProposed);
}

TEST_F(RuntimeShadows, PlatformHasNoDarkRimInDirectOnly) { expectNoRim(context(), RenderMode::kDirectOnly); }

// The penumbra: ground points across the shadow edge of the wall's south-east vertical edge, `blocker_m` from it
// along the sun's ray, seen from straight above at 1 mm a pixel. Profiles of V (the runtime's read back from the
// ground's ratio, the truth's over 512 rays of the sun's disc) every 2 mm over +-10 cm across the edge.
struct PenumbraProfile {
    std::vector<double> across_m, runtime, truth;
};

constexpr double kPenumbraFocal = 1500.0, kPenumbraEyeM = 1.5, kPenumbraStepM = 0.002, kPenumbraHalfM = 0.10;
constexpr int kPenumbraTruthSamples = 512;

PenumbraProfile penumbraProfile(const GpuDevice& device, const std::vector<glm::vec3>& wall,
                                const BakeSetData& bake_set, double utc, double blocker_m) {
    const testing::SyntheticBakeSetOptions scene = sceneOptions();
    // Sun and frame info first (a frame anywhere), then the view straight down on the edge's point.
    const FrameInfo info =
        render(device, bake_set, CameraPose::lookingAt({0, -5, 2}, {0, 0, 0}), utc, RenderMode::kProposed).info;
    const glm::dvec3 sun = info.sun_direction_enu;
    const glm::dvec3 horizontal = glm::normalize(glm::dvec3(sun.x, sun.y, 0.0));
    const glm::dvec3 across(horizontal.y, -horizontal.x, 0.0);  // on the ground, square to the shadow's edge
    const double along_m = blocker_m * std::sqrt(1.0 - sun.z * sun.z);  // the ray's ground run to the edge
    const glm::dvec3 edge = glm::dvec3(3.2, 0.0, 0.0) - horizontal * along_m;
    const CameraPose pose = CameraPose::lookingAt(edge + glm::dvec3(0, 0, kPenumbraEyeM), edge);
    const Rendered rendered = render(device, bake_set, pose, utc, RenderMode::kProposed, kPenumbraFocal);
    const double camera_linear = srgbDecode(kCameraCode / 255.0);
    const double e_sun = info.sun_irradiance_rgb.y * sun.z, e_ground = scene.ground_irradiance;
    PenumbraProfile profile;
    for (double u = -kPenumbraHalfM; u <= kPenumbraHalfM + 1e-9; u += kPenumbraStepM) {
        const glm::dvec3 point = edge + across * u;
        const glm::dvec3 camera = glm::transpose(pose.camera_to_enu) * (point - pose.position_enu);
        const uint32_t x = uint32_t(std::lround(kPenumbraFocal * camera.x / camera.z + kWidth / 2.0 - 0.5));
        const uint32_t y = uint32_t(std::lround(kPenumbraFocal * camera.y / camera.z + kHeight / 2.0 - 0.5));
        const double ratio = linearAt(rendered.pixels, x, y) / camera_linear;
        profile.across_m.push_back(u);
        profile.runtime.push_back((ratio * (e_ground + e_sun) - e_ground) / e_sun);
        profile.truth.push_back(testing::sunDiscVisibility(wall, point, {0, 0, 1}, sun, kPenumbraTruthSamples));
    }
    return profile;
}

// Where V first reaches `level` from the shadow's side (linear between samples).
double crossing(const PenumbraProfile& profile, const std::vector<double>& v, double level) {
    const bool shadow_first = v.front() < v.back();
    for (size_t index = 1; index < v.size(); ++index) {
        const double a = shadow_first ? v[index - 1] : v[v.size() - index];
        const double b = shadow_first ? v[index] : v[v.size() - index - 1];
        if (a < level && b >= level) {
            const double ua = profile.across_m[shadow_first ? index - 1 : v.size() - index];
            const double ub = profile.across_m[shadow_first ? index : v.size() - index - 1];
            return ua + (ub - ua) * (level - a) / (b - a);
        }
    }
    return NAN;
}

double width1090(const PenumbraProfile& profile, const std::vector<double>& v) {
    return std::abs(crossing(profile, v, 0.9) - crossing(profile, v, 0.1));
}

TEST_F(RuntimeShadows, PenumbraWidthGrowsWithTheBlockerDistanceAsTheSunsDisc) {
    const std::vector<glm::vec3> wall = testing::wallBuilding();
    const BakeSetData bake_set = testing::bakeSetWithBuilding(wall, sceneOptions());
    const double utc = utcAtTwentyDegrees(bake_set);
    // The map's texel, from the same fit the runtime makes (receivers: the wall and the 12 m ground grid).
    const FrameInfo info =
        render(context(), bake_set, CameraPose::lookingAt({0, -5, 2}, {0, 0, 0}), utc, RenderMode::kProposed).info;
    const double half = sceneOptions().grid_half_m;
    const ShadowFit fit = fitShadowMap({-half, -half, 0.0}, {half, half, 4.0}, {3.0, 0.0, 0.0}, {3.2, 3.0, 4.0},
                                       info.sun_direction_enu, 1024);
    const double tan_sun = std::tan(0.2675 * M_PI / 180.0);
    double runtime_widths[2], truth_widths[2];
    const double distances[2] = {3.0, 6.0};
    for (int index = 0; index < 2; ++index) {
        const PenumbraProfile profile = penumbraProfile(context(), wall, bake_set, utc, distances[index]);
        runtime_widths[index] = width1090(profile, profile.runtime);
        truth_widths[index] = width1090(profile, profile.truth);
        const double runtime_middle = crossing(profile, profile.runtime, 0.5);
        const double truth_middle = crossing(profile, profile.truth, 0.5);
        std::printf("blocker %.0f m: 10-90 %% width runtime %.1f mm, truth %.1f mm (the disc's full width d 2 tan "
                    "%.1f mm, texel %.1f mm); 50 %% point runtime %+.1f mm from the truth's\n",
                    distances[index], 1e3 * runtime_widths[index], 1e3 * truth_widths[index],
                    1e3 * distances[index] * 2.0 * tan_sun, 1e3 * fit.texel_size_m,
                    1e3 * (runtime_middle - truth_middle));
        ASSERT_TRUE(std::isfinite(runtime_widths[index]) && std::isfinite(truth_widths[index]));
        EXPECT_NEAR(runtime_widths[index], truth_widths[index], fit.texel_size_m);
        EXPECT_NEAR(runtime_middle, truth_middle, fit.texel_size_m);
    }
    // It grows with the distance as the sun's disc makes it grow (the truth's 10-90 % is 0.687 of d 2 tan).
    EXPECT_NEAR(runtime_widths[1] - runtime_widths[0], truth_widths[1] - truth_widths[0], fit.texel_size_m);
    EXPECT_NEAR(truth_widths[1] - truth_widths[0], 0.687 * 3.0 * 2.0 * tan_sun, 0.1 * 3.0 * 2.0 * tan_sun);
}

}  // namespace
}  // namespace gusuku
