// gusuku_runtime's frame (runtime.h; docs/design.md 8): the sun and slot weights on the CPU, then on the GPU the
// camera image in, colour statistics, the sun's shadow maps, the occluder's depth, the building, the ground
// ratio, and the composite out. Everything is created in open(); a frame records into one pre-allocated command
// buffer, submits it and waits on one fence, and allocates nothing.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <mutex>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "building_frag_spv.h"
#include "building_vert_spv.h"
#include "colour_statistics_pass.h"
#include "depth_only_vert_spv.h"
#include "ground_frag_spv.h"
#include "ground_vert_spv.h"
#include "gusuku/maths/bakeset_validate.h"
#include "gusuku/maths/frame_lighting.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/maths/shadow_fit.h"
#include "gusuku/gpu/vulkan_context.h"
#include "runtime_camera.h"
#include "runtime_depth_push.h"
#include "runtime_interface.h"
#include "runtime_material_push.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku {
namespace {

using namespace runtime_detail;
using shader_interface::DepthOnlyPushConstants;
using shader_interface::FrameUniforms;
using shader_interface::MaterialPushConstants;

static_assert(sizeof(FrameUniforms) == 2 * 64 + 6 * 16 + 2 * 16 + 2 * 4, "std140 layout of runtime_interface.h's FrameUniforms");
static_assert(offsetof(FrameUniforms, camera_position) == 128 && offsetof(FrameUniforms, exposure) == 140);
static_assert(offsetof(FrameUniforms, sun_direction) == 144 && offsetof(FrameUniforms, sun_shines) == 156);
static_assert(offsetof(FrameUniforms, sun_irradiance) == 160 && offsetof(FrameUniforms, site_shadows) == 172);
static_assert(offsetof(FrameUniforms, slot_layers) == 176 && offsetof(FrameUniforms, render_mode) == 188);
static_assert(offsetof(FrameUniforms, slot_weights) == 192 && offsetof(FrameUniforms, irradiance_scale) == 204);
static_assert(offsetof(FrameUniforms, direct_only_ambient) == 208 &&
              offsetof(FrameUniforms, direct_only_shadow_darkening) == 220);
static_assert(offsetof(FrameUniforms, shadow_texel_uv) == 224 && offsetof(FrameUniforms, ground_origin_east_m) == 240);
static_assert(offsetof(FrameUniforms, ground_columns) == 256 && offsetof(FrameUniforms, ground_rows) == 260);
static_assert(sizeof(DepthOnlyPushConstants) == 80 && offsetof(DepthOnlyPushConstants, pull_m) == 76);

constexpr double kNearPlaneM = 0.05;
constexpr float kGroundPullM = 0.10f;      // the ground pass moves towards the camera by this
constexpr float kOccluderPushM = 0.05f;    // the occluder pass moves away from it by this
constexpr float kPassThroughThreshold = 0.5f / 255.0f;  // |ratio - 1| below this: the camera pixel is untouched

void toShader(const glm::dmat4& matrix, shader_interface::mat4& out) {
    for (int column = 0; column < 4; ++column)
        for (int row = 0; row < 4; ++row) out.columns[column][row] = float(matrix[column][row]);
}

void toShader(const glm::dvec3& xyz, shader_interface::vec3& out) {
    out = {{float(xyz.x), float(xyz.y), float(xyz.z)}};
}

RuntimeError deviceError(const std::exception& error) {
    return RuntimeError(RuntimeErrorCode::kDevice, std::string("gusuku runtime: ") + error.what());
}

class RuntimeImpl final : public Runtime {
public:
    RuntimeImpl(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options);
    ~RuntimeImpl() override;

    FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) override;
    FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) override;
    VkImage compositeImage() const override { return colour_target_.handle(); }
    void resetColourStatistics() override { statistics_->reset(); }
    void invalidateShadowMaps() override { building_shadow_valid_ = site_shadow_valid_ = false; }
    uint64_t deviceMemoryBytes() const override;

