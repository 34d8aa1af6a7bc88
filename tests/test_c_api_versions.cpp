// The C API's versioned structs (gusuku.h, "Versions and struct sizes"), frozen here:
//   - the "0.1" structs below are written out by hand, a copy of gusuku 0.1.0's fields behind struct_size (the
//     oldest layouts the library accepts), and static_asserts pin them to gusuku.h's prefix, and API version 1's
//     fields (this release) to their offsets on LP64; moving or retyping a published field fails to compile;
//   - passed to the library with their smaller struct_size, inside buffers whose bytes past the struct are
//     0x7F (a float of 3.4e38, a width of 2.1e9: any read of them would be refused or change the frame), they
//     give today's behaviour: the same composite bytes and frame facts as the full structs with defaults, and
//     the library writes nothing past an old gusuku_frame_info;
//   - the defaults they fall back on are today's: a control runtime with ground_change_threshold 0 (an appended
//     option) draws ground quads that the default 1/255 and the 0.1 options leave alone, so a library that took
//     zeros for the missing fields would fail;
//   - sizes no layout has (the 0.1 size minus 4, today's plus 8) are refused naming the struct and the sizes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku {
namespace {

// ---------------------------------------------------------------------------------------------------------------
// gusuku 0.1.0's fields behind struct_size, by hand.

struct RuntimeOptions01 {
    uint32_t struct_size;
    uint32_t frame_width, frame_height, shadow_map_size;
    float shadow_bias_texels;
    uint32_t shadow_pcf_radius, statistics_stride;
    float statistics_smoothing_frames, colour_gain_limit, direct_only_ambient_fraction, direct_only_shadow_darkening;
};

struct VulkanDevice01 {
    uint32_t struct_size;
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family_index;
};

struct BakeSetDesc01 {
    uint32_t struct_size;
    double latitude_deg, longitude_deg, height_m;
    const float *positions, *normals, *uv0, *uv1;
    uint32_t vertex_count;
    const uint32_t* indices;
    uint32_t index_count;
    const uint32_t* triangle_material;
    const gusuku_material* materials;
    uint32_t material_count;
    const gusuku_texture* textures;
    uint32_t texture_count;
    int32_t lightmap_resolution;
    const float* occluder_positions;
    uint32_t occluder_vertex_count;
    const uint32_t* occluder_indices;
    uint32_t occluder_index_count;
    double ground_origin_enu_m[2];
    double ground_cell_m;
    int32_t ground_columns, ground_rows;
    gusuku_image ground_geometry;
    const gusuku_slot* slots;
    uint32_t slot_count;
};

struct FrameInput01 {
    uint32_t struct_size;
    const uint8_t* camera_rgba8;
    VkImage camera_image;
    VkImageLayout camera_image_layout;
    gusuku_intrinsics intrinsics;
    gusuku_pose pose;
    double utc_unix_seconds;
    int32_t has_position;
    gusuku_geo_position position;
    gusuku_weather weather;
    float exposure;
    gusuku_render_mode mode;
    gusuku_colour_match colour_match;
    uint32_t flags;
};

struct FrameInfo01 {
    uint32_t struct_size;
    double sun_azimuth_deg, sun_apparent_elevation_deg;
    int32_t sun_above_horizon;
    double sun_direction_enu[3], sun_irradiance_rgb[3];
    int32_t slot_a, slot_b;
    float slot_b_weight;
    int32_t overcast_slot;
    float overcast_weight;
};

// The hand-written prefix is gusuku.h's, field by field.
#define GUSUKU_SAME_OFFSET(OLD, NEW, FIELD) \
    static_assert(offsetof(OLD, FIELD) == offsetof(NEW, FIELD), #NEW "." #FIELD " moved")
GUSUKU_SAME_OFFSET(RuntimeOptions01, gusuku_runtime_options, frame_width);
GUSUKU_SAME_OFFSET(RuntimeOptions01, gusuku_runtime_options, shadow_map_size);
GUSUKU_SAME_OFFSET(RuntimeOptions01, gusuku_runtime_options, shadow_pcf_radius);
GUSUKU_SAME_OFFSET(RuntimeOptions01, gusuku_runtime_options, colour_gain_limit);
GUSUKU_SAME_OFFSET(RuntimeOptions01, gusuku_runtime_options, direct_only_shadow_darkening);
GUSUKU_SAME_OFFSET(VulkanDevice01, gusuku_vulkan_device, instance);
GUSUKU_SAME_OFFSET(VulkanDevice01, gusuku_vulkan_device, queue_family_index);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, latitude_deg);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, positions);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, index_count);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, texture_count);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, lightmap_resolution);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, occluder_index_count);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, ground_origin_enu_m);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, ground_geometry);
GUSUKU_SAME_OFFSET(BakeSetDesc01, gusuku_bakeset_desc, slot_count);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, camera_rgba8);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, camera_image);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, camera_image_layout);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, intrinsics);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, pose);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, has_position);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, weather);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, colour_match);
GUSUKU_SAME_OFFSET(FrameInput01, gusuku_frame_input, flags);
GUSUKU_SAME_OFFSET(FrameInfo01, gusuku_frame_info, sun_azimuth_deg);
GUSUKU_SAME_OFFSET(FrameInfo01, gusuku_frame_info, sun_above_horizon);
GUSUKU_SAME_OFFSET(FrameInfo01, gusuku_frame_info, sun_irradiance_rgb);
GUSUKU_SAME_OFFSET(FrameInfo01, gusuku_frame_info, overcast_weight);
#undef GUSUKU_SAME_OFFSET

