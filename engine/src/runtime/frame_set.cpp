// The shading passes' frame set (frame_set.h).

#include "frame_set.h"

#include "material_sets.h"
#include "runtime_material_push.h"
#include "runtime_scene.h"
#include "shadow_pass.h"

namespace gusuku::runtime_detail {

using shader_interface::FrameUniforms;

namespace {

Sampler createSampler(VkDevice device, const VkSamplerCreateInfo& info) {
    VkSampler sampler = VK_NULL_HANDLE;
    checkVk(vkCreateSampler(device, &info, nullptr, &sampler), "vkCreateSampler");
    return Sampler(device, sampler);
}

}  // namespace

FrameSet::FrameSet(const PassContext& context, const ShadowPass& shadows, const MaterialSets& materials,
                   const GpuBuffer& colour_state) {
    const VkDevice device = context.gpu.device;
    createSamplers(context);
    const VkShaderStageFlags graphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkDescriptorSetLayoutBinding bindings[RUNTIME_FRAME_BINDING_COUNT] = {
        {RUNTIME_FRAME_UNIFORMS_BINDING, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, graphics, nullptr},
        {RUNTIME_BUILDING_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_SITE_SHADOW_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_LIGHTMAP_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_IRRADIANCE_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_GROUND_GEOMETRY_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, graphics, nullptr},
        {RUNTIME_COLOUR_MATCH_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RUNTIME_BUILDING_SHADOW_DEPTH_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
         VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
        {RUNTIME_SUN_HORIZON_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
         nullptr},
    };
    VkDescriptorSetLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout_info.bindingCount = RUNTIME_FRAME_BINDING_COUNT;
    layout_info.pBindings = bindings;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &set_layout), "vkCreateDescriptorSetLayout");
    set_layout_ = DescriptorSetLayout(device, set_layout);
    shading_layout_ = createPipelineLayout(device, {set_layout, materials.layout()}, VK_SHADER_STAGE_FRAGMENT_BIT,
                                           sizeof(shader_interface::MaterialPushConstants));
    uniform_buffer_ = GpuBuffer(context.gpu, sizeof(FrameUniforms),
                                VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                GpuMemory::kDeviceLocal);
    writeSet(context, shadows, colour_state);
}

void FrameSet::createSamplers(const PassContext& context) {
    const VkDevice device = context.gpu.device;
    // Lightmaps and the ground's images: bilinear on their one level (runtime_scene.cpp's uploadLightmaps says
    // why the lightmaps have no mips).
    VkSamplerCreateInfo linear{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    linear.magFilter = VK_FILTER_LINEAR;
    linear.minFilter = VK_FILTER_LINEAR;
    linear.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    linear.addressModeU = linear.addressModeV = linear.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    linear.maxLod = 0.0f;
    linear_sampler_ = createSampler(device, linear);
    VkSamplerCreateInfo shadow = linear;
    shadow.compareEnable = VK_TRUE;
    shadow.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit when the receiver is no deeper than the stored caster
    shadow.addressModeU = shadow.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    shadow.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    shadow_sampler_ = createSampler(device, shadow);
    // The building's map read as depths (runtime_shadow.glsl's blocker search gathers them): the compare sampler's
    // addressing (outside the map: far, lit), nearest and no compare (D32_SFLOAT need not filter linearly without
    // one).
    VkSamplerCreateInfo depth = shadow;
    depth.compareEnable = VK_FALSE;
    depth.magFilter = depth.minFilter = VK_FILTER_NEAREST;
    shadow_depth_sampler_ = createSampler(device, depth);
}

void FrameSet::writeSet(const PassContext& context, const ShadowPass& shadows, const GpuBuffer& colour_state) {
    const VkDevice device = context.gpu.device;
    const GpuScene& scene = context.scene;
    const VkDescriptorPoolSize pool_sizes[3] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 7},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
    };
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 3;
    pool_info.pPoolSizes = pool_sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    checkVk(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
    pool_ = DescriptorPool(device, pool);
    VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocate.descriptorPool = pool;
    allocate.descriptorSetCount = 1;
    const VkDescriptorSetLayout set_layout = set_layout_.get();
    allocate.pSetLayouts = &set_layout;
    checkVk(vkAllocateDescriptorSets(device, &allocate, &set_), "vkAllocateDescriptorSets");

    const VkDescriptorBufferInfo uniforms{uniform_buffer_.handle(), 0, sizeof(FrameUniforms)};
    const VkDescriptorBufferInfo colour{colour_state.handle(), 0, VK_WHOLE_SIZE};
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkDescriptorImageInfo images[7] = {
        {shadow_sampler_.get(), shadows.buildingMap().view(), read},
        {shadow_sampler_.get(), shadows.siteMap().view(), read},
        {linear_sampler_.get(), scene.lightmaps.view(), read},
        {linear_sampler_.get(), scene.ground_irradiance.view(), read},
        {linear_sampler_.get(), scene.ground_geometry.view(), read},
        {shadow_depth_sampler_.get(), shadows.buildingMap().view(), read},
        {linear_sampler_.get(), scene.sun_horizon.view(), read},
    };
    const uint32_t image_bindings[7] = {RUNTIME_BUILDING_SHADOW_BINDING, RUNTIME_SITE_SHADOW_BINDING,
                                        RUNTIME_LIGHTMAP_BINDING, RUNTIME_GROUND_IRRADIANCE_BINDING,
                                        RUNTIME_GROUND_GEOMETRY_BINDING, RUNTIME_BUILDING_SHADOW_DEPTH_BINDING,
                                        RUNTIME_SUN_HORIZON_BINDING};
    VkWriteDescriptorSet writes[9];
    for (VkWriteDescriptorSet& write : writes) {
        write = VkWriteDescriptorSet{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = set_;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    }
    writes[0].dstBinding = RUNTIME_FRAME_UNIFORMS_BINDING;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    writes[0].pBufferInfo = &uniforms;
    for (int index = 0; index < 7; ++index) {
        writes[1 + index].dstBinding = image_bindings[index];
        writes[1 + index].pImageInfo = &images[index];
    }
    writes[8].dstBinding = RUNTIME_COLOUR_MATCH_BINDING;
    writes[8].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[8].pBufferInfo = &colour;
    vkUpdateDescriptorSets(device, 9, writes, 0, nullptr);
}

// Outside any render pass, before the others: this frame's uniforms into their buffer, after the earlier frames'
// reads of it.
void FrameSet::recordBefore(PassRecording& recording) {
    static_assert(sizeof uniforms_ <= 65536 && sizeof uniforms_ % 4 == 0, "vkCmdUpdateBuffer's limits");
    const VkCommandBuffer cmd = recording.cmd;
    const VkPipelineStageFlags uniform_readers =
        VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};  // the earlier frames' reads first (execution only)
    vkCmdPipelineBarrier(cmd, uniform_readers, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    vkCmdUpdateBuffer(cmd, uniform_buffer_.handle(), 0, sizeof uniforms_, &uniforms_);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_UNIFORM_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, uniform_readers, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
}

void FrameSet::bindOnce(PassRecording& recording) const {
    if (recording.bound_frame_set == set_) return;
    vkCmdBindDescriptorSets(recording.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shading_layout_.get(), RUNTIME_FRAME_SET,
                            1, &set_, 0, nullptr);
    recording.bound_frame_set = set_;
}

}  // namespace gusuku::runtime_detail