private:
    void createTargets();
    void createDescriptors();
    void createPipelines();
    void destroy() noexcept;

    FrameInfo prepareFrame(const FrameInput& frame);
    void recordCameraIn(VkCommandBuffer cmd, const FrameInput& frame);
    void recordStatistics(VkCommandBuffer cmd, const FrameInput& frame);
    void recordShadows(VkCommandBuffer cmd);
    void recordOccluder(VkCommandBuffer cmd);
    void recordBuilding(VkCommandBuffer cmd);
    void recordGround(VkCommandBuffer cmd);
    void recordReadback(VkCommandBuffer cmd);
    void beginMainPass(VkCommandBuffer cmd, VkRenderPass render_pass);
    // Records `record` into the frame's one command buffer, submits it and waits on the fence. A template, not a
    // std::function, so a frame allocates nothing even where a standard library would box the lambda.
    template <typename Record> void submit(const Record& record) {
        beginCommands();
        record(command_buffer_);
        submitCommandsAndWait();
    }
    void beginCommands();
    void submitCommandsAndWait();
    void selectGroundQuads(bool include_baked_changes, bool sun_shines, const glm::dvec3& sun_direction);
    void finishOutput(uint8_t* output_rgba8);

    const GpuDevice& gpu_;
    RuntimeOptions options_;
    BakeSetManifest manifest_;
    std::vector<LabStatistics> slot_colour_statistics_;  // per slot (zero when the manifest has none)
    GpuScene scene_;

    // Per-frame resources, all made in open().
    GpuImage colour_target_;
    GpuImage depth_target_;
    GpuImage building_shadow_;
    GpuImage site_shadow_;
    GpuBuffer camera_buffer_;    // host-visible RGBA8 of the camera frame (uploaded, or copied from the app's image)
    GpuBuffer readback_buffer_;  // host-visible RGBA8 of the composite
    GpuBuffer uniform_buffer_;   // host-visible FrameUniforms
    std::unique_ptr<ColourStatisticsPass> statistics_;

    VkRenderPass main_passes_[4] = {};  // MainPassVariant order
    VkRenderPass shadow_pass_ = VK_NULL_HANDLE;
    VkFramebuffer main_framebuffer_ = VK_NULL_HANDLE;
    VkFramebuffer building_shadow_framebuffer_ = VK_NULL_HANDLE;
    VkFramebuffer site_shadow_framebuffer_ = VK_NULL_HANDLE;
    VkSampler linear_sampler_ = VK_NULL_HANDLE;
    VkSampler shadow_sampler_ = VK_NULL_HANDLE;
    VkSampler texture_sampler_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout frame_set_layout_ = VK_NULL_HANDLE;
    VkDescriptorSetLayout material_set_layout_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet frame_set_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> material_sets_;
    VkPipelineLayout depth_layout_ = VK_NULL_HANDLE;
    VkPipelineLayout shading_layout_ = VK_NULL_HANDLE;
    VkPipeline shadow_pipeline_ = VK_NULL_HANDLE;       // the building into a shadow map
    VkPipeline site_shadow_pipeline_ = VK_NULL_HANDLE;  // the occluder into a shadow map (its own vertex stride)
    VkPipeline occluder_pipeline_ = VK_NULL_HANDLE;
    VkPipeline building_pipeline_ = VK_NULL_HANDLE;
    VkPipeline ground_pipeline_ = VK_NULL_HANDLE;          // quads the building's shadow may reach
    VkPipeline ground_baked_pipeline_ = VK_NULL_HANDLE;    // quads only its baked light changes: no building shadow
    VkPipeline ground_sunless_pipeline_ = VK_NULL_HANDLE;  // the same with no sun at all: no shadow-map reads
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
    VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;

    // This frame's CPU-side state, filled by prepareFrame.
    FrameUniforms uniforms_{};
    DepthOnlyPushConstants shadow_push_{};  // both shadow maps: the sun's view of this frame's fit
    DepthOnlyPushConstants occluder_push_{};
    bool sun_shines_ = false;
    // The shadow maps hold the sun's direction rounded to options_.shadow_sun_step_deg; they are re-rendered
    // only when that rounded direction changes (the building and the site are static).
    glm::dvec3 shadow_sun_direction_{0.0};
    ShadowFit shadow_fit_;
    bool building_shadow_valid_ = false;
    bool site_shadow_valid_ = false;
    bool render_building_shadow_ = false;
    bool render_site_shadow_ = false;
    // The ground quads drawn this frame (selectGroundQuads), and the reused host arrays that choose them.
    // What the ground quads were last chosen for (selectGroundQuads runs again only when it changes).
    struct GroundSelectionKey {
        bool wanted = false;
        bool include_baked_changes = false;
        bool sun_shines = false;
        glm::dvec3 sun{0.0};
        bool operator==(const GroundSelectionKey&) const = default;
    };
    std::optional<GroundSelectionKey> ground_selection_key_;
    uint32_t ground_index_count_ = 0;         // all quads drawn, times 6
    uint32_t ground_shadow_index_count_ = 0;  // the first of them, which the building's shadow may reach
    std::vector<uint8_t> ground_cell_marked_;
    std::vector<float> ground_shadow_candidate_;  // per cell: 1 where the building's shadow may fall
    GpuBuffer ground_candidate_buffer_;           // the same as a host-visible vertex stream
    std::vector<uint32_t> ground_quad_indices_;
    bool draw_ground_ = false;
    bool site_shadows_ = false;
    LabStatistics frame_source_statistics_{};
    ColourMatchMode frame_colour_mode_ = ColourMatchMode::kOff;
    GroundMatchView frame_ground_view_;  // mode kGround: this frame's camera and light
};