// API version 1's layouts on LP64 (x86_64, aarch64): the 0.1 prefixes' sizes and the appended fields' offsets.
#if UINTPTR_MAX == UINT64_MAX
static_assert(sizeof(RuntimeOptions01) == 44);
static_assert(offsetof(gusuku_runtime_options, shadow_sun_step_deg) == 44);
static_assert(offsetof(gusuku_runtime_options, ground_change_threshold) == 48);
static_assert(offsetof(gusuku_runtime_options, camera_format) == 52);
static_assert(offsetof(gusuku_runtime_options, frames_in_flight) == 64);
static_assert(offsetof(gusuku_runtime_options, msaa_samples) == 68);
static_assert(offsetof(gusuku_runtime_options, max_anisotropy) == 72);
static_assert(sizeof(VulkanDevice01) == 48 && sizeof(gusuku_vulkan_device) == 56);
static_assert(offsetof(gusuku_vulkan_device, instance_api_version) == 48);
static_assert(sizeof(BakeSetDesc01) == 224 && sizeof(gusuku_bakeset_desc) == 248);
static_assert(offsetof(gusuku_bakeset_desc, ground_albedo) == 224);
// API version 2 (alpha-masked materials).
static_assert(offsetof(gusuku_bakeset_desc, material_alpha_cutoffs) == 240);
static_assert(offsetof(gusuku_runtime_options, lightmap_format) == 76 &&
              offsetof(gusuku_runtime_options, texture_compression_astc_hdr) == 80);
// API version 3 (ASTC base-colour textures).
static_assert(offsetof(gusuku_runtime_options, texture_compression_astc_ldr) == 84);
// API version 6 (the zero-copy camera): the conversion handle makes the struct 8-byte aligned; version 3 ended at 88.
static_assert(offsetof(gusuku_runtime_options, camera_ycbcr_image) == 88 &&
              offsetof(gusuku_runtime_options, camera_ycbcr_chroma_filter) == 92 &&
              offsetof(gusuku_runtime_options, camera_ycbcr_conversion) == 96 && sizeof(gusuku_runtime_options) == 104);
static_assert(sizeof(FrameInput01) == 232 && offsetof(gusuku_frame_input, flags) == 224);
static_assert(offsetof(gusuku_frame_input, pose) == 72 && offsetof(gusuku_frame_input, exposure) == 212);
static_assert(offsetof(gusuku_frame_input, camera_luma) == 232);
static_assert(offsetof(gusuku_frame_input, camera_image_format) == 260 &&
              offsetof(gusuku_frame_input, signal_values) == 304);
// API version 4 (the sun apart from the sky).
static_assert(offsetof(gusuku_frame_input, sun_scale) == 312 && sizeof(gusuku_frame_input) == 320);
static_assert(sizeof(FrameInfo01) == 104 && sizeof(gusuku_frame_info) == 112);
static_assert(offsetof(gusuku_frame_info, ground_quads_drawn) == 100);
static_assert(offsetof(gusuku_frame_info, ground_quads_total) == 104);
static_assert(sizeof(gusuku_pass_timings) == 72 && offsetof(gusuku_pass_timings, total_ms) == 64);

