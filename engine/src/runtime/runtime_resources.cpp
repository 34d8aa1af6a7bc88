// The runtime's device resources made once in open() (runtime_impl.h): the ground selection's host arrays, the
// frame's targets and shadow maps, the descriptor sets, the command buffer and fence; their release; and what
// they weigh in device memory.

#include <algorithm>
#include <vector>

#include "gusuku/gpu/gpu_compute.h"
#include "runtime_impl.h"
#include "runtime_pipelines.h"

namespace gusuku::runtime_detail {

using shader_interface::FrameUniforms;

void RuntimeImpl::createGroundSelectionArrays() {
    ground_cell_marked_.assign(scene_.ground_cell_state.size(), 0);
    ground_shadow_candidate_.assign(scene_.ground_cell_state.size(), 0.0f);
    ground_quad_indices_.assign(size_t(scene_.ground_quad_capacity) * 6, 0);
}

// The main pass's render passes and the attachments the frame slots share: the depth, or multisampled, the
// colour the pass draws and its depth.
void RuntimeImpl::createMainTargets() {
    const uint32_t width = options_.frame_width, height = options_.frame_height;
    main_depth_format_ = mainDepthStencilFormat(gpu_.physical_device);  // checked by checkDeviceRequirements
    const VkSampleCountFlagBits samples = mainPassSamples();
    if (samples == VK_SAMPLE_COUNT_1_BIT) {
        GpuImageDescription depth;
        depth.format = main_depth_format_;
        depth.width = width;
        depth.height = height;
        depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        depth.aspect = VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
        depth_target_ = GpuImage(gpu_, depth);
    } else {
        msaa_colour_ = MultisampleTarget(gpu_, {kColourFormat, VK_IMAGE_ASPECT_COLOR_BIT, width, height, samples});
        msaa_depth_ = MultisampleTarget(gpu_, {main_depth_format_, VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT,
                                               width, height, samples});
    }
    const MainPassVariant variants[4] = {MainPassVariant::kWhole, MainPassVariant::kFirst, MainPassVariant::kMiddle,
                                         MainPassVariant::kLast};
    for (int index = 0; index < 4; ++index)
        main_passes_[index] = createMainRenderPass(gpu_.device, variants[index], samples, main_depth_format_);
}

void RuntimeImpl::createTargets() {
    const uint32_t width = options_.frame_width, height = options_.frame_height;
    createMainTargets();
    GpuImageDescription shadow;
    shadow.format = kDepthFormat;
    shadow.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    shadow.width = shadow.height = options_.shadow_map_size;
    shadow.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    building_shadow_ = GpuImage(gpu_, shadow);
    site_shadow_ = GpuImage(gpu_, shadow);
    uniform_buffer_ = GpuBuffer(gpu_, sizeof(FrameUniforms),
                                VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                GpuMemory::kDeviceLocal);

    const VkDevice device = gpu_.device;
    shadow_pass_ = createShadowRenderPass(device);
    building_shadow_framebuffer_ = createFramebuffer(device, shadow_pass_, {building_shadow_.view()},
                                                     options_.shadow_map_size, options_.shadow_map_size);
    site_shadow_framebuffer_ = createFramebuffer(device, shadow_pass_, {site_shadow_.view()},
                                                 options_.shadow_map_size, options_.shadow_map_size);

    GpuImageDescription colour;
    colour.format = kColourFormat;
    colour.width = width;
    colour.height = height;
    colour.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    const size_t index_bytes = std::max<size_t>(size_t(scene_.ground_quad_capacity) * 6 * sizeof(uint32_t),
                                                kMinBufferBytes);
    const size_t candidate_bytes = std::max<size_t>(ground_shadow_candidate_.size() * sizeof(float), kMinBufferBytes);
    slots_.resize(options_.frames_in_flight);
    for (FrameSlot& slot : slots_) {
        slot.composite = GpuImage(gpu_, colour);
        const std::vector<VkImageView> views =
            mainPassSamples() == VK_SAMPLE_COUNT_1_BIT
                ? std::vector<VkImageView>{slot.composite.view(), depth_target_.view()}
                : std::vector<VkImageView>{msaa_colour_.view(), msaa_depth_.view(), slot.composite.view()};
        slot.framebuffer = createFramebuffer(device, main_passes_[0], views, width, height);
        slot.readback = GpuBuffer(gpu_, size_t(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        slot.ground_indices = GpuBuffer(gpu_, index_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, GpuMemory::kHostVisible);
        slot.ground_candidates =
            GpuBuffer(gpu_, candidate_bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, GpuMemory::kHostVisible);
    }

    // Shadow maps start in the layout the frame set's descriptors name, so a frame that skips them reads a
    // defined (cleared) map; composites in the layout compositeImage() promises.
    GpuSubmitter submitter(gpu_);
    submitter.submitAndWait([&](VkCommandBuffer cmd) {
        for (const GpuImage* map : {&building_shadow_, &site_shadow_})
            recordImageLayoutTransition(cmd, map->handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, VK_ACCESS_SHADER_READ_BIT,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
        for (const FrameSlot& slot : slots_)
            recordImageLayoutTransition(cmd, slot.composite.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                        VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, 0,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    });
}

namespace {

// The building's map read as depths (runtime_shadow.glsl's blocker search gathers them): the compare sampler's
// addressing (outside the map: far, lit), nearest and no compare (D32_SFLOAT need not filter linearly without one).
VkSampler createDepthReadSampler(VkDevice device, VkSamplerCreateInfo info) {
    info.compareEnable = VK_FALSE;
    info.magFilter = info.minFilter = VK_FILTER_NEAREST;
    VkSampler sampler = VK_NULL_HANDLE;
    checkVk(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
    return sampler;
}

// The base colour's level of detail, biased towards the finer level: the trilinear read's tent over two texels of
// the chosen level is wider than a pixel's own box average of the texture (what the path tracer's samples give).
// Measured on the shrine at 320 x 180 against 512 spp truths: -0.5 took its composite from 1.84 / 1.98 to
// 1.79 / 1.86 mean dE00 and -1 to 1.76 / 1.86 (front / corner, docs/measurements.md); most of what the 1x frame
// still lacks against the truth's detail is coverage at geometric edges, not the texture. Half of that step, not
// all of it: a finer level skips more of the texels under a pixel, which shimmers as the camera moves, and the
// bench's still frames cannot measure that.
constexpr float kBaseColourLodBias = -0.5f;

}  // namespace

void RuntimeImpl::createDescriptors() {
    const VkDevice device = gpu_.device;
    // Lightmaps and the ground's images: bilinear on their one level (runtime_scene.cpp's uploadLightmaps says
    // why the lightmaps have no mips).
    VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    sampler.magFilter = VK_FILTER_LINEAR;
    sampler.minFilter = VK_FILTER_LINEAR;
    sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler.maxLod = 0.0f;
    checkVk(vkCreateSampler(device, &sampler, nullptr, &linear_sampler_), "vkCreateSampler");
    // Base colour: trilinear over the full mip chain (runtime_scene.cpp), anisotropic where the app enabled it.
    VkSamplerCreateInfo texture = sampler;
    texture.addressModeU = texture.addressModeV = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    texture.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    texture.maxLod = VK_LOD_CLAMP_NONE;
    const float anisotropy = std::min(options_.max_anisotropy, gpu_.limits().maxSamplerAnisotropy);
    texture.anisotropyEnable = anisotropy > 1.0f ? VK_TRUE : VK_FALSE;
    texture.maxAnisotropy = std::max(anisotropy, 1.0f);
    const float lod_bias_limit = gpu_.limits().maxSamplerLodBias;
    texture.mipLodBias = std::clamp(kBaseColourLodBias, -lod_bias_limit, lod_bias_limit);
    checkVk(vkCreateSampler(device, &texture, nullptr, &texture_sampler_), "vkCreateSampler");
    VkSamplerCreateInfo shadow = sampler;
    shadow.compareEnable = VK_TRUE;
    shadow.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is no deeper than the stored caster
    shadow.addressModeU = shadow.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    shadow.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    checkVk(vkCreateSampler(device, &shadow, nullptr, &shadow_sampler_), "vkCreateSampler");
    shadow_depth_sampler_ = createDepthReadSampler(device, shadow);

    const VkShaderStageFlags graphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkDescriptorSetLayoutBinding frame_bindings[RUNTIME_FRAME_BINDING_COUNT] = {
        {RUNTIME_FRAME_UNIFORMS_BINDING, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, graphics, nullptr},
        {RUNTIME_BUILDING_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_SITE_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_LIGHTMAP_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_IRRADIANCE_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_GEOMETRY_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_COLOUR_MATCH_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RUNTIME_BUILDING_SHADOW_DEPTH_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
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
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6 + material_count},
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
    const VkDescriptorBufferInfo colour_state{colourStateBuffer().handle(), 0, VK_WHOLE_SIZE};
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo images[6] = {
        {shadow_sampler_, building_shadow_.view(), read},
        {shadow_sampler_, site_shadow_.view(), read},
        {linear_sampler_, scene_.lightmaps.view(), read},
        {linear_sampler_, scene_.ground_irradiance.view(), read},
        {linear_sampler_, scene_.ground_geometry.view(), read},
        {shadow_depth_sampler_, building_shadow_.view(), read},
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
    const uint32_t image_bindings[6] = {RUNTIME_BUILDING_SHADOW_BINDING, RUNTIME_SITE_SHADOW_BINDING,
                                        RUNTIME_LIGHTMAP_BINDING, RUNTIME_GROUND_IRRADIANCE_BINDING,
                                        RUNTIME_GROUND_GEOMETRY_BINDING, RUNTIME_BUILDING_SHADOW_DEPTH_BINDING};
    for (int index = 0; index < 6; ++index)
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

void RuntimeImpl::createCommands() {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = gpu_.queue_family_index;
    checkVk(vkCreateCommandPool(gpu_.device, &pool_info, nullptr, &command_pool_), "vkCreateCommandPool");
    for (FrameSlot& slot : slots_) {
        VkCommandBufferAllocateInfo allocate_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate_info.commandPool = command_pool_;
        allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate_info.commandBufferCount = 1;
        checkVk(vkAllocateCommandBuffers(gpu_.device, &allocate_info, &slot.command_buffer),
                "vkAllocateCommandBuffers");
        VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        checkVk(vkCreateFence(gpu_.device, &fence_info, nullptr, &slot.fence), "vkCreateFence");
    }
}

void RuntimeImpl::destroy() noexcept {
    VkDevice device = gpu_.device;
    if (device == VK_NULL_HANDLE) return;
    vkDeviceWaitIdle(device);
    for (FrameSlot& slot : slots_) {
        if (slot.fence) vkDestroyFence(device, slot.fence, nullptr);
        if (slot.framebuffer) vkDestroyFramebuffer(device, slot.framebuffer, nullptr);
        slot.fence = VK_NULL_HANDLE;
        slot.framebuffer = VK_NULL_HANDLE;
    }
    camera_.reset();
    if (command_pool_) vkDestroyCommandPool(device, command_pool_, nullptr);
    for (VkPipeline pipeline :
         {shadow_pipeline_, site_shadow_pipeline_, occluder_pipeline_, building_pipeline_, ground_pipeline_,
          ground_baked_pipeline_, ground_sunless_pipeline_, building_masked_pipeline_, masked_shadow_pipeline_})
        if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    for (VkPipelineLayout layout : {depth_layout_, shading_layout_, masked_depth_layout_})
        if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
    if (descriptor_pool_) vkDestroyDescriptorPool(device, descriptor_pool_, nullptr);
    for (VkDescriptorSetLayout layout : {frame_set_layout_, material_set_layout_})
        if (layout) vkDestroyDescriptorSetLayout(device, layout, nullptr);
    for (VkSampler sampler : {linear_sampler_, shadow_sampler_, shadow_depth_sampler_, texture_sampler_})
        if (sampler) vkDestroySampler(device, sampler, nullptr);
    for (VkFramebuffer framebuffer : {building_shadow_framebuffer_, site_shadow_framebuffer_})
        if (framebuffer) vkDestroyFramebuffer(device, framebuffer, nullptr);
    for (VkRenderPass render_pass : main_passes_)
        if (render_pass) vkDestroyRenderPass(device, render_pass, nullptr);
    if (shadow_pass_) vkDestroyRenderPass(device, shadow_pass_, nullptr);
    command_pool_ = VK_NULL_HANDLE;
    shadow_pipeline_ = site_shadow_pipeline_ = occluder_pipeline_ = building_pipeline_ = ground_pipeline_ =
        ground_baked_pipeline_ = ground_sunless_pipeline_ = building_masked_pipeline_ = masked_shadow_pipeline_ =
            VK_NULL_HANDLE;
    depth_layout_ = shading_layout_ = masked_depth_layout_ = VK_NULL_HANDLE;
    descriptor_pool_ = VK_NULL_HANDLE;
    frame_set_layout_ = material_set_layout_ = VK_NULL_HANDLE;
    linear_sampler_ = shadow_sampler_ = shadow_depth_sampler_ = texture_sampler_ = VK_NULL_HANDLE;
    building_shadow_framebuffer_ = site_shadow_framebuffer_ = VK_NULL_HANDLE;
    for (VkRenderPass& render_pass : main_passes_) render_pass = VK_NULL_HANDLE;
    shadow_pass_ = VK_NULL_HANDLE;
    // Buffers, images and the statistics pass release themselves.
}

uint64_t RuntimeImpl::deviceMemoryBytes() const {
    uint64_t bytes = camera_ ? camera_->memoryBytes() : 0;
    bytes += msaa_colour_.memoryBytes() + msaa_depth_.memoryBytes();
    for (const GpuImage* image : {&depth_target_, &building_shadow_, &site_shadow_, &scene_.lightmaps,
                                  &scene_.ground_irradiance, &scene_.ground_geometry, &scene_.white_texture})
        bytes += image->memoryBytes();
    for (const GpuImage& texture : scene_.textures) bytes += texture.memoryBytes();
    for (const GpuBuffer* buffer : {&scene_.building_vertices, &scene_.building_indices, &scene_.occluder_vertices,
                                    &scene_.occluder_indices, &uniform_buffer_, &colourStateBuffer()})
        bytes += buffer->size();
    for (const FrameSlot& slot : slots_)
        bytes += slot.composite.memoryBytes() + slot.readback.size() + slot.ground_indices.size() +
                 slot.ground_candidates.size();
    return bytes;
}

}  // namespace gusuku::runtime_detail
