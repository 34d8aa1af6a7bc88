#pragma once
// The building's materials as descriptor sets (one per material: its base colour texture and the trilinear,
// anisotropic sampler), read by the building pass and by the shadow pass's alpha-masked materials. Made once in
// open(); immutable after. Private to gusuku_runtime.

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "device_object.h"
#include "frame_pass.h"

namespace gusuku::runtime_detail {

class MaterialSets {
public:
    explicit MaterialSets(const PassContext& context);
    MaterialSets(const MaterialSets&) = delete;
    MaterialSets& operator=(const MaterialSets&) = delete;

    VkDescriptorSetLayout layout() const { return layout_.get(); }
    /// Binds `material`'s set at `set_index` of `pipeline_layout`.
    void bind(VkCommandBuffer cmd, VkPipelineLayout pipeline_layout, uint32_t set_index, uint32_t material) const {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, set_index, 1,
                                &sets_[material], 0, nullptr);
    }

private:
    Sampler sampler_;
    DescriptorSetLayout layout_;
    DescriptorPool pool_;           // its sets are freed with it
    std::vector<VkDescriptorSet> sets_;
};

}  // namespace gusuku::runtime_detail