// The enums' values are ABI too: gusuku 0.1's numbers, the C and C++ enums equal, and the paper's names
// (GUSUKU_MODE_PROPOSED, kPaper, ...) still aliases of today's (GUSUKU_MODE_BAKED_LIGHT, kReinhard, ...).
static_assert(GUSUKU_MODE_BAKED_LIGHT == 0 && GUSUKU_MODE_DIRECT_ONLY == 1);
static_assert(GUSUKU_MODE_PROPOSED == GUSUKU_MODE_BAKED_LIGHT);
static_assert(RenderMode::kProposed == RenderMode::kBakedLight);
static_assert(int(RenderMode::kBakedLight) == GUSUKU_MODE_BAKED_LIGHT &&
              int(RenderMode::kDirectOnly) == GUSUKU_MODE_DIRECT_ONLY);
static_assert(GUSUKU_COLOUR_MATCH_OFF == 0 && GUSUKU_COLOUR_MATCH_REINHARD == 1 && GUSUKU_COLOUR_MATCH_PRESERVE == 2 &&
              GUSUKU_COLOUR_MATCH_GROUND == 3 && GUSUKU_COLOUR_MATCH_AUTO == 4);
static_assert(GUSUKU_COLOUR_MATCH_PAPER == GUSUKU_COLOUR_MATCH_REINHARD);
static_assert(ColourMatch::kPaper == ColourMatch::kReinhard);
static_assert(int(ColourMatch::kOff) == GUSUKU_COLOUR_MATCH_OFF &&
              int(ColourMatch::kReinhard) == GUSUKU_COLOUR_MATCH_REINHARD &&
              int(ColourMatch::kPreserve) == GUSUKU_COLOUR_MATCH_PRESERVE &&
              int(ColourMatch::kGround) == GUSUKU_COLOUR_MATCH_GROUND &&
              int(ColourMatch::kAuto) == GUSUKU_COLOUR_MATCH_AUTO);
#endif

// ---------------------------------------------------------------------------------------------------------------

constexpr uint32_t kSize = 32;
constexpr uint8_t kBeyond = 0x7F;  // every byte past an old struct

/// An old struct at the start of a buffer as large as today's struct plus some, the rest kBeyond.
template <typename Old, typename Today>
struct OldInBuffer {
    std::vector<uint8_t> bytes = std::vector<uint8_t>(sizeof(Today) + 64, kBeyond);
    explicit OldInBuffer(const Old& old) { std::memcpy(bytes.data(), &old, sizeof old); }
    const Today* today() const { return reinterpret_cast<const Today*>(bytes.data()); }
    Today* today() { return reinterpret_cast<Today*>(bytes.data()); }
};

/// A 4 m wall facing south over a 4 x 4 ground grid whose light changes by 0.1% with the building: under the
/// default ground_change_threshold (1/255) no quad gets the ratio pass, under 0 every changed one does.
struct WallScene {
    float positions[12] = {-2, 0, 0, 2, 0, 0, 2, 0, 4, -2, 0, 4};
    float normals[12] = {0, -1, 0, 0, -1, 0, 0, -1, 0, 0, -1, 0};
    float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    uint32_t triangle_material[2] = {0, 0};
    gusuku_material grey = {{0.5f, 0.5f, 0.5f, 1.0f}, -1};
    std::vector<float> lightmap = std::vector<float>(2 * 2 * 4, 1.0f);
    std::vector<float> up, with, without;
    gusuku_slot overcast{};
    WallScene() {
        for (int i = 0; i < 16; ++i) {
            up.insert(up.end(), {0.0f, 0.0f, 1.0f, 0.0f});
            with.insert(with.end(), {1.0f, 1.0f, 1.0f, 1.0f});
            without.insert(without.end(), {1.001f, 1.001f, 1.001f, 1.0f});
        }
        overcast.sky = GUSUKU_SKY_OVERCAST;
        overcast.building = {2, 2, lightmap.data()};
        overcast.ground_with = {4, 4, with.data()};
        overcast.ground_without = {4, 4, without.data()};
    }
    BakeSetDesc01 desc() const {
        BakeSetDesc01 d{};
        d.struct_size = sizeof d;
        d.latitude_deg = 26.2856;
        d.longitude_deg = 127.8008;
        d.positions = positions;
        d.normals = normals;
        d.uv0 = d.uv1 = uv;
        d.vertex_count = 4;
        d.indices = indices;
        d.index_count = 6;
        d.triangle_material = triangle_material;
        d.materials = &grey;
        d.material_count = 1;
        d.lightmap_resolution = 2;
        d.ground_origin_enu_m[0] = d.ground_origin_enu_m[1] = -8.0;
        d.ground_cell_m = 4.0;
        d.ground_columns = d.ground_rows = 4;
        d.ground_geometry = {4, 4, up.data()};
        d.slots = &overcast;
        d.slot_count = 1;
        return d;
    }
};

