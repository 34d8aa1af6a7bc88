#pragma once
// The runtime's Vulkan plumbing that is not per frame: render passes, descriptor layouts, graphics pipelines.
// Private to gusuku_runtime.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

namespace gusuku::runtime_detail {

constexpr VkFormat kColourFormat = VK_FORMAT_R8G8B8A8_SRGB;  // the composite: sRGB bytes, blending in linear
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;  // the shadow maps

/// The main pass's depth-stencil format: D32_SFLOAT_S8_UINT, else D24_UNORM_S8_UINT (Vulkan guarantees one of
/// them as a depth-stencil attachment); VK_FORMAT_UNDEFINED when the device has neither (the runtime refuses it).
/// The stencil marks the building's pixels so the ground ratio never multiplies them (see StencilUse).
VkFormat mainDepthStencilFormat(VkPhysicalDevice physical_device);

/// The stencil in the main pass. The ground pass is pulled 10 cm towards the camera so that the site's occluder
/// mesh it was sampled from cannot hide it; that also puts it in front of the building's lowest 10 cm wherever
/// the building meets the ground (a 2 cm platform's whole front face), where its ratio darkened building
/// pixels: a dark rim. The building marks the pixels it draws; the ground skips them.
enum class StencilUse {
    kNone,
    kMarkBuilding,  ///< where the fragment passes the depth test, stencil = 1
    kSkipBuilding,  ///< draw only where stencil = 0
};

/// The main pass's attachments: colour (the camera-in draw writes it first) and depth, at `samples` a pixel.
/// With one sample the colour is the composite. With more, both are multisampled (multisample_target.h) and a
/// third attachment, the composite, receives the colour's resolve at the frame's end (kWhole, kLast); the
/// variants before it keep the multisampled colour and depth for the next and leave the composite alone. The
/// variants differ only in load and store operations, layouts and (single-subpass passes, where Vulkan's
/// compatibility ignores it) the resolve, so they are compatible and share pipelines and framebuffers.
/// `whole` = one pass for the whole frame; `first`, `middle`, `last` split it for the profiling mode.
enum class MainPassVariant { kWhole, kFirst, kMiddle, kLast };
VkRenderPass createMainRenderPass(VkDevice device, MainPassVariant variant, VkSampleCountFlagBits samples,
                                  VkFormat depth_stencil_format);
/// A depth-only pass into a shadow map, left in SHADER_READ_ONLY_OPTIMAL for sampling.
VkRenderPass createShadowRenderPass(VkDevice device);

enum class BlendMode {
    kOpaque,           ///< write the fragment's colour
    kMultiplyTwice,    ///< destination x source x 2 in colour (the ground ratio), destination alpha kept
    kNoColourWrites,   ///< depth only inside a pass that has a colour attachment
};

struct VertexInput {
    uint32_t stride = 0;                                      ///< 0: no vertex buffer
    std::vector<VkVertexInputAttributeDescription> attributes;
};

struct GraphicsPipelineDescription {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    const uint32_t* vertex_spirv = nullptr;
    size_t vertex_spirv_bytes = 0;
    const uint32_t* fragment_spirv = nullptr;  ///< null: no fragment stage (depth only)
    size_t fragment_spirv_bytes = 0;
    const VkSpecializationInfo* fragment_specialization = nullptr;  ///< constant_id values of the fragment stage
    VertexInput vertex_input;
    bool depth_test = true;
    bool depth_write = true;
    VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
    StencilUse stencil = StencilUse::kNone;
    BlendMode blend = BlendMode::kOpaque;
    bool has_colour_attachment = true;
    /// rasterizationSamples: the render pass's sample count (RuntimeOptions::msaa_samples in the main pass).
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    /// alphaToCoverageEnable: the fragment's output alpha sets how many of its samples it covers (alpha-masked
    /// materials with multisampling; the colour attachment's alpha is then not written, colorWriteMask RGB).
    bool alpha_to_coverage = false;
};

/// A graphics pipeline with dynamic viewport and scissor; triangle lists, no culling (thin walls and
/// photogrammetry shells are seen from both sides). Throws std::runtime_error on failure.
VkPipeline createGraphicsPipeline(VkDevice device, const GraphicsPipelineDescription& description);

/// A framebuffer over the given views, width x height.
VkFramebuffer createFramebuffer(VkDevice device, VkRenderPass render_pass, const std::vector<VkImageView>& views,
                                uint32_t width, uint32_t height);

/// Sets the dynamic viewport and scissor to the whole width x height.
void recordViewport(VkCommandBuffer cmd, uint32_t width, uint32_t height);

}  // namespace gusuku::runtime_detail
