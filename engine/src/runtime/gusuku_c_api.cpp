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

#include "gusuku/formats/bakeset_validate.h"
#include "gusuku/maths/sun_cue_choice.h"
#include "gusuku/runtime/runtime_sun_evidence.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/runtime/runtime_version.h"
#include "gusuku_c_api_detail.h"
#include "gusuku_c_api_sizes.h"
#include "gusuku_c_api_structs.h"

/// The runtime handle. The C++ runtime holds a reference to the device view, so the view lives here, beside it,
/// at an address that never moves.
struct gusuku_runtime {
    gusuku::GpuDevice gpu;
    std::unique_ptr<gusuku::Runtime> runtime;
    mutable gusuku::c_api_detail::MessageBuffer last_error;  // written by failing calls, const ones too
};

namespace {

using gusuku::c_api_detail::fail;
using gusuku::c_api_detail::failFromCurrentException;
using gusuku::c_api_detail::convertDesc;
using gusuku::c_api_detail::DescProblem;
using gusuku::c_api_detail::MessageBuffer;
using gusuku::c_api_detail::readSized;
using gusuku::c_api_detail::findSizeProblem;
using gusuku::c_api_detail::writeSized;
using gusuku::c_api_detail::defaultOptions;
using gusuku::c_api_detail::defaultFrame;
using gusuku::c_api_detail::convertOptions;
using gusuku::c_api_detail::convertFrame;
using gusuku::c_api_detail::convertInfo;
using gusuku::c_api_detail::convertTimings;

/// "FUNCTION: PROBLEM" as an invalid argument; formats into a local buffer, so never throws.
gusuku_result failArgument(const char* function, const char* problem, MessageBuffer* handle = nullptr) noexcept {
    char text[GUSUKU_MESSAGE_CAPACITY];
    std::snprintf(text, sizeof text, "%s: %s", function, problem);
    return fail(GUSUKU_ERROR_INVALID_ARGUMENT, text, handle);
}

gusuku_result failArgument(const char* function, const std::string& problem,
                           MessageBuffer* handle = nullptr) noexcept {
    return failArgument(function, problem.c_str(), handle);
}

/// The app's options (NULL: the defaults) over today's defaults; "" or the struct_size problem.
std::string readOptions(const gusuku_runtime_options* options, gusuku_runtime_options& full) {
    return options == nullptr ? std::string() : readSized(options, "options", full);
}

/// gusuku_runtime_render(_profiled): the arguments checked (the frame's and info's sizes before any GPU work),
/// the frame rendered (profiled when timings is given), the results written in the app's layouts.
gusuku_result renderFrame(const char* function, gusuku_runtime* runtime, const gusuku_frame_input* frame,
                          uint8_t* output_rgba8, gusuku_frame_info* info, gusuku_pass_timings* timings) {
    if (runtime == nullptr) return failArgument(function, "runtime: is NULL");
    MessageBuffer* message = &runtime->last_error;
    if (frame == nullptr) return failArgument(function, "frame: is NULL", message);
    try {
        gusuku_frame_input full_frame = defaultFrame();
        size_t info_bytes = 0, timings_bytes = 0;
        std::string problem = readSized(frame, "frame", full_frame);
        if (problem.empty() && info != nullptr) problem = findSizeProblem(info, "info", info_bytes);
        if (problem.empty() && timings != nullptr) problem = findSizeProblem(timings, "timings", timings_bytes);
        if (!problem.empty()) return failArgument(function, problem, message);
        gusuku::FrameInput converted;
        if (std::string frame_problem = convertFrame(full_frame, converted); !frame_problem.empty())
            return fail(GUSUKU_ERROR_INVALID_FRAME, (std::string(function) + ": frame: " + frame_problem).c_str(),
                        message);
        gusuku::PassTimings pass_timings;
        const gusuku::FrameInfo frame_info =
            timings != nullptr ? runtime->runtime->renderFrameProfiled(converted, output_rgba8, pass_timings)
                               : runtime->runtime->renderFrame(converted, output_rgba8);
        if (info != nullptr) writeSized(convertInfo(frame_info), info, info_bytes);
        if (timings != nullptr) writeSized(convertTimings(pass_timings), timings, timings_bytes);
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function, message);
    }
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

const char* gusuku_version(void) { return gusuku::runtimeVersion(); }

uint32_t gusuku_api_version(void) { return GUSUKU_API_VERSION; }

gusuku_result gusuku_bakeset_create(const gusuku_bakeset_desc* desc, gusuku_bakeset** out_bake_set) {
    const char* function = "gusuku_bakeset_create";
    if (out_bake_set == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_bakeset_create: out_bake_set: is NULL");
    *out_bake_set = nullptr;
    try {
        if (desc == nullptr) return failArgument(function, "desc: is NULL");
        gusuku_bakeset_desc full_desc;
        std::memset(&full_desc, 0, sizeof full_desc);  // every desc field's default is zero
        if (std::string problem = readSized(desc, "desc", full_desc); !problem.empty())
            return failArgument(function, problem);
        auto bake_set = std::make_unique<gusuku_bakeset>();
        if (DescProblem problem = convertDesc(full_desc, bake_set->data))
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

gusuku_result gusuku_runtime_options_fill_defaults(gusuku_runtime_options* options) {
    if (options == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_options_fill_defaults: options: is NULL");
    size_t field_bytes = 0;
    if (std::string problem = findSizeProblem(options, "options", field_bytes); !problem.empty())
        return failArgument("gusuku_runtime_options_fill_defaults", problem);
    writeSized(defaultOptions(), options, field_bytes);
    return GUSUKU_OK;
}

gusuku_result gusuku_frame_input_fill_defaults(gusuku_frame_input* frame) {
    if (frame == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_frame_input_fill_defaults: frame: is NULL");
    size_t field_bytes = 0;
    if (std::string problem = findSizeProblem(frame, "frame", field_bytes); !problem.empty())
        return failArgument("gusuku_frame_input_fill_defaults", problem);
    writeSized(defaultFrame(), frame, field_bytes);
    return GUSUKU_OK;
}

gusuku_result gusuku_runtime_open(const gusuku_vulkan_device* device, const gusuku_bakeset* bake_set,
                                  const gusuku_runtime_options* options, gusuku_runtime** out_runtime) {
    const char* function = "gusuku_runtime_open";
    if (out_runtime == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: out_runtime: is NULL");
    *out_runtime = nullptr;
    if (device == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: device: is NULL");
    if (bake_set == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_open: bake_set: is NULL");
    gusuku_vulkan_device vulkan;
    std::memset(&vulkan, 0, sizeof vulkan);
    if (std::string problem = readSized(device, "device", vulkan); !problem.empty())
        return failArgument(function, problem);
    if (vulkan.instance == VK_NULL_HANDLE || vulkan.physical_device == VK_NULL_HANDLE ||
        vulkan.device == VK_NULL_HANDLE || vulkan.queue == VK_NULL_HANDLE)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT,
                    "gusuku_runtime_open: device: instance, physical_device, device and queue must all be set");
    gusuku_runtime_options full_options = defaultOptions();
    if (std::string problem = readOptions(options, full_options); !problem.empty())
        return failArgument(function, problem);
    return openRuntime(function, out_runtime, [&](gusuku_runtime& handle) {
        handle.gpu = gusuku::GpuDevice::describe(vulkan.instance, vulkan.physical_device, vulkan.device, vulkan.queue,
                                                 vulkan.queue_family_index, nullptr,
                                                 vulkan.instance_api_version != 0 ? vulkan.instance_api_version
                                                                                  : VK_API_VERSION_1_1);
        handle.runtime = gusuku::Runtime::open(handle.gpu, bake_set->data, convertOptions(full_options));
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
    gusuku_runtime_options full_options = defaultOptions();
    if (std::string problem = readOptions(options, full_options); !problem.empty())
        return failArgument(function, problem);
    return openRuntime(function, out_runtime, [&](gusuku_runtime& handle) {
        handle.runtime = gusuku::Runtime::openHeadless(bake_set->data, convertOptions(full_options));
    });
}

gusuku_result gusuku_runtime_render(gusuku_runtime* runtime, const gusuku_frame_input* frame, uint8_t* output_rgba8,
                                    gusuku_frame_info* info) {
    return renderFrame("gusuku_runtime_render", runtime, frame, output_rgba8, info, nullptr);
}

gusuku_result gusuku_runtime_render_profiled(gusuku_runtime* runtime, const gusuku_frame_input* frame,
                                             uint8_t* output_rgba8, gusuku_frame_info* info,
                                             gusuku_pass_timings* timings) {
    const char* function = "gusuku_runtime_render_profiled";
    if (runtime != nullptr && timings == nullptr)
        return failArgument(function, "timings: is NULL", &runtime->last_error);
    return renderFrame(function, runtime, frame, output_rgba8, info, timings);
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

gusuku_result gusuku_runtime_invalidate_shadow_maps(gusuku_runtime* runtime) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_invalidate_shadow_maps: runtime: is NULL");
    try {
        runtime->runtime->invalidateShadowMaps();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_invalidate_shadow_maps", &runtime->last_error);
    }
}

gusuku_result gusuku_runtime_wait_idle(gusuku_runtime* runtime) {
    if (runtime == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_wait_idle: runtime: is NULL");
    try {
        runtime->runtime->waitIdle();
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_wait_idle", &runtime->last_error);
    }
}

gusuku_result gusuku_runtime_forget_camera_image(gusuku_runtime* runtime, VkImage image) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_forget_camera_image: runtime: is NULL");
    try {
        runtime->runtime->forgetCameraImage(image);
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_forget_camera_image", &runtime->last_error);
    }
}

gusuku_result gusuku_runtime_lightmap_format(const gusuku_runtime* runtime, gusuku_lightmap_format* out_format) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_lightmap_format: runtime: is NULL");
    if (out_format == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_lightmap_format: out_format: is NULL",
                    &runtime->last_error);
    *out_format = gusuku_lightmap_format(runtime->runtime->lightmapFormat());
    return GUSUKU_OK;
}

gusuku_result gusuku_runtime_astc_texture_count(const gusuku_runtime* runtime, uint32_t* out_count) {
    if (runtime == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_astc_texture_count: runtime: is NULL");
    if (out_count == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_astc_texture_count: out_count: is NULL",
                    &runtime->last_error);
    *out_count = runtime->runtime->astcTextureCount();
    return GUSUKU_OK;
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

gusuku_result gusuku_runtime_sun_evidence(gusuku_runtime* runtime, gusuku_sun_evidence_reading* out_reading) {
    if (runtime == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_sun_evidence: runtime: is NULL");
    if (out_reading == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_runtime_sun_evidence: out_reading: is NULL",
                    &runtime->last_error);
    if (out_reading->struct_size != sizeof(gusuku_sun_evidence_reading)) {
        const std::string message = "gusuku_runtime_sun_evidence: out_reading.struct_size: " +
                                    std::to_string(out_reading->struct_size) + " is not " +
                                    std::to_string(sizeof(gusuku_sun_evidence_reading));
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message.c_str(), &runtime->last_error);
    }
    try {
        const std::optional<gusuku::RuntimeSunEvidence> latest = gusuku::latestSunEvidence(*runtime->runtime);
        gusuku_sun_evidence_reading reading{};
        reading.struct_size = sizeof reading;
        if (latest) {
            const gusuku::SunEvidenceEstimate& estimate = latest->estimate;
            reading.measured = 1;
            reading.sun_out_probability = estimate.evidence.sun_out_probability;
            reading.confidence = estimate.evidence.confidence;
            reading.sun_strength = estimate.evidence.sun_strength;
            reading.cue = uint32_t(estimate.cue);
            reading.shadowed_samples = estimate.shadowed_samples;
            reading.lit_samples = estimate.lit_samples;
            reading.shade_log2_ratio = estimate.shade_log2_ratio;
            reading.strength = estimate.strength;
            reading.strength_standard_error = estimate.strength_standard_error;
            reading.frame_index = latest->frame_index;
            reading.utc_unix_seconds = latest->utc_unix_seconds;
        }
        *out_reading = reading;
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException("gusuku_runtime_sun_evidence", &runtime->last_error);
    }
}

gusuku_result gusuku_sun_evidence_choose(const gusuku_sun_evidence_reading* reading, int32_t exposure_is_metered,
                                         gusuku_sun_evidence_reading* out_reading) {
    if (reading == nullptr) return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_sun_evidence_choose: reading: is NULL");
    if (out_reading == nullptr)
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, "gusuku_sun_evidence_choose: out_reading: is NULL");
    if (reading->struct_size != sizeof(gusuku_sun_evidence_reading)) {
        const std::string message = "gusuku_sun_evidence_choose: reading.struct_size: " +
                                    std::to_string(reading->struct_size) + " is not " +
                                    std::to_string(sizeof(gusuku_sun_evidence_reading));
        return fail(GUSUKU_ERROR_INVALID_ARGUMENT, message.c_str());
    }
    gusuku::SunEvidenceEstimate estimate;
    estimate.evidence = {reading->sun_out_probability, reading->confidence, reading->sun_strength};
    estimate.cue = reading->cue <= 2u ? gusuku::SunEvidenceCue(reading->cue) : gusuku::SunEvidenceCue::kNone;
    estimate.lit_samples = reading->lit_samples;
    estimate.strength_standard_error = reading->strength_standard_error;
    const gusuku::SunCueChoice choice = gusuku::sunEvidenceForFilter(estimate, exposure_is_metered != 0);
    gusuku_sun_evidence_reading chosen = *reading;
    chosen.sun_out_probability = choice.evidence.sun_out_probability;
    chosen.confidence = choice.evidence.confidence;
    chosen.sun_strength = choice.evidence.sun_strength;
    chosen.cue = uint32_t(choice.cue);
    *out_reading = chosen;
    return GUSUKU_OK;
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