/// A frame 10 m south of the wall at 2 m looking north, overcast, the 0.1 fields filled by hand.
FrameInput01 frame01(const uint8_t* camera) {
    FrameInput01 frame{};
    frame.struct_size = sizeof frame;
    frame.camera_rgba8 = camera;
    frame.camera_image_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    frame.intrinsics = {16.0, 16.0, kSize / 2.0, kSize / 2.0, kSize, kSize};
    frame.pose = {{0.0, -10.0, 2.0}, {1, 0, 0, 0, 0, 1, 0, -1, 0}};
    frame.utc_unix_seconds = 1782000000.0;
    frame.weather.cloud_cover = 1.0f;
    frame.exposure = 1.0f;
    frame.mode = GUSUKU_MODE_PROPOSED;  // 0.1's spelling, kept as an alias of GUSUKU_MODE_BAKED_LIGHT
    frame.colour_match = GUSUKU_COLOUR_MATCH_OFF;
    frame.flags = GUSUKU_FRAME_BLEND_SLOTS | GUSUKU_FRAME_GROUND_RATIO;
    return frame;
}

RuntimeOptions01 options01() {
    RuntimeOptions01 options{sizeof(RuntimeOptions01), kSize, kSize, 64, 1.5f, 1, 8, 8.0f, 2.0f, 1.0f, 0.6f};
    return options;
}

struct Rendered {
    std::vector<uint8_t> composite = std::vector<uint8_t>(size_t(kSize) * kSize * 4);
    gusuku_frame_info info{};
};

class CApiVersionsTest : public testing::GpuTest {
protected:
    gusuku_vulkan_device device() {
        return {sizeof(gusuku_vulkan_device), context().instance(), context().physicalDevice(), context().device(),
                context().queue(), context().queueFamily()};
    }

    /// Opens a runtime with `options` on the test's device, renders `frame` into a full info, closes it.
    Rendered render(const gusuku_vulkan_device* vulkan, const gusuku_bakeset* set,
                    const gusuku_runtime_options* options, const gusuku_frame_input* frame) {
        Rendered rendered;
        gusuku_runtime* runtime = nullptr;
        EXPECT_EQ(gusuku_runtime_open(vulkan, set, options, &runtime), GUSUKU_OK) << gusuku_last_error_message();
        if (runtime == nullptr) return rendered;
        rendered.info.struct_size = sizeof rendered.info;
        EXPECT_EQ(gusuku_runtime_render(runtime, frame, rendered.composite.data(), &rendered.info), GUSUKU_OK)
            << gusuku_runtime_last_error(runtime);
        EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
        return rendered;
    }
};

// API version 2's field: material_alpha_cutoffs is read (a cutoff in [0, 1] or a negative one, opaque, is accepted;
// above 1 or NaN is refused naming the material); an older layout reads it as NULL (the test below).
TEST_F(CApiVersionsTest, MaterialAlphaCutoffsAreReadAndCheckedFromVersion2) {
    const WallScene scene;
    gusuku_bakeset_desc desc;
    std::memset(&desc, 0, sizeof desc);
    const BakeSetDesc01 old = scene.desc();
    std::memcpy(&desc, &old, sizeof old);
    desc.struct_size = sizeof desc;
    for (const float cutoff : {0.25f, -1.0f}) {
        desc.material_alpha_cutoffs = &cutoff;
        gusuku_bakeset* bake_set = nullptr;
        ASSERT_EQ(gusuku_bakeset_create(&desc, &bake_set), GUSUKU_OK) << gusuku_last_error_message();
        EXPECT_EQ(gusuku_bakeset_free(bake_set), GUSUKU_OK);
    }
    for (const float bad : {1.5f, NAN}) {
        desc.material_alpha_cutoffs = &bad;
        gusuku_bakeset* bake_set = nullptr;
        EXPECT_EQ(gusuku_bakeset_create(&desc, &bake_set), GUSUKU_ERROR_INVALID_BAKE_SET);
        EXPECT_NE(std::string(gusuku_last_error_message()).find("building.materials[0].alpha_cutoff: "),
                  std::string::npos)
            << gusuku_last_error_message();
    }
}