RuntimeImpl::RuntimeImpl(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options)
    : gpu_(gpu), options_(options), manifest_(bake_set.manifest) {
    if (options.frame_width == 0 || options.frame_height == 0 || options.frame_width > 8192 ||
        options.frame_height > 8192)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.frame_width/height: must be in [1, 8192]");
    if (options.shadow_map_size < 64 || options.shadow_map_size > 8192)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.shadow_map_size: must be in [64, 8192]");
    if (options.shadow_pcf_radius > 3)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "options.shadow_pcf_radius: must be in [0, 3]");
    if (const std::optional<std::string> problem = findBakeSetProblem(bake_set))
        throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet, "bake set: " + *problem);
    for (const BakeSetSlot& slot : manifest_.slots) {
        LabStatistics statistics;
        if (slot.colour_statistics) {
            statistics.mean = glm::vec3(slot.colour_statistics->lab_mean);
            statistics.standard_deviation = glm::vec3(slot.colour_statistics->lab_sigma);
        }
        slot_colour_statistics_.push_back(statistics);
    }
    try {
        scene_ = uploadScene(gpu, bake_set, options.ground_change_threshold);
        ground_cell_marked_.assign(scene_.ground_cell_state.size(), 0);
        ground_shadow_candidate_.assign(scene_.ground_cell_state.size(), 0.0f);
        ground_candidate_buffer_ = GpuBuffer(gpu, std::max<size_t>(ground_shadow_candidate_.size() * sizeof(float), 16),
                                             VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, GpuMemory::kHostVisible);
        ground_quad_indices_.assign(size_t(scene_.ground_quad_capacity) * 6, 0);
        createTargets();
        // Mode kGround's ground (null without ground albedo: older bake sets, the mode then refuses frames).
        const std::optional<GroundMatchScene> ground = groundMatchSceneFrom(bake_set);
        statistics_ = std::make_unique<ColourStatisticsPass>(gpu, options.frame_width, options.frame_height,
                                                             options.statistics_stride,
                                                             options.statistics_smoothing_frames,
                                                             ground ? &*ground : nullptr);
        createDescriptors();
        createPipelines();
        VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = gpu.queue_family_index;
        checkVk(vkCreateCommandPool(gpu.device, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate_info.commandPool = command_pool_;
        allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate_info.commandBufferCount = 1;
        checkVk(vkAllocateCommandBuffers(gpu.device, &allocate_info, &command_buffer_), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        checkVk(vkCreateFence(gpu.device, &fence_info, nullptr, &fence_), "vkCreateFence");
    } catch (const RuntimeError&) {
        destroy();
        throw;
    } catch (const std::exception& error) {
        destroy();
        throw deviceError(error);
    }
}

RuntimeImpl::~RuntimeImpl() { destroy(); }

void RuntimeImpl::destroy() noexcept {
    VkDevice device = gpu_.device;
    if (device == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device);
    if (fence_) vkDestroyFence(device, fence_, nullptr);
    if (command_pool_) vkDestroyCommandPool(device, command_pool_, nullptr);
    for (VkPipeline pipeline :
         {shadow_pipeline_, site_shadow_pipeline_, occluder_pipeline_, building_pipeline_, ground_pipeline_,
          ground_baked_pipeline_, ground_sunless_pipeline_})
        if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    for (VkPipelineLayout layout : {depth_layout_, shading_layout_})
        if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
    if (descriptor_pool_) vkDestroyDescriptorPool(device, descriptor_pool_, nullptr);
    for (VkDescriptorSetLayout layout : {frame_set_layout_, material_set_layout_})
        if (layout) vkDestroyDescriptorSetLayout(device, layout, nullptr);
    for (VkSampler sampler : {linear_sampler_, shadow_sampler_, texture_sampler_})
        if (sampler) vkDestroySampler(device, sampler, nullptr);
    for (VkFramebuffer framebuffer : {main_framebuffer_, building_shadow_framebuffer_, site_shadow_framebuffer_})
        if (framebuffer) vkDestroyFramebuffer(device, framebuffer, nullptr);
    for (VkRenderPass render_pass : main_passes_)
        if (render_pass) vkDestroyRenderPass(device, render_pass, nullptr);
    if (shadow_pass_) vkDestroyRenderPass(device, shadow_pass_, nullptr);
    fence_ = VK_NULL_HANDLE;
    command_pool_ = VK_NULL_HANDLE;
    shadow_pipeline_ = site_shadow_pipeline_ = occluder_pipeline_ = building_pipeline_ = ground_pipeline_ =
        ground_baked_pipeline_ = ground_sunless_pipeline_ = VK_NULL_HANDLE;
    depth_layout_ = shading_layout_ = VK_NULL_HANDLE;
    descriptor_pool_ = VK_NULL_HANDLE;
    frame_set_layout_ = material_set_layout_ = VK_NULL_HANDLE;
    linear_sampler_ = shadow_sampler_ = texture_sampler_ = VK_NULL_HANDLE;
    main_framebuffer_ = building_shadow_framebuffer_ = site_shadow_framebuffer_ = VK_NULL_HANDLE;
    for (VkRenderPass& render_pass : main_passes_) render_pass = VK_NULL_HANDLE;
    shadow_pass_ = VK_NULL_HANDLE;
    // Buffers, images and the statistics pass release themselves.
}

void RuntimeImpl::createTargets() {
    const uint32_t width = options_.frame_width, height = options_.frame_height;
    GpuImageDescription colour;
    colour.format = kColourFormat;
    colour.width = width;
    colour.height = height;
    colour.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                   VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    colour_target_ = GpuImage(gpu_, colour);
    GpuImageDescription depth;
    depth.format = kDepthFormat;
    depth.width = width;
    depth.height = height;
    depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    depth.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    depth_target_ = GpuImage(gpu_, depth);
    GpuImageDescription shadow = depth;
    shadow.width = shadow.height = options_.shadow_map_size;
    shadow.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    building_shadow_ = GpuImage(gpu_, shadow);
    site_shadow_ = GpuImage(gpu_, shadow);

    const size_t frame_bytes = size_t(width) * height * 4;
    camera_buffer_ = GpuBuffer(gpu_, frame_bytes,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    readback_buffer_ = GpuBuffer(gpu_, frame_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    uniform_buffer_ = GpuBuffer(gpu_, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);

    const VkDevice device = gpu_.device;
    main_passes_[0] = createMainRenderPass(device, MainPassVariant::kWhole);
    main_passes_[1] = createMainRenderPass(device, MainPassVariant::kFirst);
    main_passes_[2] = createMainRenderPass(device, MainPassVariant::kMiddle);
    main_passes_[3] = createMainRenderPass(device, MainPassVariant::kLast);
    shadow_pass_ = createShadowRenderPass(device);
    main_framebuffer_ =
        createFramebuffer(device, main_passes_[0], {colour_target_.view(), depth_target_.view()}, width, height);
    building_shadow_framebuffer_ = createFramebuffer(device, shadow_pass_, {building_shadow_.view()},
                                                     options_.shadow_map_size, options_.shadow_map_size);
    site_shadow_framebuffer_ = createFramebuffer(device, shadow_pass_, {site_shadow_.view()},
                                                 options_.shadow_map_size, options_.shadow_map_size);

    // Shadow maps start in the layout the frame set's descriptors name, so a frame that skips them reads a
    // defined (cleared) map.
    GpuSubmitter submitter(gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        for (const GpuImage* map : {&building_shadow_, &site_shadow_})
            recordImageLayoutTransition(cmd, map->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, VK_ACCESS_SHADER_READ_BIT,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
    });
}

void RuntimeImpl::createDescriptors() {
    const VkDevice device = gpu_.device;
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = VK_FILTER_LINEAR;
    sampler.minFilter = VK_FILTER_LINEAR;
    sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.maxLod = 0.0f;
    checkVk(vkCreateSampler(device, &sampler, nullptr, &linear_sampler_), "vkCreateSampler");
    VkSamplerCreateInfo texture = sampler;
    texture.addressModeU = texture.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    checkVk(vkCreateSampler(device, &texture, nullptr, &texture_sampler_), "vkCreateSampler");
    VkSamplerCreateInfo shadow = sampler;
    shadow.compareEnable = VK_TRUE;
    shadow.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is no deeper than the stored caster
    shadow.addressModeU = shadow.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    shadow.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    checkVk(vkCreateSampler(device, &shadow, nullptr, &shadow_sampler_), "vkCreateSampler");

    const VkShaderStageFlags graphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkDescriptorSetLayoutBinding frame_bindings[RUNTIME_FRAME_BINDING_COUNT] = {
        {RUNTIME_FRAME_UNIFORMS_BINDING, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, graphics, nullptr},
        {RUNTIME_BUILDING_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_SITE_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_LIGHTMAP_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_IRRADIANCE_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_GEOMETRY_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_COLOUR_MATCH_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
    };
    VkDescriptorSetLayoutCreateInfo frame_layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    frame_layout.bindingCount = RUNTIME_FRAME_BINDING_COUNT;
    frame_layout.pBindings = frame_bindings;
    checkVk(vkCreateDescriptorSetLayout(device, &frame_layout, nullptr, &frame_set_layout_),
            "vkCreateDescriptorSetLayout");
    const VkDescriptorSetLayoutBinding material_binding = {
        RUNTIME_BASE_COLOUR_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo material_layout{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    material_layout.bindingCount = 1;
    material_layout.pBindings = &material_binding;
    checkVk(vkCreateDescriptorSetLayout(device, &material_layout, nullptr, &material_set_layout_),
            "vkCreateDescriptorSetLayout");

    const uint32_t material_count = uint32_t(scene_.base_colour_factors.size());
    const VkDescriptorPoolSize pool_sizes[3] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5 + material_count},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
    };
    VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool.maxSets = 1 + material_count;
    pool.poolSizeCount = 3;
    pool.pPoolSizes = pool_sizes;
    checkVk(vkCreateDescriptorPool(device, &pool, nullptr, &descriptor_pool_), "vkCreateDescriptorPool");

    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = descriptor_pool_;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &frame_set_layout_;
    checkVk(vkAllocateDescriptorSets(device, &allocate, &frame_set_), "vkAllocateDescriptorSets");
    material_sets_.resize(material_count);
    std::vector<VkDescriptorSetLayout> material_layouts(material_count, material_set_layout_);
    allocate.descriptorSetCount = material_count;
    allocate.pSetLayouts = material_layouts.data();
    checkVk(vkAllocateDescriptorSets(device, &allocate, material_sets_.data()), "vkAllocateDescriptorSets");

    const VkDescriptorBufferInfo uniforms{uniform_buffer_.handle(), 0, sizeof(FrameUniforms)};
    const VkDescriptorBufferInfo colour_state{statistics_->stateBuffer().handle(), 0, VK_WHOLE_SIZE};
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo images[5] = {
        {shadow_sampler_, building_shadow_.view(), read},
        {shadow_sampler_, site_shadow_.view(), read},
        {linear_sampler_, scene_.lightmaps.view(), read},
        {linear_sampler_, scene_.ground_irradiance.view(), read},
        {linear_sampler_, scene_.ground_geometry.view(), read},
    };
    std::vector<VkWriteDescriptorSet> writes;
    auto write = [&](VkDescriptorSet set, uint32_t binding, VkDescriptorType type) {
        VkWriteDescriptorSet entry{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        entry.dstSet = set;
        entry.dstBinding = binding;
        entry.descriptorCount = 1;
        entry.descriptorType = type;
        writes.push_back(entry);
        return &writes.back();
    };
    writes.reserve(8 + material_count);
    write(frame_set_, RUNTIME_FRAME_UNIFORMS_BINDING, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)->pBufferInfo = &uniforms;
    const uint32_t image_bindings[5] = {RUNTIME_BUILDING_SHADOW_BINDING, RUNTIME_SITE_SHADOW_BINDING,
                                        RUNTIME_LIGHTMAP_BINDING, RUNTIME_GROUND_IRRADIANCE_BINDING,
                                        RUNTIME_GROUND_GEOMETRY_BINDING};
    for (int index = 0; index < 5; ++index)
        write(frame_set_, image_bindings[index], VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)->pImageInfo = &images[index];
    write(frame_set_, RUNTIME_COLOUR_MATCH_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)->pBufferInfo = &colour_state;
    std::vector<VkDescriptorImageInfo> material_images(material_count);
    for (uint32_t material = 0; material < material_count; ++material) {
        const int texture = scene_.material_texture[material];
        const GpuImage& image = texture >= 0 && size_t(texture) < scene_.textures.size()
                                    ? scene_.textures[size_t(texture)]
                                    : scene_.white_texture;
        material_images[material] = {texture_sampler_, image.view(), read};
        write(material_sets_[material], RUNTIME_BASE_COLOUR_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)
            ->pImageInfo = &material_images[material];
    }
    vkUpdateDescriptorSets(device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void RuntimeImpl::createPipelines() {
    const VkDevice device = gpu_.device;
    VkPushConstantRange depth_push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(DepthOnlyPushConstants)};
    VkPipelineLayoutCreateInfo depth_layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    depth_layout.pushConstantRangeCount = 1;
    depth_layout.pPushConstantRanges = &depth_push;
    checkVk(vkCreatePipelineLayout(device, &depth_layout, nullptr, &depth_layout_), "vkCreatePipelineLayout");
    const VkDescriptorSetLayout set_layouts[2] = {frame_set_layout_, material_set_layout_};
    VkPushConstantRange material_push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(MaterialPushConstants)};
    VkPipelineLayoutCreateInfo shading_layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    shading_layout.setLayoutCount = 2;
    shading_layout.pSetLayouts = set_layouts;
    shading_layout.pushConstantRangeCount = 1;
    shading_layout.pPushConstantRanges = &material_push;
    checkVk(vkCreatePipelineLayout(device, &shading_layout, nullptr, &shading_layout_), "vkCreatePipelineLayout");

    VertexInput positions_only;  // the building's vertices read for position alone, and the occluder's vec3s
    positions_only.stride = sizeof(BuildingVertex);
    positions_only.attributes = {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0}};
    VertexInput occluder_positions = positions_only;
    occluder_positions.stride = sizeof(float) * 3;
    VertexInput building_vertex;
    building_vertex.stride = sizeof(BuildingVertex);
    building_vertex.attributes = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(BuildingVertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, base_colour_uv)},
        {3, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(BuildingVertex, lightmap_uv)},
    };

    GraphicsPipelineDescription shadow;
    shadow.layout = depth_layout_;
    shadow.render_pass = shadow_pass_;
    shadow.vertex_spirv = kDepthOnlyVertSpirv;
    shadow.vertex_spirv_bytes = sizeof(kDepthOnlyVertSpirv);
    shadow.vertex_input = positions_only;
    shadow.has_colour_attachment = false;
    shadow_pipeline_ = createGraphicsPipeline(device, shadow);
    // The occluder's vertices are bare vec3s: the stride is part of a pipeline, so it has pipelines of its own.
    GraphicsPipelineDescription site_shadow = shadow;
    site_shadow.vertex_input = occluder_positions;
    site_shadow_pipeline_ = createGraphicsPipeline(device, site_shadow);
    GraphicsPipelineDescription occluder = shadow;
    occluder.render_pass = main_passes_[0];
    occluder.vertex_input = occluder_positions;
    occluder.has_colour_attachment = true;
    occluder.blend = BlendMode::kNoColourWrites;
    occluder_pipeline_ = createGraphicsPipeline(device, occluder);

    GraphicsPipelineDescription building;
    building.layout = shading_layout_;
    building.render_pass = main_passes_[0];
    building.vertex_spirv = kBuildingVertSpirv;
    building.vertex_spirv_bytes = sizeof(kBuildingVertSpirv);
    building.fragment_spirv = kBuildingFragSpirv;
    building.fragment_spirv_bytes = sizeof(kBuildingFragSpirv);
    building.vertex_input = building_vertex;
    building_pipeline_ = createGraphicsPipeline(device, building);

    GraphicsPipelineDescription ground;
    ground.vertex_input.stride = sizeof(float);  // per cell: the building's shadow may fall here this frame
    ground.vertex_input.attributes = {{0, 0, VK_FORMAT_R32_SFLOAT, 0}};
    ground.layout = shading_layout_;
    ground.render_pass = main_passes_[0];
    ground.vertex_spirv = kGroundVertSpirv;
    ground.vertex_spirv_bytes = sizeof(kGroundVertSpirv);
    ground.fragment_spirv = kGroundFragSpirv;
    ground.fragment_spirv_bytes = sizeof(kGroundFragSpirv);
    ground.depth_write = false;
    ground.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
    ground.blend = BlendMode::kMultiplyTwice;
    // Two variants of the ground's shader, by a specialisation constant: llvmpipe runs every branch of a
    // fragment shader for the whole SIMD group (masked), so a shadow lookup that most fragments skip still costs
    // them all; the quads no shadow can reach get a shader without one (measured on the sample at 1280x720:
    // the ratio pass went from 37 ms to a fraction of it).
    // constant 0: read the building's shadow; constant 1: the sun shines (read the site's shadow, add E_sun).
    const VkBool32 variants[3][2] = {{VK_TRUE, VK_TRUE}, {VK_FALSE, VK_TRUE}, {VK_FALSE, VK_FALSE}};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(VkBool32)}, {1, sizeof(VkBool32), sizeof(VkBool32)}};
    VkSpecializationInfo specialization{2, entries, sizeof(variants[0]), variants[0]};
    ground.fragment_specialization = &specialization;
    ground_pipeline_ = createGraphicsPipeline(device, ground);
    specialization.pData = variants[1];
    ground_baked_pipeline_ = createGraphicsPipeline(device, ground);
    specialization.pData = variants[2];
    ground_sunless_pipeline_ = createGraphicsPipeline(device, ground);
}

uint64_t RuntimeImpl::deviceMemoryBytes() const {
    uint64_t bytes = 0;
    for (const GpuImage* image : {&colour_target_, &depth_target_, &building_shadow_, &site_shadow_,
                                  &scene_.lightmaps, &scene_.ground_irradiance, &scene_.ground_geometry,
                                  &scene_.white_texture})
        bytes += image->memoryBytes();
    for (const GpuImage& texture : scene_.textures) bytes += texture.memoryBytes();
    for (const GpuBuffer* buffer : {&scene_.building_vertices, &scene_.building_indices, &scene_.occluder_vertices,
                                    &scene_.occluder_indices, &scene_.ground_indices, &camera_buffer_,
                                    &readback_buffer_, &ground_candidate_buffer_, &uniform_buffer_, &statistics_->stateBuffer()})
        bytes += buffer->size();
    return bytes;
}

// ---------------------------------------------------------------------------------------------------------------
// The frame on the CPU

FrameInfo RuntimeImpl::prepareFrame(const FrameInput& frame) {
    if (const std::optional<std::string> problem = findFrameProblem(frame, options_.frame_width, options_.frame_height))
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "frame: " + *problem);

    SunObserver observer;
    const GeoPosition position = frame.position.value_or(
        GeoPosition{manifest_.site.latitude_deg, manifest_.site.longitude_deg, manifest_.site.height_m});
    observer.latitude_deg = position.latitude_deg;
    observer.longitude_deg = position.longitude_deg;
    observer.height_m = position.height_m;
    FrameLighting lighting;
    try {
        lighting = computeFrameLighting(manifest_, observer, frame.utc_unix_seconds, frame.weather.cloud_cover,
                                        frame.blend_slots);
    } catch (const std::exception& error) {
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, std::string("frame: ") + error.what());
    }

    FrameInfo info;
    info.sun_azimuth_deg = lighting.sun.azimuth_deg;
    info.sun_apparent_elevation_deg = lighting.sun.apparent_elevation_deg;
    info.sun_above_horizon = lighting.sun.above_horizon;
    info.sun_direction_enu = lighting.sun.direction_enu;
    info.sun_irradiance_rgb = lighting.sun_irradiance_rgb;
    info.slot_a = lighting.slot_a;
    info.slot_b = lighting.slot_b;
    info.slot_b_weight = lighting.slot_b_weight;
    info.overcast_slot = lighting.overcast_slot;
    info.overcast_weight = lighting.overcast_weight;

    const bool direct_only = frame.mode == RenderMode::kDirectOnly;
    sun_shines_ = lighting.sun.above_horizon && glm::length(lighting.sun_irradiance_rgb) > 0.0;
    site_shadows_ = sun_shines_ && !direct_only && scene_.occluder_index_count > 0;
    // The shadow maps' sun: rounded so that they are re-rendered only every shadow_sun_step_deg of its motion.
    glm::dvec3 shadow_sun = lighting.sun.direction_enu;
    if (options_.shadow_sun_step_deg > 0.0f) {
        const double step = double(options_.shadow_sun_step_deg);
        const double azimuth = std::round(lighting.sun.azimuth_deg / step) * step * std::numbers::pi / 180.0;
        const double elevation =
            std::round(lighting.sun.apparent_elevation_deg / step) * step * std::numbers::pi / 180.0;
        shadow_sun = glm::dvec3(std::cos(elevation) * std::sin(azimuth), std::cos(elevation) * std::cos(azimuth),
                                std::sin(elevation));
    }
    // The ground quads to draw: chosen again only when what chooses them changes (the rounded sun, the mode,
    // whether the sun shines); their margin covers the rounding.
    const bool ground_wanted = direct_only ? sun_shines_ : frame.ground_ratio;
    const GroundSelectionKey ground_key{ground_wanted, !direct_only, sun_shines_, shadow_sun};
    if (ground_selection_key_ != ground_key) {
        ground_selection_key_ = ground_key;
        ground_index_count_ = ground_shadow_index_count_ = 0;
        if (ground_wanted) selectGroundQuads(!direct_only, sun_shines_, shadow_sun);
    }
    draw_ground_ = ground_index_count_ > 0;
    info.ground_quads_drawn = ground_index_count_ / 6;
    info.ground_quads_total = scene_.ground_quad_capacity;

    FrameUniforms& u = uniforms_;
    const double far_m = std::max(4.0 * scene_.scene_radius_m + glm::length(frame.pose.position_enu), 100.0);
    toShader(cameraEnuToClip(frame.intrinsics, frame.pose, kNearPlaneM, far_m), u.enu_to_clip);
    // The fit depends only on the static bounds and this rounded sun: made again only when the sun moves a step.
    if (shadow_sun != shadow_sun_direction_) {
        shadow_sun_direction_ = shadow_sun;
        building_shadow_valid_ = site_shadow_valid_ = false;
        shadow_fit_ = fitShadowMap(scene_.receivers_min, scene_.receivers_max, scene_.casters_min,
                                   scene_.casters_max, shadow_sun, options_.shadow_map_size);
    }
    render_building_shadow_ = sun_shines_ && !building_shadow_valid_;
    render_site_shadow_ = site_shadows_ && !site_shadow_valid_;
    const ShadowFit& fit = shadow_fit_;
    toShader(fit.enu_to_clip, u.enu_to_shadow_clip);
    toShader(frame.pose.position_enu, u.camera_position);
    u.exposure = frame.exposure;
    toShader(lighting.sun.direction_enu, u.sun_direction);
    u.sun_shines = sun_shines_ ? 1u : 0u;
    toShader(lighting.sun_irradiance_rgb, u.sun_irradiance);
    u.site_shadows = site_shadows_ ? 1u : 0u;
    const float slot_a = float(std::max(lighting.slot_a, 0)), slot_b = float(std::max(lighting.slot_b, 0));
    const float overcast = float(std::max(lighting.overcast_slot, 0));
    u.slot_layers = {{slot_a, slot_b, overcast}};
    u.render_mode = direct_only ? RUNTIME_RENDER_MODE_DIRECT_ONLY : RUNTIME_RENDER_MODE_PROPOSED;
    const float weight_a = lighting.slot_a >= 0 ? lighting.sunny_weight * (1.0f - lighting.slot_b_weight) : 0.0f;
    const float weight_b = lighting.slot_b >= 0 ? lighting.sunny_weight * lighting.slot_b_weight : 0.0f;
    u.slot_weights = {{weight_a, weight_b, lighting.overcast_slot >= 0 ? lighting.overcast_weight : 0.0f}};
    // Depth bias: the stated texels of the map, in its depth units.
    const double bias = options_.shadow_bias_texels * fit.texel_size_m / fit.depth_range_m;
    u.shadow_texel_uv = 1.0f / float(options_.shadow_map_size);
    u.shadow_depth_bias = float(bias);
    u.shadow_pcf_radius = float(options_.shadow_pcf_radius);
    u.pass_through_threshold = kPassThroughThreshold;
    const GroundGrid& grid = manifest_.ground_grid.grid;
    u.ground_origin_east_m = float(grid.origin_enu_m.x);
    u.ground_origin_north_m = float(grid.origin_enu_m.y);
    u.ground_cell_m = float(grid.cell_m);
    u.ground_pull_m = kGroundPullM;
    u.ground_columns = std::max(grid.columns, 1);
    u.ground_rows = std::max(grid.rows, 1);
    // Direct-only's ambient: one colour, the frame's slots' mean baked E_ind over the building.
    const int blend_slots[3] = {lighting.slot_a, lighting.slot_b, lighting.overcast_slot};
    const float blend_weights[3] = {u.slot_weights[0], u.slot_weights[1], u.slot_weights[2]};
    glm::dvec3 ambient(0.0);
    for (int index = 0; index < 3; ++index)
        if (blend_slots[index] >= 0)
            ambient += double(blend_weights[index]) * glm::dvec3(scene_.slot_mean_indirect[size_t(blend_slots[index])]);
    toShader(ambient * double(options_.direct_only_ambient_fraction), u.direct_only_ambient);
    u.direct_only_shadow_darkening = options_.direct_only_shadow_darkening;
    u.irradiance_scale = scene_.irradiance_scale;
    uniform_buffer_.upload(&uniforms_, sizeof uniforms_);

    // The colour match's source: the baked appearance's statistics, blended like the lightmaps.
    if (frame.colour_match == ColourMatchMode::kGround && !statistics_->hasGround())
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "frame: colour_match: ground needs the bake set's ground_grid.albedo, which this bake set "
                           "lacks (bake it again)");
    frame_colour_mode_ = direct_only ? ColourMatchMode::kOff : frame.colour_match;
    if (frame_colour_mode_ == ColourMatchMode::kGround) {
        GroundMatchView& view = frame_ground_view_;
        view.fx = frame.intrinsics.fx;
        view.fy = frame.intrinsics.fy;
        view.cx = frame.intrinsics.cx;
        view.cy = frame.intrinsics.cy;
        view.camera_position_enu = frame.pose.position_enu;
        view.camera_to_enu = frame.pose.camera_to_enu;
        view.sun_direction_enu = lighting.sun.direction_enu;
        view.sun_shines = sun_shines_;
        view.sun_irradiance_rgb = lighting.sun_irradiance_rgb;
        view.exposure = frame.exposure;
        for (int index = 0; index < 3; ++index) {
            view.slots[index] = blend_slots[index];
            view.weights[index] = blend_weights[index];
        }
    }
    LabStatistics slot_statistics[3];
    for (int index = 0; index < 3; ++index)
        if (blend_slots[index] >= 0) slot_statistics[index] = slot_colour_statistics_[size_t(blend_slots[index])];
    if (blend_weights[0] + blend_weights[1] + blend_weights[2] > 0.0f)
        frame_source_statistics_ = blendLabStatistics(slot_statistics, blend_weights);
    else
        frame_colour_mode_ = ColourMatchMode::kOff;  // night: nothing baked to match from

    // Depth passes' push constants.
    toShader(shadow_fit_.enu_to_clip, shadow_push_.enu_to_clip);
    occluder_push_.enu_to_clip = u.enu_to_clip;
    occluder_push_.pull_m = -kOccluderPushM;
    occluder_push_.pull_origin = u.camera_position;

    if (frame.camera_rgba8 != nullptr)
        camera_buffer_.upload(frame.camera_rgba8, size_t(options_.frame_width) * options_.frame_height * 4);
    return info;
}

