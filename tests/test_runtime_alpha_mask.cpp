// Alpha-masked materials at run time (issue 21 item 3): a masked quad's sun shadow on the ground has the mask's
// shape, and its holes show the ground through the building pass. On lavapipe with validation on, in the
// closed-form bake set (synthetic_bakeset.h), against a CPU truth computed from the mask itself: a ground point
// is lit when its ray to the sun misses the quad or crosses it in an open texel. The same quad unmasked casts a
// solid shadow, so the test fails without the alpha test.
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/sun.h"
#include "gusuku/runtime/runtime.h"
#include "shadow_scenes.h"
#include "gusuku/synthetic/synthetic_bakeset.h"

namespace gusuku {
namespace {

constexpr uint32_t kWidth = 320, kHeight = 240;
constexpr double kFocal = 300.0;
constexpr uint8_t kCameraCode = 150;
constexpr int kMaskSide = 4;                           // texels a side, 0.5 m each
constexpr double kQuadMin = -1.0, kQuadSize = 2.0, kQuadHeight = 0.5;
constexpr double kEdgeMarginM = 0.04;                  // penumbra and filtering about the texel edges: left out

bool openTexel(int x, int y) { return (x + y) % 2 == 0 || (x == 3 && y == 0); }

// Where a point of the quad's plane falls in its mask (texel indices), or false off the quad; `near_edge` when
// within kEdgeMarginM of a texel's edge.
bool maskTexel(const glm::dvec3& point, int& x, int& y, bool& near_edge) {
    const double u = (point.x - kQuadMin) / kQuadSize * kMaskSide, v = (point.y - kQuadMin) / kQuadSize * kMaskSide;
    const double margin = kEdgeMarginM / kQuadSize * kMaskSide;
    near_edge = std::abs(u - std::round(u)) < margin || std::abs(v - std::round(v)) < margin;
    if (u < -margin || v < -margin || u > kMaskSide + margin || v > kMaskSide + margin) return false;
    x = std::clamp(int(std::floor(u)), 0, kMaskSide - 1);
    y = std::clamp(int(std::floor(v)), 0, kMaskSide - 1);
    return true;
}

BakeSetData maskedQuadBakeSet(bool masked) {
    testing::SyntheticBakeSetOptions options;
    options.grid_half_m = 6.0;
    const glm::vec3 a(kQuadMin, kQuadMin, kQuadHeight), b(kQuadMin + kQuadSize, kQuadMin, kQuadHeight),
        c(kQuadMin + kQuadSize, kQuadMin + kQuadSize, kQuadHeight), d(kQuadMin, kQuadMin + kQuadSize, kQuadHeight);
    BakeSetData data = testing::bakeSetWithBuilding({a, b, c, a, c, d}, options);
    for (size_t vertex = 0; vertex < data.building.positions.size(); ++vertex) {
        const glm::vec3& p = data.building.positions[vertex];
        data.building.uv0[vertex] = glm::vec2((p.x - kQuadMin) / kQuadSize, (p.y - kQuadMin) / kQuadSize);
    }
    BakeSetTexture mask{kMaskSide, kMaskSide, {}};
    for (int y = 0; y < kMaskSide; ++y)
        for (int x = 0; x < kMaskSide; ++x)
            mask.rgba8.insert(mask.rgba8.end(), {200, 200, 200, uint8_t(openTexel(x, y) ? 0 : 255)});
    data.building.textures = {mask};
    data.building.materials[0].base_color_texture = 0;
    data.building.materials[0].alpha_masked = masked;
    data.building.materials[0].alpha_cutoff = 0.5f;
    return data;
}

double utcAtTwentyDegrees(const BakeSetData& bake_set) {
    SunObserver observer;
    observer.latitude_deg = bake_set.manifest.site.latitude_deg;
    observer.longitude_deg = bake_set.manifest.site.longitude_deg;
    observer.height_m = bake_set.manifest.site.height_m;
    for (double utc = testing::syntheticLocalTime(5, 0);; utc += 60.0)
        if (computeSunPosition(observer, utc).apparent_elevation_deg >= 20.0) return utc;
}

struct Agreement {
    int compared = 0, agreeing = 0, lit_through_holes = 0, hole_pixels = 0;
};

// Renders the quad's shadow from straight above its centre and compares each ground pixel's sun visibility
// (read back from the ground's ratio, as tests/test_runtime_shadows.cpp's penumbra does) with the truth.
Agreement compareShadow(const GpuDevice& device, bool masked) {
    const BakeSetData bake_set = maskedQuadBakeSet(masked);
    const double utc = utcAtTwentyDegrees(bake_set);
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    std::unique_ptr<Runtime> runtime = Runtime::open(device, bake_set, options);
    const std::vector<uint8_t> camera(size_t(kWidth) * kHeight * 4, kCameraCode);
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {kFocal, kFocal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.utc_unix_seconds = utc;
    frame.weather = Weather::sunny();
    frame.exposure = 0.5f;
    frame.colour_match = ColourMatch::kOff;
    frame.mode = RenderMode::kProposed;
    frame.pose = CameraPose::lookingAt({0, 0, 4}, {0, 0, 0});
    std::vector<uint8_t> pixels(camera.size());
    FrameInfo info = runtime->renderFrame(frame, pixels.data());
    const glm::dvec3 sun = info.sun_direction_enu;
    // Look straight down at the shadow's centre (the quad's centre moved along the sun's ray to the ground).
    const glm::dvec3 centre = glm::dvec3(0.0, 0.0, kQuadHeight) - sun * (kQuadHeight / sun.z);
    const CameraPose pose = CameraPose::lookingAt(centre + glm::dvec3(0, 0, 4), centre);
    frame.pose = pose;
    info = runtime->renderFrame(frame, pixels.data());
    const double camera_linear = srgbDecode(kCameraCode / 255.0);
    const double e_sun = info.sun_irradiance_rgb.y * sun.z, e_ground = testing::SyntheticBakeSetOptions{}.ground_irradiance;
    Agreement agreement;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const glm::dvec3 ray = glm::normalize(
                pose.camera_to_enu * glm::dvec3((x + 0.5 - kWidth / 2.0) / kFocal, (y + 0.5 - kHeight / 2.0) / kFocal, 1.0));
            int tx, ty;
            bool near_edge;
            const glm::dvec3 at_quad = pose.position_enu + ray * ((kQuadHeight - pose.position_enu.z) / ray.z);
            const bool through_quad = maskTexel(at_quad, tx, ty, near_edge);
            if (through_quad && (near_edge || !masked || !openTexel(tx, ty))) continue;  // the quad itself
            const glm::dvec3 ground = pose.position_enu + ray * (-pose.position_enu.z / ray.z);
            const glm::dvec3 towards_quad = ground + sun * (kQuadHeight / sun.z);
            bool shaded = false;
            if (maskTexel(towards_quad, tx, ty, near_edge)) {
                if (near_edge) continue;
                shaded = !(masked && openTexel(tx, ty));
            }
            const size_t index = (size_t(y) * kWidth + x) * 4 + 1;
            const double ratio = srgbDecode(pixels[index] / 255.0) / camera_linear;
            const double visibility = (ratio * (e_ground + e_sun) - e_ground) / e_sun;
            ++agreement.compared;
            agreement.agreeing += std::abs(visibility - (shaded ? 0.0 : 1.0)) < 0.25;
            agreement.hole_pixels += through_quad;
            agreement.lit_through_holes += !shaded && towards_quad.x > kQuadMin && towards_quad.x < kQuadMin + kQuadSize &&
                                           towards_quad.y > kQuadMin && towards_quad.y < kQuadMin + kQuadSize;
        }
    std::printf("%s: %d ground pixels compared, %d agree; %d lit through the holes; %d seen through a hole\n",
                masked ? "masked" : "opaque", agreement.compared, agreement.agreeing, agreement.lit_through_holes,
                agreement.hole_pixels);
    return agreement;
}

class RuntimeAlphaMask : public testing::GpuTest {};

TEST_F(RuntimeAlphaMask, MaskedQuadsShadowHasTheMasksShapeAndItsHolesShowTheGround) {
    const Agreement masked = compareShadow(context(), true);
    ASSERT_GT(masked.compared, 20000);
    EXPECT_GT(masked.lit_through_holes, 5000) << "sunlight passes the mask's open texels";
    EXPECT_GT(masked.hole_pixels, 1000) << "the camera sees the ground through the holes";
    EXPECT_GE(double(masked.agreeing), 0.99 * masked.compared);
}

TEST_F(RuntimeAlphaMask, TheSameQuadOpaqueCastsASolidShadow) {
    const Agreement opaque = compareShadow(context(), false);
    ASSERT_GT(opaque.compared, 20000);
    EXPECT_EQ(opaque.lit_through_holes, 0);
    EXPECT_GE(double(opaque.agreeing), 0.99 * opaque.compared);
}

}  // namespace
}  // namespace gusuku