// API version 2's options: lightmap_format and texture_compression_astc_hdr are read and checked, and
// gusuku_runtime_lightmap_format reports what open chose; a version-1 layout, whose bytes past it are kBeyond
// (0x7F7F7F7F would be refused as a format), takes the default, AUTO, which is E5B9G9R9 on a device that does not
// sample ASTC HDR or a bake set without its blocks (this one).
TEST_F(CApiVersionsTest, LightmapFormatIsReadFromVersion2AndDefaultsBeforeIt) {
    const WallScene scene;
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    gusuku_bakeset* set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &set), GUSUKU_OK) << gusuku_last_error_message();
    const gusuku_vulkan_device vulkan = device();
    const auto formatOpened = [&](const gusuku_runtime_options* options, gusuku_lightmap_format* format) {
        gusuku_runtime* runtime = nullptr;
        const gusuku_result result = gusuku_runtime_open(&vulkan, set, options, &runtime);
        if (result == GUSUKU_OK) {
            EXPECT_EQ(gusuku_runtime_lightmap_format(runtime, format), GUSUKU_OK);
            EXPECT_EQ(gusuku_runtime_lightmap_format(runtime, nullptr), GUSUKU_ERROR_INVALID_ARGUMENT);
            EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
        }
        return result;
    };
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    EXPECT_EQ(options.lightmap_format, GUSUKU_LIGHTMAP_AUTO);
    EXPECT_EQ(options.texture_compression_astc_hdr, 0u);
    options.frame_width = options.frame_height = kSize;
    options.shadow_map_size = 64;

    gusuku_lightmap_format format = GUSUKU_LIGHTMAP_RGBA32F;
    std::vector<uint8_t> version1(sizeof options + 64, kBeyond);
    std::memcpy(version1.data(), &options, offsetof(gusuku_runtime_options, lightmap_format));
    reinterpret_cast<gusuku_runtime_options*>(version1.data())->struct_size =
        uint32_t(offsetof(gusuku_runtime_options, lightmap_format));
    EXPECT_EQ(formatOpened(reinterpret_cast<const gusuku_runtime_options*>(version1.data()), &format), GUSUKU_OK)
        << gusuku_last_error_message();
    EXPECT_EQ(format, GUSUKU_LIGHTMAP_E5B9G9R9);

    options.lightmap_format = GUSUKU_LIGHTMAP_RGBA16F;
    EXPECT_EQ(formatOpened(&options, &format), GUSUKU_OK) << gusuku_last_error_message();
    EXPECT_EQ(format, GUSUKU_LIGHTMAP_RGBA16F);

    // ASTC without the app's word that it enabled the feature, and a value past the enum: refused by name.
    options.lightmap_format = GUSUKU_LIGHTMAP_ASTC_4X4_HDR;
    EXPECT_EQ(formatOpened(&options, &format), GUSUKU_ERROR_DEVICE);
    EXPECT_NE(std::string(gusuku_last_error_message()).find("options.lightmap_format: "), std::string::npos)
        << gusuku_last_error_message();
    options.lightmap_format = gusuku_lightmap_format(9);
    EXPECT_EQ(formatOpened(&options, &format), GUSUKU_ERROR_INVALID_FRAME);
    EXPECT_NE(std::string(gusuku_last_error_message()).find("options.lightmap_format: 9"), std::string::npos)
        << gusuku_last_error_message();
    EXPECT_EQ(gusuku_runtime_lightmap_format(nullptr, &format), GUSUKU_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(gusuku_bakeset_free(set), GUSUKU_OK);
}

