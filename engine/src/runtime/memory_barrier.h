#pragma once
// One global memory barrier, for the runtime's compute passes that order their own buffers' writes against later
// reads (the colour statistics and the sun evidence): a VkMemoryBarrier covers every buffer at once, which is all
// these passes need and cheaper to record than a barrier per buffer.

#include <vulkan/vulkan.h>

namespace gusuku::runtime_detail {

inline void recordMemoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags source_stages, VkAccessFlags source_access,
                                VkPipelineStageFlags destination_stages, VkAccessFlags destination_access) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = source_access;
    barrier.dstAccessMask = destination_access;
    vkCmdPipelineBarrier(cmd, source_stages, destination_stages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace gusuku::runtime_detail
