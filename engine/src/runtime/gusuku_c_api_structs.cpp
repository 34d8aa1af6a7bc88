// The C API's structs: which struct_size values are accepted (gusuku_c_api_sizes.h's tables), today's defaults,
// and the conversions to and from the C++ runtime's structs, field by field in the order gusuku.h declares them.
#include "gusuku_c_api_structs.h"

#include <cstring>
#include <string>

#include "gusuku_c_api_sizes.h"

namespace gusuku::c_api_detail {

// The C enums are the C++ ones by value (the conversions below cast), pinned here where both are in view.
static_assert(GUSUKU_LIGHTMAP_E5B9G9R9 == int(LightmapFormat::kE5b9g9r9) &&
              GUSUKU_LIGHTMAP_RGBA16F == int(LightmapFormat::kRgba16f) &&
              GUSUKU_LIGHTMAP_RGBA32F == int(LightmapFormat::kRgba32f) &&
              GUSUKU_LIGHTMAP_ASTC_4X4_HDR == int(LightmapFormat::kAstc4x4Hdr) &&
              GUSUKU_LIGHTMAP_AUTO == int(LightmapFormat::kAuto));
static_assert(GUSUKU_CAMERA_RGBA8 == int(CameraFormat::kRgba8) && GUSUKU_CAMERA_BGRA8 == int(CameraFormat::kBgra8) &&
              GUSUKU_CAMERA_NV12 == int(CameraFormat::kNv12) && GUSUKU_CAMERA_NV21 == int(CameraFormat::kNv21));

namespace {

/// "104 or 112" / "44, 52 or 60": the sizes of a struct's layouts, for a message.
std::string listSizes(std::span<const StructLayout> layouts) {
    std::string list;
    for (size_t k = 0; k < layouts.size(); ++k) {
        if (k > 0) list += k + 1 == layouts.size() ? " or " : ", ";
        list += std::to_string(layouts[k].size());
    }
    return list;
}

}  // namespace

std::string findSizeProblem(uint32_t struct_size, const char* argument, const char* struct_name,
                            std::span<const StructLayout> layouts, size_t& field_bytes) {
    for (const StructLayout& layout : layouts)
        if (struct_size == layout.size()) {
            field_bytes = layout.fields_end;
            return {};
        }
    std::string problem = std::string(argument) + ".struct_size: " + std::to_string(struct_size) +
                          " is not the size of any " + struct_name + " this library knows (" + listSizes(layouts) +
                          " bytes): ";
    if (struct_size > layouts.back().size())
        return problem + "the app was built against a newer gusuku.h than the library it links";
    return problem + "set it to sizeof(" + struct_name + ")";
}

gusuku_runtime_options defaultOptions() {
    const RuntimeOptions defaults;
    gusuku_runtime_options options;
    std::memset(&options, 0, sizeof options);
    options.struct_size = sizeof options;
    options.frame_width = defaults.frame_width;
    options.frame_height = defaults.frame_height;
    options.shadow_map_size = defaults.shadow_map_size;
    options.shadow_bias_texels = defaults.shadow_bias_texels;
    options.shadow_pcf_radius = defaults.shadow_pcf_radius;
    options.statistics_stride = defaults.statistics_stride;
    options.statistics_smoothing_frames = defaults.statistics_smoothing_frames;
    options.colour_gain_limit = defaults.colour_gain_limit;
    options.direct_only_ambient_fraction = defaults.direct_only_ambient_fraction;
    options.direct_only_shadow_darkening = defaults.direct_only_shadow_darkening;
    options.shadow_sun_step_deg = defaults.shadow_sun_step_deg;
    options.ground_change_threshold = defaults.ground_change_threshold;
    options.camera_format = gusuku_camera_format(defaults.camera_format);
    options.camera_ycbcr_model = gusuku_ycbcr_model(defaults.camera_ycbcr_model);
    options.camera_ycbcr_range = gusuku_ycbcr_range(defaults.camera_ycbcr_range);
    options.frames_in_flight = defaults.frames_in_flight;
    options.msaa_samples = defaults.msaa_samples;
    options.max_anisotropy = defaults.max_anisotropy;
    options.lightmap_format = gusuku_lightmap_format(defaults.lightmap_format);
    options.texture_compression_astc_hdr = defaults.texture_compression_astc_hdr ? 1u : 0u;
    options.texture_compression_astc_ldr = defaults.texture_compression_astc_ldr ? 1u : 0u;
    options.camera_ycbcr_image = defaults.camera_ycbcr_image ? 1u : 0u;
    options.camera_ycbcr_chroma_filter = defaults.camera_ycbcr_chroma_filter;
    options.camera_ycbcr_conversion = defaults.camera_ycbcr_conversion;
    return options;
}

gusuku_frame_input defaultFrame() {
    const FrameInput defaults;
    gusuku_frame_input frame;
    std::memset(&frame, 0, sizeof frame);
    frame.struct_size = sizeof frame;
    frame.camera_image = VK_NULL_HANDLE;
    frame.camera_image_layout = defaults.camera_image_layout;
    frame.camera_image_format = defaults.camera_image_format;
    frame.pose = convertPose(defaults.pose);
    frame.utc_unix_seconds = defaults.utc_unix_seconds;
    frame.weather.cloud_cover = defaults.weather.cloud_cover;
    frame.sun_scale = defaults.weather.sun_scale;
    frame.exposure = defaults.exposure;
    frame.mode = GUSUKU_MODE_BAKED_LIGHT;
    frame.colour_match = GUSUKU_COLOUR_MATCH_AUTO;  // FrameInput's ColourMatch::kAuto
    frame.flags = (defaults.blend_slots ? GUSUKU_FRAME_BLEND_SLOTS : 0u) |
                  (defaults.ground_ratio ? GUSUKU_FRAME_GROUND_RATIO : 0u);
    return frame;
}

RuntimeOptions convertOptions(const gusuku_runtime_options& options) {
    RuntimeOptions converted;
    converted.frame_width = options.frame_width;
    converted.frame_height = options.frame_height;
    converted.shadow_map_size = options.shadow_map_size;
    converted.shadow_bias_texels = options.shadow_bias_texels;
    converted.shadow_pcf_radius = options.shadow_pcf_radius;
    converted.statistics_stride = options.statistics_stride;
    converted.statistics_smoothing_frames = options.statistics_smoothing_frames;
    converted.colour_gain_limit = options.colour_gain_limit;
    converted.direct_only_ambient_fraction = options.direct_only_ambient_fraction;
    converted.direct_only_shadow_darkening = options.direct_only_shadow_darkening;
    converted.shadow_sun_step_deg = options.shadow_sun_step_deg;
    converted.ground_change_threshold = options.ground_change_threshold;
    // Out-of-range enum values pass through and are refused, by name, when the runtime checks its options.
    converted.camera_format = CameraFormat(options.camera_format);
    converted.camera_ycbcr_model = YcbcrModel(options.camera_ycbcr_model);
    converted.camera_ycbcr_range = YcbcrRange(options.camera_ycbcr_range);
    converted.frames_in_flight = options.frames_in_flight;
    converted.msaa_samples = options.msaa_samples;
    converted.max_anisotropy = options.max_anisotropy;
    converted.lightmap_format = LightmapFormat(options.lightmap_format);
    converted.texture_compression_astc_hdr = options.texture_compression_astc_hdr != 0;
    converted.texture_compression_astc_ldr = options.texture_compression_astc_ldr != 0;
    converted.camera_ycbcr_image = options.camera_ycbcr_image != 0;
    converted.camera_ycbcr_chroma_filter = options.camera_ycbcr_chroma_filter;
    converted.camera_ycbcr_conversion = options.camera_ycbcr_conversion;
    return converted;
}

CameraIntrinsics convertIntrinsics(const gusuku_intrinsics& intrinsics) {
    return {intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy, intrinsics.width, intrinsics.height};
}

CameraPose convertPose(const gusuku_pose& pose) {
    CameraPose converted;
    converted.position_enu = glm::dvec3(pose.position_enu[0], pose.position_enu[1], pose.position_enu[2]);
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            converted.camera_to_enu[column][row] = pose.camera_to_enu[3 * row + column];
    return converted;
}

gusuku_pose convertPose(const CameraPose& pose) {
    gusuku_pose converted;
    for (int i = 0; i < 3; ++i) converted.position_enu[i] = pose.position_enu[i];
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            converted.camera_to_enu[3 * row + column] = pose.camera_to_enu[column][row];
    return converted;
}

std::string convertFrame(const gusuku_frame_input& frame, FrameInput& converted) {
    converted.camera_rgba8 = frame.camera_rgba8;
    converted.camera_image = frame.camera_image;
    converted.camera_image_layout = frame.camera_image_layout;
    converted.camera_image_format = frame.camera_image_format;
    converted.camera_row_bytes = frame.camera_row_bytes;
    converted.camera_luma = frame.camera_luma;
    converted.camera_chroma = frame.camera_chroma;
    converted.camera_luma_row_bytes = frame.camera_luma_row_bytes;
    converted.camera_chroma_row_bytes = frame.camera_chroma_row_bytes;
    converted.sync.wait_count = frame.wait_semaphore_count;
    converted.sync.wait_semaphores = frame.wait_semaphores;
    converted.sync.wait_values = frame.wait_values;
    converted.sync.wait_stages = frame.wait_stages;
    converted.sync.signal_count = frame.signal_semaphore_count;
    converted.sync.signal_semaphores = frame.signal_semaphores;
    converted.sync.signal_values = frame.signal_values;
    converted.intrinsics = convertIntrinsics(frame.intrinsics);
    converted.pose = convertPose(frame.pose);
    converted.utc_unix_seconds = frame.utc_unix_seconds;
    if (frame.has_position)
        converted.position = GeoPosition{frame.position.latitude_deg, frame.position.longitude_deg,
                                         frame.position.height_m};
    converted.weather.cloud_cover = frame.weather.cloud_cover;
    converted.weather.sun_scale = frame.sun_scale;
    converted.exposure = frame.exposure;
    switch (frame.mode) {
    case GUSUKU_MODE_BAKED_LIGHT: converted.mode = RenderMode::kBakedLight; break;
    case GUSUKU_MODE_DIRECT_ONLY: converted.mode = RenderMode::kDirectOnly; break;
    default: return "mode: " + std::to_string(int(frame.mode)) + " is not a gusuku_render_mode";
    }
    switch (frame.colour_match) {
    case GUSUKU_COLOUR_MATCH_OFF: converted.colour_match = ColourMatch::kOff; break;
    case GUSUKU_COLOUR_MATCH_REINHARD: converted.colour_match = ColourMatch::kReinhard; break;
    case GUSUKU_COLOUR_MATCH_PRESERVE: converted.colour_match = ColourMatch::kPreserve; break;
    case GUSUKU_COLOUR_MATCH_GROUND: converted.colour_match = ColourMatch::kGround; break;
    case GUSUKU_COLOUR_MATCH_AUTO: converted.colour_match = ColourMatch::kAuto; break;
    default: return "colour_match: " + std::to_string(int(frame.colour_match)) + " is not a gusuku_colour_match";
    }
    const uint32_t known = GUSUKU_FRAME_BLEND_SLOTS | GUSUKU_FRAME_GROUND_RATIO;
    if ((frame.flags & ~known) != 0) return "flags: unknown bits " + std::to_string(frame.flags & ~known);
    converted.blend_slots = (frame.flags & GUSUKU_FRAME_BLEND_SLOTS) != 0;
    converted.ground_ratio = (frame.flags & GUSUKU_FRAME_GROUND_RATIO) != 0;
    return {};
}

gusuku_frame_info convertInfo(const FrameInfo& info) {
    gusuku_frame_info out;
    std::memset(&out, 0, sizeof out);
    out.struct_size = sizeof out;
    out.sun_azimuth_deg = info.sun_azimuth_deg;
    out.sun_apparent_elevation_deg = info.sun_apparent_elevation_deg;
    out.sun_above_horizon = info.sun_above_horizon ? 1 : 0;
    for (int c = 0; c < 3; ++c) {
        out.sun_direction_enu[c] = info.sun_direction_enu[c];
        out.sun_irradiance_rgb[c] = info.sun_irradiance_rgb[c];
    }
    out.slot_a = info.slot_a;
    out.slot_b = info.slot_b;
    out.slot_b_weight = info.slot_b_weight;
    out.overcast_slot = info.overcast_slot;
    out.overcast_weight = info.overcast_weight;
    out.ground_quads_drawn = info.ground_quads_drawn;
    out.ground_quads_total = info.ground_quads_total;
    return out;
}

gusuku_pass_timings convertTimings(const PassTimings& timings) {
    gusuku_pass_timings out;
    std::memset(&out, 0, sizeof out);
    out.struct_size = sizeof out;
    out.upload_ms = timings.upload_ms;
    out.shadow_ms = timings.shadow_ms;
    out.occluder_ms = timings.occluder_ms;
    out.building_ms = timings.building_ms;
    out.ground_ms = timings.ground_ms;
    out.statistics_ms = timings.statistics_ms;
    out.readback_ms = timings.readback_ms;
    out.total_ms = timings.total_ms;
    return out;
}

}  // namespace gusuku::c_api_detail