TEST_F(CApiVersionsTest, TheOldestLayoutsGiveTodaysFrameWithTodaysDefaults) {
    const WallScene scene;
    std::vector<uint8_t> camera(size_t(kSize) * kSize * 4, 30);
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    const OldInBuffer<RuntimeOptions01, gusuku_runtime_options> old_options(options01());
    const OldInBuffer<FrameInput01, gusuku_frame_input> old_frame(frame01(camera.data()));
    const gusuku_vulkan_device today_device = device();
    VulkanDevice01 device01;
    std::memcpy(&device01, &today_device, sizeof device01);
    const OldInBuffer<VulkanDevice01, gusuku_vulkan_device> old_device(device01);

    // Today's structs, from the defaults.
    gusuku_bakeset_desc desc;
    std::memset(&desc, 0, sizeof desc);
    std::memcpy(&desc, &old_desc.bytes[0], sizeof(BakeSetDesc01));
    desc.struct_size = sizeof desc;
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    options.frame_width = options.frame_height = kSize;
    options.shadow_map_size = 64;
    gusuku_frame_input frame;
    ASSERT_EQ(gusuku_frame_input_default(&frame), GUSUKU_OK);
    std::memcpy(&frame, &old_frame.bytes[0], sizeof(FrameInput01));
    frame.struct_size = sizeof frame;

    gusuku_bakeset *old_set = nullptr, *today_set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &old_set), GUSUKU_OK) << gusuku_last_error_message();
    ASSERT_EQ(gusuku_bakeset_create(&desc, &today_set), GUSUKU_OK) << gusuku_last_error_message();
    const Rendered old = render(old_device.today(), old_set, old_options.today(), old_frame.today());
    const Rendered today = render(&today_device, today_set, &options, &frame);
    options.ground_change_threshold = 0.0f;  // the control: an appended option that changes the frame
    const Rendered control = render(&today_device, today_set, &options, &frame);
    EXPECT_EQ(gusuku_bakeset_free(old_set), GUSUKU_OK);
    EXPECT_EQ(gusuku_bakeset_free(today_set), GUSUKU_OK);

    EXPECT_TRUE(old.composite == today.composite) << "the 0.1 layouts' frame differs from today's defaults'";
    EXPECT_EQ(old.info.ground_quads_total, 9u);  // (4 - 1)^2
    EXPECT_EQ(old.info.ground_quads_drawn, 0u);
    EXPECT_EQ(today.info.ground_quads_drawn, 0u);
    EXPECT_EQ(control.info.ground_quads_drawn, 9u) << "ground_change_threshold 0 should draw every changed quad";
    EXPECT_EQ(old.info.overcast_slot, 0);
    EXPECT_EQ(old.info.overcast_weight, today.info.overcast_weight);
    EXPECT_EQ(old.info.sun_azimuth_deg, today.info.sun_azimuth_deg);
}

TEST_F(CApiVersionsTest, AnOldFrameInfoIsWrittenOnlyAsFarAsItsSize) {
    const WallScene scene;
    std::vector<uint8_t> camera(size_t(kSize) * kSize * 4, 30);
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    const OldInBuffer<RuntimeOptions01, gusuku_runtime_options> old_options(options01());
    const OldInBuffer<FrameInput01, gusuku_frame_input> old_frame(frame01(camera.data()));
    // The app's old info: its struct_size, then kBeyond everywhere, its tail padding included.
    FrameInfo01 info01;
    std::memset(&info01, kBeyond, sizeof info01);
    info01.struct_size = sizeof info01;
    OldInBuffer<FrameInfo01, gusuku_frame_info> old_info(info01);

    gusuku_bakeset* set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &set), GUSUKU_OK) << gusuku_last_error_message();
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime* runtime = nullptr;
    ASSERT_EQ(gusuku_runtime_open(&vulkan, set, old_options.today(), &runtime), GUSUKU_OK)
        << gusuku_last_error_message();
    EXPECT_EQ(gusuku_bakeset_free(set), GUSUKU_OK);
    ASSERT_EQ(gusuku_runtime_render(runtime, old_frame.today(), nullptr, old_info.today()), GUSUKU_OK)
        << gusuku_runtime_last_error(runtime);
    FrameInfo01 written;
    std::memcpy(&written, old_info.bytes.data(), sizeof written);
    EXPECT_EQ(written.struct_size, sizeof(FrameInfo01));
    EXPECT_EQ(written.overcast_slot, 0);
    EXPECT_EQ(written.overcast_weight, 1.0f);
    const size_t fields_end = offsetof(FrameInfo01, overcast_weight) + sizeof(float);
    size_t written_past_fields = 0;
    for (size_t i = fields_end; i < old_info.bytes.size(); ++i) written_past_fields += old_info.bytes[i] != kBeyond;
    EXPECT_EQ(written_past_fields, 0u) << "bytes past the 0.1 info's fields were written";

    // Sizes no layout has are refused, naming the struct and the sizes it takes.
    FrameInput01 frame = frame01(camera.data());
    frame.struct_size = sizeof frame - 4;
    EXPECT_EQ(gusuku_runtime_render(runtime, reinterpret_cast<const gusuku_frame_input*>(&frame), nullptr, nullptr),
              GUSUKU_ERROR_INVALID_ARGUMENT);
    const std::string too_small = gusuku_runtime_last_error(runtime);
    EXPECT_EQ(too_small.rfind("gusuku_runtime_render: frame.struct_size: " + std::to_string(sizeof frame - 4) +
                                  " is not the size of any gusuku_frame_input this library knows (",
                              0),
              0u)
        << too_small;
    EXPECT_NE(too_small.find("set it to sizeof(gusuku_frame_input)"), std::string::npos) << too_small;
    old_info.today()->struct_size = sizeof(gusuku_frame_info) + 8;
    EXPECT_EQ(gusuku_runtime_render(runtime, old_frame.today(), nullptr, old_info.today()),
              GUSUKU_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(gusuku_runtime_last_error(runtime)).find("info.struct_size"), std::string::npos);
    EXPECT_NE(std::string(gusuku_runtime_last_error(runtime)).find("newer gusuku.h"), std::string::npos);
    EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);

    RuntimeOptions01 options = options01();
    options.struct_size = sizeof options - 4;
    EXPECT_EQ(gusuku_runtime_options_fill_defaults(reinterpret_cast<gusuku_runtime_options*>(&options)),
              GUSUKU_ERROR_INVALID_ARGUMENT);
    const std::string message = gusuku_last_error_message();
    EXPECT_NE(message.find("options.struct_size: 40 is not the size of any gusuku_runtime_options this library "
                           "knows (44, 76, 84, 88 or 104 bytes)"),
              std::string::npos)
        << message;
}


