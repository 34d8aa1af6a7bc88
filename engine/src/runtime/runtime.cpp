// gusuku_runtime's Runtime (runtime.h; docs/design.md 8): the options' checks, open() and the headless wrapper.
// The rest of RuntimeImpl lives in the files runtime_impl.h lists, one job each.

#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "gusuku/gpu/vulkan_context.h"
#include "gusuku/formats/bakeset_validate.h"
#include "device_requirements.h"
#include "lightmap_format_choice.h"
#include "runtime_error_category.h"
#include "runtime_impl.h"

namespace gusuku {
namespace runtime_detail {

// The options' ranges (runtime.h's RuntimeOptions).
constexpr uint32_t kMaxFrameSide = 8192;
constexpr uint32_t kMinShadowMapSize = 64, kMaxShadowMapSize = 8192;
constexpr uint32_t kMaxShadowPcfRadius = 3;

// What open() does, for its errors' messages ("gusuku runtime: out of host memory opening the bake set").
constexpr const char* kOpening = "opening the bake set";

// The float options' ranges, as runtime.h documents them: a bound is where a value stops meaning anything
// (a gain limit below 1 inverts the clamp, a darkening above 1 brightens, a smoothing below one frame is none).
struct RealOptionRange {
    const char* name;
    float RuntimeOptions::*member;
    float minimum, maximum;
    const char* bounds;
};
constexpr RealOptionRange kRealOptionRanges[] = {
    {"shadow_bias_texels", &RuntimeOptions::shadow_bias_texels, 0.0f, 64.0f, "0, 64"},
    {"shadow_sun_step_deg", &RuntimeOptions::shadow_sun_step_deg, 0.0f, 10.0f, "0, 10"},
    {"statistics_smoothing_frames", &RuntimeOptions::statistics_smoothing_frames, 1.0f, 1e6f, "1, 1e6"},
    {"colour_gain_limit", &RuntimeOptions::colour_gain_limit, 1.0f, 100.0f, "1, 100"},
    {"ground_change_threshold", &RuntimeOptions::ground_change_threshold, 0.0f, 1.0f, "0, 1"},
    {"direct_only_ambient_fraction", &RuntimeOptions::direct_only_ambient_fraction, 0.0f, 100.0f, "0, 100"},
    {"direct_only_shadow_darkening", &RuntimeOptions::direct_only_shadow_darkening, 0.0f, 1.0f, "0, 1"},
    {"max_anisotropy", &RuntimeOptions::max_anisotropy, 1.0f, 16.0f, "1, 16"},
};

void checkRuntimeOptions(const RuntimeOptions& options) {
    if (options.frame_width == 0 || options.frame_height == 0 || options.frame_width > kMaxFrameSide ||
        options.frame_height > kMaxFrameSide)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.frame_width/height: must be in [1, 8192]");
    // The colour statistics sample every stride-th pixel each way, so a frame must hold one stride at least; said
    // here in the frame's terms rather than by the statistics pass's own check of its stride.
    const uint32_t smaller_side = std::min(options.frame_width, options.frame_height);
    if (options.statistics_stride == 0 || options.statistics_stride > smaller_side)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.frame_width/height: " + std::to_string(options.frame_width) + " x " +
                               std::to_string(options.frame_height) + " is smaller than options.statistics_stride (" +
                               std::to_string(options.statistics_stride) + ") on a side: a frame must be at least " +
                               "that many pixels each way (or lower statistics_stride, at least 1)");
    if (options.shadow_map_size < kMinShadowMapSize || options.shadow_map_size > kMaxShadowMapSize)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.shadow_map_size: must be in [64, 8192]");
    if (options.shadow_pcf_radius > kMaxShadowPcfRadius)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.shadow_pcf_radius: must be in [0, 3]");
    // Every float option in its documented range (runtime.h), NaN refused by the same test (!(x >= min)).
    if (options.frames_in_flight < 1 || options.frames_in_flight > 3)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.frames_in_flight: " + std::to_string(options.frames_in_flight) +
                               " is outside [1, 3]");
    const uint32_t samples = options.msaa_samples;
    if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.msaa_samples: " + std::to_string(samples) + " is not 1, 2, 4 or 8");
    if (options.lightmap_format != LightmapFormat::kAuto &&
        formats::findLightmapFormat(int(options.lightmap_format)) == nullptr) {
        std::string names;  // the table's lightmap rows: "e5b9g9r9, rgba16f, ... or auto"
        for (const formats::FormatRow& row : formats::kFormatRows)
            if (row.family == formats::FormatFamily::kLightmap) names += std::string(row.name) + ", ";
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.lightmap_format: " +
                                                                std::to_string(uint32_t(options.lightmap_format)) +
                                                                " is not " + names.substr(0, names.size() - 2) + " or auto");
    }
    const uint32_t camera_format = uint32_t(options.camera_format);
    if (camera_format > uint32_t(CameraFormat::kNv21))
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.camera_format: " + std::to_string(camera_format) +
                                                                " is not rgba8, bgra8, nv12 or nv21");
    if (uint32_t(options.camera_ycbcr_model) > 1u || uint32_t(options.camera_ycbcr_range) > 1u)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.camera_ycbcr_model/range: not bt601/bt709 and narrow/full");
    const bool yuv = options.camera_format == CameraFormat::kNv12 || options.camera_format == CameraFormat::kNv21;
    if (yuv && (options.frame_width % 2 != 0 || options.frame_height % 2 != 0))
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.frame_width/height: " + std::to_string(options.frame_width) + " x " +
                               std::to_string(options.frame_height) +
                               ": a 4:2:0 camera (nv12, nv21) needs an even width and height");
    if (options.camera_ycbcr_image && !yuv)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.camera_ycbcr_image: needs options.camera_format nv12 or nv21 (the zero-copy "
                           "camera is a two-plane Y'CbCr image)");
    if (options.camera_ycbcr_conversion != VK_NULL_HANDLE && !options.camera_ycbcr_image)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.camera_ycbcr_conversion: set, but options.camera_ycbcr_image is false");
    if (options.camera_ycbcr_chroma_filter != VK_FILTER_NEAREST && options.camera_ycbcr_chroma_filter != VK_FILTER_LINEAR)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "options.camera_ycbcr_chroma_filter: " + std::to_string(int(options.camera_ycbcr_chroma_filter)) +
                               " is not VK_FILTER_NEAREST or VK_FILTER_LINEAR");
    for (const RealOptionRange& range : kRealOptionRanges) {
        const float value = options.*(range.member);
        if (!(value >= range.minimum && value <= range.maximum))
            throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                               std::string("options.") + range.name + ": " + std::to_string(value) +
                                   " is outside [" + range.bounds + "]");
    }
}

