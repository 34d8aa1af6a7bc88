// The C API (gusuku.h) over the C++ runtime (runtime.h): C structs in, C++ structs through, and every exception
// caught at the boundary and turned into a code and a one-line message.
#include "gusuku/runtime/gusuku.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <numbers>
#include <string>
#include <tuple>

#include "gusuku/maths/bakeset_validate.h"
#include "gusuku/maths/input_error.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/runtime/runtime_version.h"
#include "gusuku_c_api_detail.h"

/// The runtime handle. The C++ runtime holds a reference to the device view, so the view lives here, beside it,
/// at an address that never moves.
struct gusuku_runtime {
    gusuku::GpuDevice gpu;
    std::unique_ptr<gusuku::Runtime> runtime;
    mutable gusuku::c_api_detail::MessageBuffer last_error;  // written by failing calls, const ones too
};

namespace gusuku::c_api_detail {

namespace {

thread_local MessageBuffer t_thread_message;

gusuku_result codeOf(RuntimeErrorCode code) {
    switch (code) {
    case RuntimeErrorCode::kInvalidBakeSet: return GUSUKU_ERROR_INVALID_BAKE_SET;
    case RuntimeErrorCode::kInvalidFrame: return GUSUKU_ERROR_INVALID_FRAME;
    case RuntimeErrorCode::kDevice: return GUSUKU_ERROR_DEVICE;
    case RuntimeErrorCode::kOutOfMemory: return GUSUKU_ERROR_OUT_OF_MEMORY;
    }
    return GUSUKU_ERROR_INTERNAL;
}

/// "context: message" into a local buffer, then recorded; no allocation.
gusuku_result failWithContext(gusuku_result code, const char* context, const char* message,
                              MessageBuffer* handle_message) noexcept {
    char text[GUSUKU_MESSAGE_CAPACITY];
    std::snprintf(text, sizeof text, "%s: %s", context, message);
    return fail(code, text, handle_message);
}

}  // namespace

void MessageBuffer::set(const char* message) noexcept {
    size_t length = 0;
    for (; message != nullptr && message[length] != '\0' && length + 1 < sizeof text; ++length)
        text[length] = (message[length] == '\n' || message[length] == '\r') ? ' ' : message[length];
    text[length] = '\0';
}

gusuku_result fail(gusuku_result code, const char* message, MessageBuffer* handle_message) noexcept {
    t_thread_message.set(message);
    if (handle_message != nullptr) handle_message->set(message);
    return code;
}

gusuku_result failFromCurrentException(const char* context, MessageBuffer* handle_message) noexcept {
    try {
        throw;
    } catch (const RuntimeError& error) {
        return failWithContext(codeOf(error.code()), context, error.what(), handle_message);
    } catch (const InputError& error) {
        return failWithContext(GUSUKU_ERROR_INVALID_BAKE_SET, context, error.what(), handle_message);
    } catch (const std::bad_alloc&) {
        return failWithContext(GUSUKU_ERROR_OUT_OF_MEMORY, context, "out of host memory", handle_message);
    } catch (const std::exception& error) {
        return failWithContext(GUSUKU_ERROR_INTERNAL, context, error.what(), handle_message);
    } catch (...) {
        return failWithContext(GUSUKU_ERROR_INTERNAL, context, "an unknown exception", handle_message);
    }
}

}  // namespace gusuku::c_api_detail