// ---------------------------------------------------------------------------------------------------------------
// The frame on the GPU, pass by pass

void RuntimeImpl::recordCameraIn(VkCommandBuffer cmd, const FrameInput& frame) {
    const VkExtent3D extent{options_.frame_width, options_.frame_height, 1};
    if (frame.camera_image != VK_NULL_HANDLE) {
        // The app's image into our buffer (for the statistics and the copy below), in its given layout.
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = extent;
        vkCmdCopyImageToBuffer(cmd, frame.camera_image, frame.camera_image_layout, camera_buffer_.handle(), 1,
                               &region);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
    }
    // The previous frame left the composite in TRANSFER_SRC; its content is replaced whole.
    recordImageLayoutTransition(cmd, colour_target_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_READ_BIT,
                                VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                VK_PIPELINE_STAGE_TRANSFER_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = extent;
    vkCmdCopyBufferToImage(cmd, camera_buffer_.handle(), colour_target_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           1, &region);
    recordImageLayoutTransition(cmd, colour_target_.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
}

void RuntimeImpl::recordStatistics(VkCommandBuffer cmd, const FrameInput& frame) {
    statistics_->recordSourceUpdate(cmd, frame_source_statistics_, frame_colour_mode_, options_.colour_gain_limit);
    if (frame_colour_mode_ == ColourMatchMode::kGround)
        statistics_->recordGround(cmd, camera_buffer_, frame_ground_view_);
    else if (frame_colour_mode_ != ColourMatchMode::kOff)
        statistics_->record(cmd, camera_buffer_);
}

void RuntimeImpl::recordShadows(VkCommandBuffer cmd) {
    if (!render_building_shadow_ && !render_site_shadow_) return;
    const VkDeviceSize offset = 0;
    auto shadowPass = [&](VkFramebuffer framebuffer, const DepthOnlyPushConstants& push, VkPipeline pipeline,
                          const GpuBuffer& vertices, const GpuBuffer& indices, uint32_t index_count) {
        VkClearValue clear{};
        clear.depthStencil = {1.0f, 0};
        VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        begin.renderPass = shadow_pass_;
        begin.framebuffer = framebuffer;
        begin.renderArea = {{0, 0}, {options_.shadow_map_size, options_.shadow_map_size}};
        begin.clearValueCount = 1;
        begin.pClearValues = &clear;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        recordViewport(cmd, options_.shadow_map_size, options_.shadow_map_size);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vkCmdPushConstants(cmd, depth_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof push, &push);
        const VkBuffer vertex_buffer = vertices.handle();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
        vkCmdBindIndexBuffer(cmd, indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, index_count, 1, 0, 0, 0);
        vkCmdEndRenderPass(cmd);
    };
    if (render_building_shadow_) {
        shadowPass(building_shadow_framebuffer_, shadow_push_, shadow_pipeline_, scene_.building_vertices,
                   scene_.building_indices, scene_.building_index_count);
        building_shadow_valid_ = true;
    }
    if (render_site_shadow_) {
        shadowPass(site_shadow_framebuffer_, shadow_push_, site_shadow_pipeline_, scene_.occluder_vertices,
                   scene_.occluder_indices, scene_.occluder_index_count);
        site_shadow_valid_ = true;
    }
}

void RuntimeImpl::beginMainPass(VkCommandBuffer cmd, VkRenderPass render_pass) {
    VkClearValue clears[2]{};
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = render_pass;
    begin.framebuffer = main_framebuffer_;  // compatible with every variant
    begin.renderArea = {{0, 0}, {options_.frame_width, options_.frame_height}};
    begin.clearValueCount = 2;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    recordViewport(cmd, options_.frame_width, options_.frame_height);
}

void RuntimeImpl::recordOccluder(VkCommandBuffer cmd) {
    if (scene_.occluder_index_count == 0) return;
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, occluder_pipeline_);
    vkCmdPushConstants(cmd, depth_layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof occluder_push_, &occluder_push_);
    const VkBuffer vertex_buffer = scene_.occluder_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene_.occluder_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, scene_.occluder_index_count, 1, 0, 0, 0);
}