// API version 3's option texture_compression_astc_ldr: 0 by default; a version-2 layout (its bytes past it
// kBeyond, which read as nonzero) opens as the default; gusuku_runtime_astc_texture_count says how many textures
// are drawn from ASTC blocks (none here: the wall has no texture, and lavapipe samples no ASTC).
// API version 4's field: sun_scale is read from a frame of today's size (NaN and above 2 refused, naming it), and
// a frame of version 1's size, with 0x7F bytes where sun_scale would be (3.4e38, which would be refused), takes
// the default (-1: the sun follows the cover) and renders as today's default frame does.
TEST_F(CApiVersionsTest, SunScaleIsReadFromVersion4AndDefaultsBeforeIt) {
    const WallScene scene;
    std::vector<uint8_t> camera(size_t(kSize) * kSize * 4, 30);
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    gusuku_bakeset* set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &set), GUSUKU_OK) << gusuku_last_error_message();
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    options.frame_width = options.frame_height = kSize;
    options.shadow_map_size = 64;
    gusuku_frame_input frame;
    ASSERT_EQ(gusuku_frame_input_default(&frame), GUSUKU_OK);
    EXPECT_EQ(frame.sun_scale, -1.0f);
    const FrameInput01 frame_fields = frame01(camera.data());
    std::memcpy(&frame, &frame_fields, sizeof frame_fields);
    frame.struct_size = sizeof frame;
    std::vector<uint8_t> version1(sizeof frame + 64, kBeyond);
    std::memcpy(version1.data(), &frame, offsetof(gusuku_frame_input, sun_scale));
    reinterpret_cast<gusuku_frame_input*>(version1.data())->struct_size =
        uint32_t(offsetof(gusuku_frame_input, sun_scale));
    const Rendered today = render(&vulkan, set, &options, &frame);
    const Rendered old = render(&vulkan, set, &options, reinterpret_cast<const gusuku_frame_input*>(version1.data()));
    EXPECT_TRUE(old.composite == today.composite) << "version 1's frame differs from today's default frame";

    gusuku_runtime* runtime = nullptr;
    ASSERT_EQ(gusuku_runtime_open(&vulkan, set, &options, &runtime), GUSUKU_OK) << gusuku_last_error_message();
    std::vector<uint8_t> output(camera.size());
    for (float bad : {std::nanf(""), 2.5f}) {
        frame.sun_scale = bad;
        EXPECT_EQ(gusuku_runtime_render(runtime, &frame, output.data(), nullptr), GUSUKU_ERROR_INVALID_FRAME);
        EXPECT_NE(std::string(gusuku_runtime_last_error(runtime)).find("weather.sun_scale"), std::string::npos)
            << gusuku_runtime_last_error(runtime);
    }
    frame.sun_scale = 1.0f;
    EXPECT_EQ(gusuku_runtime_render(runtime, &frame, output.data(), nullptr), GUSUKU_OK)
        << gusuku_runtime_last_error(runtime);
    EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
    EXPECT_EQ(gusuku_bakeset_free(set), GUSUKU_OK);
}

