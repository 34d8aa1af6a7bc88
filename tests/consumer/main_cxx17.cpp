// A C++17 app against the installed gusuku (as Android NDK and Unity native-plugin code is built): the C++ API
// (gusuku/runtime/runtime.h), a one-wall bake set in memory, a headless runtime, one frame. The same scene as
// main.c: the wall is lit by its overcast slot alone, so its pixel is sRGB(albedo / pi * E_ind), computed here.
// An optional argument sets the samples a pixel, as main.c's does.
#if __cplusplus < 201703L || __cplusplus >= 202002L
#error "tests/consumer/main_cxx17.cpp is the C++17 consumer: compile it as C++17 exactly"
#endif

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <vector>

#include <gusuku/runtime/runtime.h>
#include <gusuku/runtime/runtime_version.h>

namespace {

constexpr uint32_t kSize = 16;
constexpr double kPi = 3.14159265358979323846;

/// A size x size float RGBA image of one value per channel.
gusuku::BakeSetImage uniformImage(int size, float r, float g, float b, float a) {
    gusuku::BakeSetImage image;
    image.width = image.height = size;
    image.rgba.resize(size_t(size) * size_t(size) * 4);
    for (size_t texel = 0; texel < image.rgba.size(); texel += 4) {
        image.rgba[texel] = r;
        image.rgba[texel + 1] = g;
        image.rgba[texel + 2] = b;
        image.rgba[texel + 3] = a;
    }
    return image;
}

/// A 4 m x 4 m wall in the plane y = 0 facing south (-y), centre (0, 0, 2), albedo 0.5; a 2 x 2 ground grid of
/// 4 m cells from (-4, -4); one overcast slot with E_ind = 1 on the wall and 2 on the ground.
gusuku::BakeSetData oneWallBakeSet() {
    gusuku::BakeSetData data;
    data.manifest.site.name = "consumer_cxx17";
    data.manifest.site.latitude_deg = 26.2856;
    data.manifest.site.longitude_deg = 127.8008;
    data.manifest.building.lightmap_resolution = 2;
    data.manifest.ground_grid.grid.origin_enu_m = glm::dvec2(-4.0, -4.0);
    data.manifest.ground_grid.grid.cell_m = 4.0;
    data.manifest.ground_grid.grid.columns = data.manifest.ground_grid.grid.rows = 2;

    gusuku::BakeSetMesh& wall = data.building;
    wall.positions = {{-2, 0, 0}, {2, 0, 0}, {2, 0, 4}, {-2, 0, 4}};
    wall.normals.assign(4, glm::vec3(0, -1, 0));
    wall.uv0 = wall.uv1 = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}};
    wall.indices = {0, 1, 2, 0, 2, 3};
    wall.triangle_material = {0, 0};
    gusuku::BakeSetMaterial material;
    material.base_color_factor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    wall.materials.push_back(material);

    data.ground_geometry = uniformImage(2, 0, 0, 1, 0);  // normal up, height 0

    gusuku::BakeSetSlot overcast;
    overcast.name = "overcast";
    overcast.sky = gusuku::BakeSetSky::Overcast;
    overcast.sun.irradiance_source = "none: overcast";
    data.manifest.slots.push_back(overcast);
    gusuku::BakeSetSlotImages images;
    images.building = uniformImage(2, 1, 1, 1, 1);
    images.ground_with = images.ground_without = uniformImage(2, 2, 2, 2, 1);
    data.slots.push_back(images);
    return data;
}

/// 10 m south of the wall at 2 m, looking north: camera x = east, y = down, z = north.
gusuku::FrameInput frameFacingTheWall(const std::vector<uint8_t>& camera) {
    gusuku::FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics.fx = frame.intrinsics.fy = 16.0;
    frame.intrinsics.cx = frame.intrinsics.cy = kSize / 2.0;
    frame.intrinsics.width = frame.intrinsics.height = kSize;
    frame.pose.position_enu = glm::dvec3(0.0, -10.0, 2.0);
    frame.pose.camera_to_enu = glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
    frame.utc_unix_seconds = 1782000000.0;
    frame.colour_match = gusuku::ColourMatch::kOff;
    return frame;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        gusuku::RuntimeOptions options;
        options.frame_width = options.frame_height = kSize;
        options.shadow_map_size = 64;
        if (argc > 1) options.msaa_samples = uint32_t(std::strtoul(argv[1], nullptr, 10));  // open() refuses a bad one
        const std::unique_ptr<gusuku::Runtime> runtime = gusuku::Runtime::openHeadless(oneWallBakeSet(), options);

        const std::vector<uint8_t> camera(kSize * kSize * 4, 30);
        std::vector<uint8_t> output(kSize * kSize * 4, 0);
        runtime->renderFrame(frameFacingTheWall(camera), output.data());

        const uint8_t* centre = &output[((kSize / 2) * kSize + kSize / 2) * 4];
        const double linear = 0.5 / kPi * 1.0;
        const double expected = 255.0 * (1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
        std::printf("consumer C++17: gusuku %s, %ux%u frame, %llu bytes of device memory, wall pixel %d %d %d "
                    "(expected %.1f)\n",
                    gusuku::runtimeVersion(), kSize, kSize, (unsigned long long)runtime->deviceMemoryBytes(),
                    centre[0], centre[1], centre[2], expected);
        return std::fabs(centre[0] - expected) <= 1.5 && std::fabs(centre[1] - expected) <= 1.5 ? 0 : 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "consumer C++17: %s\n", error.what());
        return 1;
    }
}