void RuntimeImpl::recordBuilding(VkCommandBuffer cmd) {
    const VkDeviceSize offset = 0;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, building_pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_FRAME_SET, 1, &frame_set_,
                            0, nullptr);
    const VkBuffer vertex_buffer = scene_.building_vertices.handle();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &offset);
    vkCmdBindIndexBuffer(cmd, scene_.building_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    for (const MaterialDraw& draw : scene_.draws) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_MATERIAL_SET, 1,
                                &material_sets_[draw.material], 0, nullptr);
        const glm::vec4& factor = scene_.base_colour_factors[draw.material];
        const MaterialPushConstants push{{{factor.r, factor.g, factor.b, factor.a}}};
        vkCmdPushConstants(cmd, shading_layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push, &push);
        vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, 0, 0);
    }
}

void RuntimeImpl::recordGround(VkCommandBuffer cmd) {
    if (!draw_ground_) return;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_, RUNTIME_FRAME_SET, 1, &frame_set_,
                            0, nullptr);
    const VkBuffer candidates = ground_candidate_buffer_.handle();
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &candidates, &offset);
    vkCmdBindIndexBuffer(cmd, scene_.ground_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    if (ground_shadow_index_count_ > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ground_pipeline_);
        vkCmdDrawIndexed(cmd, ground_shadow_index_count_, 1, 0, 0, 0);
    }
    if (ground_index_count_ > ground_shadow_index_count_) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          sun_shines_ ? ground_baked_pipeline_ : ground_sunless_pipeline_);
        vkCmdDrawIndexed(cmd, ground_index_count_ - ground_shadow_index_count_, 1, ground_shadow_index_count_, 0, 0);
    }
}