namespace {

using gusuku::c_api_detail::fail;
using gusuku::c_api_detail::failFromCurrentException;
using gusuku::c_api_detail::convertDesc;
using gusuku::c_api_detail::DescProblem;
using gusuku::c_api_detail::MessageBuffer;

gusuku_result failArgument(const char* function, const std::string& problem, MessageBuffer* handle = nullptr) {
    return fail(GUSUKU_ERROR_INVALID_ARGUMENT, (std::string(function) + ": " + problem).c_str(), handle);
}

// ---------------------------------------------------------------------------------------------------------------
// Options and frames

gusuku::RuntimeOptions convertOptions(const gusuku_runtime_options* options) {
    gusuku::RuntimeOptions converted;
    if (options == nullptr) return converted;
    converted.frame_width = options->frame_width;
    converted.frame_height = options->frame_height;
    converted.shadow_map_size = options->shadow_map_size;
    converted.shadow_bias_texels = options->shadow_bias_texels;
    converted.shadow_pcf_radius = options->shadow_pcf_radius;
    converted.statistics_stride = options->statistics_stride;
    converted.statistics_smoothing_frames = options->statistics_smoothing_frames;
    converted.colour_gain_limit = options->colour_gain_limit;
    converted.direct_only_ambient_fraction = options->direct_only_ambient_fraction;
    converted.direct_only_shadow_darkening = options->direct_only_shadow_darkening;
    return converted;
}

/// The C frame as the C++ one; "" or the problem with an enum or flag the C++ side cannot see.
std::string convertFrame(const gusuku_frame_input& frame, gusuku::FrameInput& converted) {
    converted.camera_rgba8 = frame.camera_rgba8;
    converted.camera_image = frame.camera_image;
    converted.camera_image_layout = frame.camera_image_layout;
    converted.intrinsics = {frame.intrinsics.fx, frame.intrinsics.fy, frame.intrinsics.cx, frame.intrinsics.cy,
                            frame.intrinsics.width, frame.intrinsics.height};
    converted.pose.position_enu =
        glm::dvec3(frame.pose.position_enu[0], frame.pose.position_enu[1], frame.pose.position_enu[2]);
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            converted.pose.camera_to_enu[column][row] = frame.pose.camera_to_enu[3 * row + column];
    converted.utc_unix_seconds = frame.utc_unix_seconds;
    if (frame.has_position)
        converted.position = gusuku::GeoPosition{frame.position.latitude_deg, frame.position.longitude_deg,
                                                 frame.position.height_m};
    converted.weather.cloud_cover = frame.weather.cloud_cover;
    converted.exposure = frame.exposure;
    switch (frame.mode) {
    case GUSUKU_MODE_PROPOSED: converted.mode = gusuku::RenderMode::kProposed; break;
    case GUSUKU_MODE_DIRECT_ONLY: converted.mode = gusuku::RenderMode::kDirectOnly; break;
    default: return "mode: " + std::to_string(int(frame.mode)) + " is not a gusuku_render_mode";
    }
    switch (frame.colour_match) {
    case GUSUKU_COLOUR_MATCH_OFF: converted.colour_match = gusuku::ColourMatch::kOff; break;
    case GUSUKU_COLOUR_MATCH_PAPER: converted.colour_match = gusuku::ColourMatch::kPaper; break;
    case GUSUKU_COLOUR_MATCH_PRESERVE: converted.colour_match = gusuku::ColourMatch::kPreserve; break;
    case GUSUKU_COLOUR_MATCH_GROUND: converted.colour_match = gusuku::ColourMatch::kGround; break;
    default: return "colour_match: " + std::to_string(int(frame.colour_match)) + " is not a gusuku_colour_match";
    }
    const uint32_t known = GUSUKU_FRAME_BLEND_SLOTS | GUSUKU_FRAME_GROUND_RATIO;
    if ((frame.flags & ~known) != 0) return "flags: unknown bits " + std::to_string(frame.flags & ~known);
    converted.blend_slots = (frame.flags & GUSUKU_FRAME_BLEND_SLOTS) != 0;
    converted.ground_ratio = (frame.flags & GUSUKU_FRAME_GROUND_RATIO) != 0;
    return {};
}

void convertInfo(const gusuku::FrameInfo& info, gusuku_frame_info& out) {
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
}

/// Opens with `open` into a new handle; the handle exists first so the device view's address is fixed.
template <typename Open>
gusuku_result openRuntime(const char* function, gusuku_runtime** out_runtime, Open open) {
    try {
        auto handle = std::make_unique<gusuku_runtime>();
        open(*handle);
        *out_runtime = handle.release();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

}  // namespace

extern "C" {

const char* gusuku_result_name(gusuku_result result) {
    switch (result) {
    case GUSUKU_OK: return "GUSUKU_OK";
    case GUSUKU_ERROR_INVALID_BAKE_SET: return "GUSUKU_ERROR_INVALID_BAKE_SET";
    case GUSUKU_ERROR_INVALID_FRAME: return "GUSUKU_ERROR_INVALID_FRAME";
    case GUSUKU_ERROR_DEVICE: return "GUSUKU_ERROR_DEVICE";
    case GUSUKU_ERROR_OUT_OF_MEMORY: return "GUSUKU_ERROR_OUT_OF_MEMORY";
    case GUSUKU_ERROR_INVALID_ARGUMENT: return "GUSUKU_ERROR_INVALID_ARGUMENT";
    case GUSUKU_ERROR_INTERNAL: return "GUSUKU_ERROR_INTERNAL";
    }
    return "GUSUKU_UNKNOWN_RESULT";
}

const char* gusuku_last_error_message(void) { return gusuku::c_api_detail::t_thread_message.text; }

const char* gusuku_version(void) { return gusuku::runtimeVersion(); }

gusuku_result gusuku_bakeset_create(const gusuku_bakeset_desc* desc, gusuku_bakeset** out_bake_set) {
    const char* function = "gusuku_bakeset_create";
    if (out_bake_set == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_create: out_bake_set: is NULL");
    *out_bake_set = nullptr;
    try {
        if (desc == nullptr) return failArgument(function, "desc: is NULL");
        auto bake_set = std::make_unique<gusuku_bakeset>();
        if (DescProblem problem = convertDesc(*desc, bake_set->data))
            return fail(problem.code, (std::string(function) + ": " + problem.message).c_str());
        if (std::optional<std::string> problem = gusuku::findBakeSetProblem(bake_set->data))
            return fail(GUSUKU_ERROR_INVALID_BAKE_SET, (std::string(function) + ": bake set: " + *problem).c_str());
        *out_bake_set = bake_set.release();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

gusuku_result gusuku_bakeset_free(gusuku_bakeset* bake_set) {
    delete bake_set;  // BakeSetData's destructor does not throw
    return GUSUKU_OK;
}

gusuku_result gusuku_runtime_options_default(gusuku_runtime_options* options) {
    if (options == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_options_default: options: is NULL");
    const gusuku::RuntimeOptions defaults;
    *options = gusuku_runtime_options{defaults.frame_width,
                                      defaults.frame_height,
                                      defaults.shadow_map_size,
                                      defaults.shadow_bias_texels,
                                      defaults.shadow_pcf_radius,
                                      defaults.statistics_stride,
                                      defaults.statistics_smoothing_frames,
                                      defaults.colour_gain_limit,
                                      defaults.direct_only_ambient_fraction,
                                      defaults.direct_only_shadow_darkening};
    return GUSUKU_OK;
}

gusuku_result gusuku_frame_input_default(gusuku_frame_input* frame) {
    if (frame == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_frame_input_default: frame: is NULL");
    const gusuku::FrameInput defaults;
    std::memset(frame, 0, sizeof *frame);
    frame->camera_image = VK_NULL_HANDLE;
    frame->camera_image_layout = defaults.camera_image_layout;
    for (int i = 0; i < 3; ++i) frame->pose.camera_to_enu[4 * i] = 1.0;
    frame->weather.cloud_cover = defaults.weather.cloud_cover;
    frame->exposure = defaults.exposure;
    frame->mode = GUSUKU_MODE_PROPOSED;
    frame->colour_match = GUSUKU_COLOUR_MATCH_OFF;
    frame->flags = (defaults.blend_slots ? GUSUKU_FRAME_BLEND_SLOTS : 0u) |
                   (defaults.ground_ratio ? GUSUKU_FRAME_GROUND_RATIO : 0u);
    return GUSUKU_OK;
}

gusuku_result gusuku_runtime_open(const gusuku_vulkan_device* device, const gusuku_bakeset* bake_set,
                                  const gusuku_runtime_options* options, gusuku_runtime** out_runtime) {
    const char* function = "gusuku_runtime_open";
    if (out_runtime == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: out_runtime: is NULL");
    *out_runtime = nullptr;
    if (device == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: device: is NULL");
    if (bake_set == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: bake_set: is NULL");
    if (device->instance == VK_NULL_HANDLE || device->physical_device == VK_NULL_HANDLE ||
        device->device == VK_NULL_HANDLE || device->queue == VK_NULL_HANDLE)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT,
                    "gusuku_runtime_open: device: instance, physical_device, device and queue must all be set");
    return openRuntime(function, out_runtime, [&](gusuku_runtime& handle) {
        handle.gpu = gusuku::GpuDevice::describe(device->instance, device->physical_device, device->device,
                                                 device->queue, device->queue_family_index);
        handle.runtime = gusuku::Runtime::open(handle.gpu, bake_set->data, convertOptions(options));
    });
}

gusuku_result gusuku_runtime_open_headless(const gusuku_bakeset* bake_set, const gusuku_runtime_options* options,
                                           gusuku_runtime** out_runtime) {
    const char* function = "gusuku_runtime_open_headless";
    if (out_runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open_headless: out_runtime: is NULL");
    *out_runtime = nullptr;
    if (bake_set == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open_headless: bake_set: is NULL");
    return openRuntime(function, out_runtime, [&](gusuku_runtime& handle) {
        handle.runtime = gusuku::Runtime::openHeadless(bake_set->data, convertOptions(options));
    });
}

gusuku_result gusuku_runtime_render(gusuku_runtime* runtime, const gusuku_frame_input* frame, uint8_t* output_rgba8,
                                    gusuku_frame_info* info) {
    const char* function = "gusuku_runtime_render";
    if (runtime == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_render: runtime: is NULL");
    MessageBuffer* message = &runtime->last_error;
    if (frame == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_render: frame: is NULL", message);
    try {
        gusuku::FrameInput converted;
        if (std::string problem = convertFrame(*frame, converted); !problem.empty())
            return fail(GUSUKU_ERROR_INVALID_FRAME, (std::string(function) + ": frame: " + problem).c_str(), message);
        const gusuku::FrameInfo frame_info = runtime->runtime->renderFrame(converted, output_rgba8);
        if (info != nullptr) convertInfo(frame_info, *info);
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function, message);
    }
}

gusuku_result gusuku_runtime_composite_image(const gusuku_runtime* runtime, VkImage* out_image) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_composite_image: runtime: is NULL");
    if (out_image == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_composite_image: out_image: is NULL",
                    &runtime->last_error);
    try {
        *out_image = runtime->runtime->compositeImage();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_composite_image",
                                        &runtime->last_error);
    }
}

gusuku_result gusuku_runtime_reset_colour_statistics(gusuku_runtime* runtime) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_reset_colour_statistics: runtime: is NULL");
    try {
        runtime->runtime->resetColourStatistics();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_reset_colour_statistics", &runtime->last_error);
    }
}

gusuku_result gusuku_runtime_device_memory_bytes(const gusuku_runtime* runtime, uint64_t* out_bytes) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_device_memory_bytes: runtime: is NULL");
    if (out_bytes == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_device_memory_bytes: out_bytes: is NULL",
                    &runtime->last_error);
    try {
        *out_bytes = runtime->runtime->deviceMemoryBytes();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_device_memory_bytes",
                                        &runtime->last_error);
    }
}

const char* gusuku_runtime_last_error(const gusuku_runtime* runtime) {
    return runtime == nullptr ? "" : runtime->last_error.text;
}

gusuku_result gusuku_runtime_close(gusuku_runtime* runtime) {
    if (runtime == nullptr) return GUSUKU_OK;
    try {
        runtime->runtime.reset();
    } catch (...) {
        const gusuku_result code = failFromCurrentException("gusuku_runtime_close");
        delete runtime;
        return code;
    }
    delete runtime;
    return GUSUKU_OK;
}

}  // extern "C"
