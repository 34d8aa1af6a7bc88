// The one helper device_object.h declares beside its RAII holder.

#include "device_object.h"

#include "gusuku/gpu/gpu_device.h"

namespace gusuku::runtime_detail {

PipelineLayout createPipelineLayout(VkDevice device, std::initializer_list<VkDescriptorSetLayout> set_layouts,
                                    VkShaderStageFlags push_stages, uint32_t push_bytes) {
    const VkPushConstantRange push{push_stages, 0, push_bytes};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = uint32_t(set_layouts.size());
    info.pSetLayouts = set_layouts.begin();
    info.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    info.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    checkVk(vkCreatePipelineLayout(device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return PipelineLayout(device, layout);
}

}  // namespace gusuku::runtime_detail