void RuntimeImpl::recordReadback(VkCommandBuffer cmd) {
    // The main pass left the composite in TRANSFER_SRC_OPTIMAL (its final layout).
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {options_.frame_width, options_.frame_height, 1};
    vkCmdCopyImageToBuffer(cmd, colour_target_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           readback_buffer_.handle(), 1, &region);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr,
                         0, nullptr);
}

// The ground quads the building can change this frame: those touching a cell whose baked light it changes
// (proposed mode), or a cell whose ray towards the sun passes through the building's bounds grown by a margin
// (its shadow with the PCF's reach). The rest of the grid is not drawn at all: its camera pixels are never
// touched. Fills the host arrays made at open and the host-visible index buffer; a few microseconds per frame.
void RuntimeImpl::selectGroundQuads(bool include_baked_changes, bool sun_shines, const glm::dvec3& sun_direction) {
    const GroundGrid& grid = manifest_.ground_grid.grid;
    const size_t columns = size_t(std::max(grid.columns, 0)), rows = size_t(std::max(grid.rows, 0));
    if (scene_.ground_quad_capacity == 0 || scene_.ground_cell_state.size() != columns * rows) return;
    const double margin = 2.0 * grid.cell_m + 0.25;
    const glm::dvec3 low = scene_.building_min - margin, high = scene_.building_max + margin;
    for (size_t row = 0; row < rows; ++row)
        for (size_t column = 0; column < columns; ++column) {
            const size_t cell = row * columns + column;
            const uint8_t state = scene_.ground_cell_state[cell];
            const bool baked_change = include_baked_changes && state == 2;
            bool shadow_candidate = false;
            if (state != 0 && sun_shines) {
                // Slab test of the ray cell centre + t s, t > 0, against the grown bounds.
                const glm::dvec3 origin(grid.origin_enu_m.x + (double(column) + 0.5) * grid.cell_m,
                                        grid.origin_enu_m.y + (double(rows - row) - 0.5) * grid.cell_m,
                                        double(scene_.ground_cell_height[cell]));
                double near_t = 0.0, far_t = 1e30;
                for (int axis = 0; axis < 3 && near_t <= far_t; ++axis) {
                    if (std::abs(sun_direction[axis]) < 1e-12) {
                        if (origin[axis] < low[axis] || origin[axis] > high[axis]) far_t = -1.0;
                        continue;
                    }
                    double t0 = (low[axis] - origin[axis]) / sun_direction[axis];
                    double t1 = (high[axis] - origin[axis]) / sun_direction[axis];
                    if (t0 > t1) std::swap(t0, t1);
                    near_t = std::max(near_t, t0);
                    far_t = std::min(far_t, t1);
                }
                shadow_candidate = near_t <= far_t;
            }
            ground_cell_marked_[cell] = (baked_change || shadow_candidate) ? 1 : 0;
            ground_shadow_candidate_[cell] = shadow_candidate ? 1.0f : 0.0f;
        }
    // Quads the shadow may reach first (drawn with the shadow-reading shader), then the rest.
    uint32_t quads = 0;
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t row = 0; row + 1 < rows; ++row)
            for (size_t column = 0; column + 1 < columns; ++column) {
                const uint32_t a = uint32_t(row * columns + column), b = a + 1, c = a + uint32_t(columns), d = c + 1;
                if (!(ground_cell_marked_[a] | ground_cell_marked_[b] | ground_cell_marked_[c] | ground_cell_marked_[d]))
                    continue;
                const bool shadow = ground_shadow_candidate_[a] + ground_shadow_candidate_[b] +
                                        ground_shadow_candidate_[c] + ground_shadow_candidate_[d] > 0.0f;
                if (shadow != (pass == 0)) continue;
                uint32_t* quad = &ground_quad_indices_[size_t(quads) * 6];
                quad[0] = a, quad[1] = c, quad[2] = b, quad[3] = b, quad[4] = c, quad[5] = d;
                ++quads;
            }
        if (pass == 0) ground_shadow_index_count_ = quads * 6;
    }
    ground_index_count_ = quads * 6;
    if (quads > 0) {
        scene_.ground_indices.upload(ground_quad_indices_.data(), size_t(quads) * 6 * sizeof(uint32_t));
        ground_candidate_buffer_.upload(ground_shadow_candidate_.data(), ground_shadow_candidate_.size() * sizeof(float));
    }
}