RuntimeImpl::RuntimeImpl(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options)
    : gpu_(gpu), options_(options), manifest_(bake_set.manifest) {
    checkRuntimeOptions(options);
    if (const std::optional<std::string> problem = findBakeSetProblem(bake_set))
        throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet, "bake set: " + *problem);
    options_.lightmap_format = chooseLightmapFormat(gpu_, bake_set, options_);
    checkDeviceRequirements(gpu_, options_);
    checkBakeSetLimits(gpu_, bake_set);
    try {
        scene_ = uploadScene(gpu_, bake_set, options.ground_change_threshold, options_.lightmap_format,
                             options_.texture_compression_astc_ldr && deviceSamplesAstcLdr(gpu_));
        makePasses(bake_set);
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidBakeSet, kOpening);  // the passes made release themselves
    }
}

// Each pass made from what it reads, in that order; then the list, in the frame's order, with the PassTimings
// figure each hook counts toward in the profiled frame (the camera's draw with the occluder's, its layout's
// return with the ground's: they share those submissions).
void RuntimeImpl::makePasses(const BakeSetData& bake_set) {
    const PassContext context = passContext();
    targets_ = std::make_unique<MainTargets>(context, options_.frames_in_flight);
    submission_ = std::make_unique<FrameSubmission>(context, *targets_);
    materials_ = std::make_unique<MaterialSets>(context);
    // The occluder lowered by its simplification error in the camera's depth and the site's shadow map alike.
    const float occluder_drop_m =
        manifest_.occluder ? float(std::max(0.0, manifest_.occluder->simplification_error_m)) : 0.0f;
    shadows_ = std::make_unique<ShadowPass>(context, *materials_, occluder_drop_m);
    camera_ = std::make_unique<CameraInput>(gpu_, options_, options_.frames_in_flight,
                                            ColourStatisticsPass::deviceSupports(gpu_));
    // Mode kGround's ground (null without ground albedo: older bake sets, the mode then refuses frames).
    const std::optional<GroundMatchScene> ground = groundMatchSceneFrom(bake_set);
    colour_ = std::make_unique<ColourMatchPass>(context, manifest_, ground ? &*ground : nullptr,
                                                camera_->packedBuffer());
    frame_set_ = std::make_unique<FrameSet>(context, *shadows_, *materials_, colour_->stateBuffer());
    const VkRenderPass main_pass = targets_->renderPass(MainPassVariant::kWhole);
    camera_->createDrawPipeline(main_pass, targets_->samples());
    occluder_ = std::make_unique<OccluderPass>(context, main_pass, targets_->samples(), occluder_drop_m);
    building_ = std::make_unique<BuildingPass>(context, *frame_set_, *materials_, main_pass, targets_->samples());
    ground_ = std::make_unique<GroundPass>(context, manifest_.ground_grid.grid, *frame_set_, options_.frames_in_flight,
                                           main_pass, targets_->samples());
    // The sun from the site's shadows: the ground match's samples and the site occluder's map.
    if (ColourStatisticsPass* statistics = colour_->statistics();
        statistics && statistics->hasGround() && scene_.occluder_index_count > 0)
        sun_evidence_ = std::make_unique<SunEvidencePass>(context, *statistics, *shadows_, options_.frames_in_flight);
    using T = PassTimings;
    passes_ = {{
        {frame_set_.get(), &T::upload_ms, nullptr, nullptr},
        {camera_.get(), &T::upload_ms, &T::occluder_ms, &T::ground_ms},
        {colour_.get(), &T::statistics_ms, nullptr, nullptr},
        {shadows_.get(), &T::shadow_ms, nullptr, nullptr},
        {occluder_.get(), nullptr, &T::occluder_ms, nullptr},
        {building_.get(), nullptr, &T::building_ms, nullptr},
        {ground_.get(), nullptr, &T::ground_ms, nullptr},
        {sun_evidence_ ? static_cast<FramePass*>(sun_evidence_.get()) : &no_sun_evidence_, nullptr, nullptr,
         sun_evidence_ ? &T::statistics_ms : nullptr},
        {submission_.get(), nullptr, nullptr, &T::readback_ms},
    }};
}