TEST_F(CApiVersionsTest, AstcTextureOptionIsReadFromVersion3AndDefaultsBeforeIt) {
    const WallScene scene;
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    gusuku_bakeset* set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &set), GUSUKU_OK) << gusuku_last_error_message();
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    EXPECT_EQ(options.texture_compression_astc_ldr, 0u);
    EXPECT_EQ(options.struct_size, 104u);
    options.frame_width = options.frame_height = kSize;
    options.shadow_map_size = 64;
    std::vector<uint8_t> version2(sizeof options + 64, kBeyond);
    std::memcpy(version2.data(), &options, offsetof(gusuku_runtime_options, texture_compression_astc_ldr));
    reinterpret_cast<gusuku_runtime_options*>(version2.data())->struct_size =
        uint32_t(offsetof(gusuku_runtime_options, texture_compression_astc_ldr));
    options.texture_compression_astc_ldr = 1;
    const gusuku_runtime_options* layouts[2] = {reinterpret_cast<const gusuku_runtime_options*>(version2.data()),
                                                &options};
    for (const gusuku_runtime_options* given : layouts) {
        gusuku_runtime* runtime = nullptr;
        ASSERT_EQ(gusuku_runtime_open(&vulkan, set, given, &runtime), GUSUKU_OK) << gusuku_last_error_message();
        uint32_t count = 99;
        EXPECT_EQ(gusuku_runtime_astc_texture_count(runtime, &count), GUSUKU_OK);
        EXPECT_EQ(count, 0u);
        EXPECT_EQ(gusuku_runtime_astc_texture_count(runtime, nullptr), GUSUKU_ERROR_INVALID_ARGUMENT);
        EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
    }
    EXPECT_EQ(gusuku_runtime_astc_texture_count(nullptr, nullptr), GUSUKU_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(gusuku_bakeset_free(set), GUSUKU_OK);
}

// API version 6's zero-copy camera options: 0, NEAREST and no conversion by default; read from a layout of today's
// size (camera_ycbcr_image with an RGBA8 camera refused naming it, whatever the device); a version-3 layout, whose
// bytes past it are kBeyond (a nonzero camera_ycbcr_image, which would be refused so), opens with the defaults.
TEST_F(CApiVersionsTest, ZeroCopyCameraOptionsAreReadFromVersion6AndDefaultBeforeIt) {
    const WallScene scene;
    const OldInBuffer<BakeSetDesc01, gusuku_bakeset_desc> old_desc(scene.desc());
    gusuku_bakeset* set = nullptr;
    ASSERT_EQ(gusuku_bakeset_create(old_desc.today(), &set), GUSUKU_OK) << gusuku_last_error_message();
    const gusuku_vulkan_device vulkan = device();
    gusuku_runtime_options options;
    ASSERT_EQ(gusuku_runtime_options_default(&options), GUSUKU_OK);
    EXPECT_EQ(options.camera_ycbcr_image, 0u);
    EXPECT_EQ(options.camera_ycbcr_chroma_filter, VK_FILTER_NEAREST);
    EXPECT_TRUE(options.camera_ycbcr_conversion == VK_NULL_HANDLE);
    options.frame_width = options.frame_height = kSize;
    options.shadow_map_size = 64;
    std::vector<uint8_t> version3(sizeof options + 64, kBeyond);
    std::memcpy(version3.data(), &options, offsetof(gusuku_runtime_options, camera_ycbcr_image));
    reinterpret_cast<gusuku_runtime_options*>(version3.data())->struct_size =
        uint32_t(offsetof(gusuku_runtime_options, camera_ycbcr_image));
    gusuku_runtime* runtime = nullptr;
    ASSERT_EQ(gusuku_runtime_open(&vulkan, set, reinterpret_cast<const gusuku_runtime_options*>(version3.data()),
                                  &runtime),
              GUSUKU_OK)
        << gusuku_last_error_message();
    EXPECT_EQ(gusuku_runtime_close(runtime), GUSUKU_OK);
    options.camera_ycbcr_image = 1;
    EXPECT_EQ(gusuku_runtime_open(&vulkan, set, &options, &runtime), GUSUKU_ERROR_INVALID_FRAME);
    EXPECT_NE(std::string(gusuku_last_error_message()).find("options.camera_ycbcr_image: needs"), std::string::npos)
        << gusuku_last_error_message();
    EXPECT_EQ(gusuku_bakeset_free(set), GUSUKU_OK);
}

}  // namespace
}  // namespace gusuku