void RuntimeImpl::beginCommands() {
    checkVk(vkResetCommandBuffer(command_buffer_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    checkVk(vkBeginCommandBuffer(command_buffer_, &begin), "vkBeginCommandBuffer");
}

void RuntimeImpl::submitCommandsAndWait() {
    checkVk(vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");
    VkSubmitInfo submit_info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit_info.commandBufferCount = 1;
    submit_info.pCommandBuffers = &command_buffer_;
    checkVk(gpu_.submitToQueue(submit_info, fence_), "vkQueueSubmit");
    checkVk(vkWaitForFences(gpu_.device, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    checkVk(vkResetFences(gpu_.device, 1, &fence_), "vkResetFences");
}

void RuntimeImpl::finishOutput(uint8_t* output_rgba8) {
    if (output_rgba8 != nullptr)
        readback_buffer_.download(output_rgba8, size_t(options_.frame_width) * options_.frame_height * 4);
}

FrameInfo RuntimeImpl::renderFrame(const FrameInput& frame, uint8_t* output_rgba8) {
    const FrameInfo info = prepareFrame(frame);
    try {
        submit([&](VkCommandBuffer cmd) {
            recordCameraIn(cmd, frame);
            recordStatistics(cmd, frame);
            recordShadows(cmd);
            beginMainPass(cmd, main_passes_[0]);
            recordOccluder(cmd);
            recordBuilding(cmd);
            recordGround(cmd);
            vkCmdEndRenderPass(cmd);
            recordReadback(cmd);
        });
        finishOutput(output_rgba8);
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
    return info;
}

FrameInfo RuntimeImpl::renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) {
    using Clock = std::chrono::steady_clock;
    auto milliseconds = [](Clock::time_point from, Clock::time_point to) {
        return std::chrono::duration<double, std::milli>(to - from).count();
    };
    const Clock::time_point start = Clock::now();
    const FrameInfo info = prepareFrame(frame);
    // Each pass alone in its own submission, waited for: lavapipe writes timestamps only when graphics work is
    // flushed (docs/design.md 5), so wall time around a fenced submission is the honest per-pass figure.
    auto timed = [&](double& slot, const auto& record) {
        const Clock::time_point pass_start = Clock::now();
        submit(record);
        slot = milliseconds(pass_start, Clock::now());
    };
    try {
        timed(timings.upload_ms, [&](VkCommandBuffer cmd) { recordCameraIn(cmd, frame); });
        timed(timings.statistics_ms, [&](VkCommandBuffer cmd) { recordStatistics(cmd, frame); });
        timed(timings.shadow_ms, [&](VkCommandBuffer cmd) { recordShadows(cmd); });
        timed(timings.occluder_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[1]);
            recordOccluder(cmd);
            vkCmdEndRenderPass(cmd);
        });
        timed(timings.building_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[2]);
            recordBuilding(cmd);
            vkCmdEndRenderPass(cmd);
        });
        timed(timings.ground_ms, [&](VkCommandBuffer cmd) {
            beginMainPass(cmd, main_passes_[3]);
            recordGround(cmd);
            vkCmdEndRenderPass(cmd);
        });
        timed(timings.readback_ms, [&](VkCommandBuffer cmd) { recordReadback(cmd); });
        const Clock::time_point copy_start = Clock::now();
        finishOutput(output_rgba8);
        timings.readback_ms += milliseconds(copy_start, Clock::now());
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
    timings.total_ms = milliseconds(start, Clock::now());
    return info;
}

// A runtime that owns the headless device it runs on: the context is made first and destroyed last.
class HeadlessRuntime final : public Runtime {
public:
    HeadlessRuntime(const BakeSetData& bake_set, const RuntimeOptions& options)
        : context_(vulkanOptionsFromEnvironment()), runtime_(context_.gpu(), bake_set, options) {}
    FrameInfo renderFrame(const FrameInput& frame, uint8_t* output_rgba8) override {
        return runtime_.renderFrame(frame, output_rgba8);
    }
    FrameInfo renderFrameProfiled(const FrameInput& frame, uint8_t* output_rgba8, PassTimings& timings) override {
        return runtime_.renderFrameProfiled(frame, output_rgba8, timings);
    }
    VkImage compositeImage() const override { return runtime_.compositeImage(); }
    void resetColourStatistics() override { runtime_.resetColourStatistics(); }
    void invalidateShadowMaps() override { runtime_.invalidateShadowMaps(); }
    uint64_t deviceMemoryBytes() const override { return runtime_.deviceMemoryBytes(); }

private:
    VulkanContext context_;
    RuntimeImpl runtime_;
};

}  // namespace

std::unique_ptr<Runtime> Runtime::openHeadless(const BakeSetData& bake_set, const RuntimeOptions& options) {
    try {
        return std::make_unique<HeadlessRuntime>(bake_set, options);
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw RuntimeError(RuntimeErrorCode::kOutOfMemory, "gusuku runtime: out of host memory opening the bake set");
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
}

std::unique_ptr<Runtime> Runtime::open(const GpuDevice& gpu, const BakeSetData& bake_set,
                                       const RuntimeOptions& options) {
    try {
        return std::make_unique<RuntimeImpl>(gpu, bake_set, options);
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw RuntimeError(RuntimeErrorCode::kOutOfMemory, "gusuku runtime: out of host memory opening the bake set");
    } catch (const std::exception& error) {
        throw deviceError(error);
    }
}

}  // namespace gusuku