RuntimeImpl::~RuntimeImpl() {
    if (gpu_.device != VK_NULL_HANDLE) vkDeviceWaitIdle(gpu_.device);  // then the passes release themselves
}

std::optional<RuntimeSunEvidence> RuntimeImpl::latestSunEvidence() {
    if (!sun_evidence_) return std::nullopt;
    return sun_evidence_->latest([&](uint32_t slot) { return submission_->finished(slot); });
}

}  // namespace runtime_detail

namespace {

using runtime_detail::kOpening;
using runtime_detail::rethrowAsRuntimeError;
using runtime_detail::RuntimeImpl;

// The options as the headless device can honour them: that device knows whether it enabled samplerAnisotropy
// (VulkanContext enables it where the device has it), so anisotropy is turned off, not made invalid, without it.
RuntimeOptions optionsForContext(const VulkanContext& context, RuntimeOptions options) {
    if (!context.enabledFeatures().samplerAnisotropy && options.max_anisotropy > 1.0f) options.max_anisotropy = 1.0f;
    options.texture_compression_astc_hdr = false;  // VulkanContext does not enable either
    options.texture_compression_astc_ldr = false;
    return options;
}

// A runtime that owns the headless device it runs on: the context is made first and destroyed last.
class HeadlessRuntime final : public Runtime, public runtime_detail::SunEvidenceSource {
public:
    HeadlessRuntime(const BakeSetData& bake_set, const RuntimeOptions& options)
        : context_(vulkanOptionsFromEnvironment()),
          runtime_(context_.gpu(), bake_set, optionsForContext(context_, options)) {}
    FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) override {
        return runtime_.renderFrame(frame, output_rgba8);
    }
    FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) override {
        return runtime_.renderFrameProfiled(frame, output_rgba8, timings);
    }
    VkImage compositeImage() const override { return runtime_.compositeImage(); }
    void waitIdle() override { runtime_.waitIdle(); }
    void forgetCameraImage(VkImage image) override { runtime_.forgetCameraImage(image); }
    void resetColourStatistics() override { runtime_.resetColourStatistics(); }
    void invalidateShadowMaps() override { runtime_.invalidateShadowMaps(); }
    uint64_t deviceMemoryBytes() const override { return runtime_.deviceMemoryBytes(); }
    LightmapFormat lightmapFormat() const override { return runtime_.lightmapFormat(); }
    uint32_t astcTextureCount() const override { return runtime_.astcTextureCount(); }
    std::optional<RuntimeSunEvidence> latestSunEvidence() override { return runtime_.latestSunEvidence(); }

private:
    VulkanContext context_;
    RuntimeImpl runtime_;
};

}  // namespace

std::optional<RuntimeSunEvidence> latestSunEvidence(Runtime& runtime) {
    auto* source = dynamic_cast<runtime_detail::SunEvidenceSource*>(&runtime);
    return source ? source->latestSunEvidence() : std::nullopt;
}

std::unique_ptr<Runtime> Runtime::openHeadless(const BakeSetData& bake_set, const RuntimeOptions& options) {
    try {
        return std::make_unique<HeadlessRuntime>(bake_set, options);
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidBakeSet, kOpening);
    }
}

std::unique_ptr<Runtime> Runtime::open(const GpuDevice& gpu, const BakeSetData& bake_set,
                                       const RuntimeOptions& options) {
    try {
        return std::make_unique<RuntimeImpl>(gpu, bake_set, options);
    } catch (...) {
        rethrowAsRuntimeError(RuntimeErrorCode::kInvalidBakeSet, kOpening);
    }
}

}  // namespace gusuku
