// The runtime's device requirements (device_requirements.h).

#include "device_requirements.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "camera_input.h"
#include "camera_interface.h"
#include "colour_match_interface.h"
#include "colour_statistics_pass.h"
#include "gusuku/gpu/device_limits.h"
#include "runtime_depth_push.h"
#include "runtime_interface.h"
#include "runtime_masked_depth_push.h"
#include "runtime_material_push.h"
#include "runtime_pipelines.h"
#include "runtime_scene.h"

namespace gusuku::runtime_detail {
namespace {

struct FormatNeed {
    VkFormat format;
    VkFormatFeatureFlags features;
    const char* name;
    const char* use;
};

std::string missingFeatures(VkFormatFeatureFlags missing) {
    std::string names;
    auto add = [&](VkFormatFeatureFlags bit, const char* name) {
        if (missing & bit) names += std::string(names.empty() ? "" : ", ") + name;
    };
    add(VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT, "SAMPLED_IMAGE");
    add(VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT, "SAMPLED_IMAGE_FILTER_LINEAR");
    add(VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "COLOR_ATTACHMENT");
    add(VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT, "COLOR_ATTACHMENT_BLEND");
    add(VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT, "DEPTH_STENCIL_ATTACHMENT");
    add(VK_FORMAT_FEATURE_TRANSFER_SRC_BIT, "TRANSFER_SRC");
    add(VK_FORMAT_FEATURE_TRANSFER_DST_BIT, "TRANSFER_DST");
    return names;
}

std::string hexadecimal(uint32_t value) {
    char text[16];
    std::snprintf(text, sizeof text, "%x", value);
    return text;
}

std::string mebibytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    return text;
}

// What the runtime's fixed parts need of the device's limits, each the most any of its pipelines uses. All are
// within Vulkan 1.0's required minimum (device_limits.h's vulkan10 column; test_device_limits pins both), so a
// conformant device always has them; they are checked anyway, by the name a limit has in
// VkPhysicalDeviceLimits, so a device or a clamp below them is refused by name rather than by a failed call.
struct LimitNeed {
    const char* limit;  // as deviceLimitValue names it
    double needed;
    const char* use;
};

// The frame set's combined image samplers: its bindings but the uniform block and the colour-match state.
constexpr uint32_t kFrameSetSamplers = RUNTIME_FRAME_BINDING_COUNT - 2;
constexpr uint32_t kFragmentSamplers = kFrameSetSamplers + 1;  // and the material's base colour (set 1)
constexpr uint32_t kLargestPushConstants =
    uint32_t(std::max({sizeof(shader_interface::MaterialPushConstants), sizeof(shader_interface::DepthOnlyPushConstants),
                       sizeof(shader_interface::MaskedDepthPushConstants), sizeof(shader_interface::CameraPushConstants)}));
static_assert(kLargestPushConstants <= 128, "Vulkan 1.0 promises 128 bytes of push constants, no more");

const LimitNeed kFixedNeeds[] = {
    {"maxBoundDescriptorSets", RUNTIME_MATERIAL_SET + 1, "the frame's descriptor set and the material's"},
    {"maxPerStageDescriptorSamplers", kFragmentSamplers,
     "the building's fragment shader: two shadow maps, the shadow depths, the lightmaps, the ground's two "
     "images, the sun horizons and the base colour"},
    {"maxPerStageDescriptorSampledImages", kFragmentSamplers, "the building's fragment shader (as above)"},
    {"maxDescriptorSetSamplers", kFragmentSamplers, "the building's pipeline layout"},
    {"maxDescriptorSetSampledImages", kFragmentSamplers, "the building's pipeline layout"},
    {"maxPerStageDescriptorUniformBuffers", 1, "the frame's uniform block"},
    {"maxDescriptorSetUniformBuffers", 1, "the frame's uniform block"},
    {"maxUniformBufferRange", sizeof(shader_interface::FrameUniforms), "the frame's uniform block (FrameUniforms)"},
    {"maxPerStageDescriptorStorageBuffers", 1, "the colour match state read by the fragment shaders"},
    {"maxPerStageResources", kFragmentSamplers + 3,
     "the building's fragment shader: its samplers, the uniform block, the colour state and the composite"},
    {"maxFragmentCombinedOutputResources", 2, "the composite and the colour state"},
    {"maxPushConstantsSize", kLargestPushConstants, "the largest of the raster passes' push constants"},
    {"maxVertexInputAttributes", 4, "the building's vertex: position, normal and two texture coordinates"},
    {"maxVertexInputBindingStride", sizeof(BuildingVertex), "the building's vertex (BuildingVertex)"},
    {"maxComputeWorkGroupInvocations", CAMERA_PACK_WORKGROUP * CAMERA_PACK_WORKGROUP,
     "the camera pack's 8 x 8 tiles"},
    {"maxComputeWorkGroupSize[0]", CAMERA_PACK_WORKGROUP, "the camera pack's tiles"},
    {"maxComputeWorkGroupSize[1]", CAMERA_PACK_WORKGROUP, "the camera pack's tiles"},
};

void checkFixedNeeds(const GpuDevice& gpu) {
    for (const LimitNeed& need : kFixedNeeds) {
        const double have = deviceLimitValue(gpu.limits(), need.limit);
        if (have < need.needed)
            throw RuntimeError(RuntimeErrorCode::kDevice,
                               std::string("gusuku runtime: the device's ") + need.limit + " is " +
                                   std::to_string(uint64_t(have)) + ", below the " +
                                   std::to_string(uint64_t(need.needed)) + " that " + need.use +
                                   " need; Vulkan 1.0 promises at least that much, so the device (or a "
                                   "GUSUKU_CLAMP_LIMITS clamp) is below the specification");
    }
}

/// The frame's size against the device's limits on what each frame-sized resource needs, so a frame inside the
/// options' [1, 8192] that this device cannot hold is refused naming the options, not by the resource that fails.
void checkFrameSizeLimits(const GpuDevice& gpu, const RuntimeOptions& options) {
    const VkPhysicalDeviceLimits& limits = gpu.limits();
    const std::string size = std::to_string(options.frame_width) + " x " + std::to_string(options.frame_height);
    const std::string device = std::string("this device's (") + gpu.properties.deviceName + ") ";
    auto fail = [&](const std::string& what) {
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           "options.frame_width/height: " + size + " " + what + ": choose a smaller frame");
    };
    const uint32_t side = std::max(options.frame_width, options.frame_height);
    if (side > limits.maxImageDimension2D)
        fail("is larger than " + device + "maxImageDimension2D of " + std::to_string(limits.maxImageDimension2D));
    if (options.frame_width > limits.maxFramebufferWidth || options.frame_height > limits.maxFramebufferHeight)
        fail("is larger than " + device + "maxFramebufferWidth/Height of " +
             std::to_string(limits.maxFramebufferWidth) + " x " + std::to_string(limits.maxFramebufferHeight));
    if (options.frame_width > limits.maxViewportDimensions[0] || options.frame_height > limits.maxViewportDimensions[1])
        fail("is larger than " + device + "maxViewportDimensions of " + std::to_string(limits.maxViewportDimensions[0]) +
             " x " + std::to_string(limits.maxViewportDimensions[1]));
    // The colour statistics and the camera pack run a workgroup per 8 x 8 pixels at most.
    const uint64_t groups_x = (uint64_t(options.frame_width) + CAMERA_PACK_WORKGROUP - 1) / CAMERA_PACK_WORKGROUP;
    const uint64_t groups_y = (uint64_t(options.frame_height) + CAMERA_PACK_WORKGROUP - 1) / CAMERA_PACK_WORKGROUP;
    if (groups_x > limits.maxComputeWorkGroupCount[0] || groups_y > limits.maxComputeWorkGroupCount[1])
        fail("needs " + std::to_string(groups_x) + " x " + std::to_string(groups_y) +
             " workgroups of the camera pack, beyond " + device + "maxComputeWorkGroupCount of " +
             std::to_string(limits.maxComputeWorkGroupCount[0]) + " x " +
             std::to_string(limits.maxComputeWorkGroupCount[1]));
    // The shadow maps are depth attachments of shadow_map_size squared, drawn through a viewport of that size.
    const uint32_t shadow = options.shadow_map_size;
    const uint32_t shadow_limit = std::min({limits.maxImageDimension2D, limits.maxFramebufferWidth,
                                            limits.maxFramebufferHeight, limits.maxViewportDimensions[0],
                                            limits.maxViewportDimensions[1]});
    if (shadow > shadow_limit)
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           "options.shadow_map_size: " + std::to_string(shadow) + " is larger than " + device +
                               "maxImageDimension2D, maxFramebufferWidth/Height and maxViewportDimensions allow (" +
                               std::to_string(shadow_limit) + "): choose a smaller shadow map");
    // The colour statistics read the camera as one frame-sized storage buffer of RGBA8 words (camera_pack.comp).
    const uint64_t packed_bytes = uint64_t(options.frame_width) * options.frame_height * 4;
    if (ColourStatisticsPass::deviceSupports(gpu) && packed_bytes > limits.maxStorageBufferRange)
        fail("needs a " + mebibytes(packed_bytes) + " storage buffer for the colour statistics' camera copy (4 "
             "bytes a pixel), beyond " + device + "maxStorageBufferRange of " +
             mebibytes(limits.maxStorageBufferRange) + " (" + std::to_string(limits.maxStorageBufferRange / 4) +
             " pixels)");
}

}  // namespace

void checkDeviceRequirements(const GpuDevice& gpu, const RuntimeOptions& options) {
    auto fail = [](const std::string& what) {
        throw RuntimeError(RuntimeErrorCode::kDevice, "gusuku runtime: the device " + what);
    };
    // Vulkan 1.0 is enough for the frame; the colour matches' subgroups (1.1) are checked by their pass, and a
    // device without them opens with the matches off (ColourStatisticsPass::deviceSupports).
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(gpu.physical_device, &family_count, families.data());
    const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (gpu.queue_family_index >= family_count || (families[gpu.queue_family_index].queueFlags & needed) != needed)
        fail("queue family " + std::to_string(gpu.queue_family_index) + " lacks graphics and compute");

    // The main pass's attachments at msaa_samples (a count checkRuntimeOptions allowed: one bit of the flags).
    const VkSampleCountFlags samples = VkSampleCountFlags(options.msaa_samples);
    const VkPhysicalDeviceLimits& limits = gpu.limits();
    if ((limits.framebufferColorSampleCounts & samples) == 0 || (limits.framebufferDepthSampleCounts & samples) == 0)
        fail("cannot draw options.msaa_samples = " + std::to_string(options.msaa_samples) +
             " samples a pixel (framebufferColorSampleCounts 0x" + hexadecimal(limits.framebufferColorSampleCounts) +
             ", framebufferDepthSampleCounts 0x" + hexadecimal(limits.framebufferDepthSampleCounts) +
             "): choose a count both include, or 1");

    checkFixedNeeds(gpu);
    checkFrameSizeLimits(gpu, options);

    const CameraPlaneFormats camera = cameraPlaneFormats(options.camera_format);
    const VkFormatFeatureFlags sampled = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    std::vector<FormatNeed> needs = {
        {kColourFormat,
         VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
             VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT,
         "R8G8B8A8_SRGB", "the composite"},
        {kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT,
         "D32_SFLOAT", "depth and the shadow maps"},
        {VK_FORMAT_R16G16B16A16_SFLOAT, sampled | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
         "R16G16B16A16_SFLOAT", "the ground's irradiance"},
        {lightmapVkFormat(options.lightmap_format), sampled | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT,
         lightmapFormatName(options.lightmap_format), "the lightmaps (options.lightmap_format)"},
    };
    if (options.camera_ycbcr_image) {
        checkYcbcrCameraSupport(gpu, options);  // the app's images, no planes of the runtime's
    } else {
        needs.push_back({camera.plane0, sampled, "the camera's first plane format", "the camera"});
        if (camera.plane1 != VK_FORMAT_UNDEFINED)
            needs.push_back({camera.plane1, sampled, "R8G8_UNORM", "the camera's chroma"});
    }
    if (mainDepthStencilFormat(gpu.physical_device) == VK_FORMAT_UNDEFINED)
        fail("lacks DEPTH_STENCIL_ATTACHMENT for both D32_SFLOAT_S8_UINT and D24_UNORM_S8_UINT (the main pass's "
             "depth and the building's stencil marks)");
    for (const FormatNeed& need : needs) {
        VkFormatProperties properties{};
        vkGetPhysicalDeviceFormatProperties(gpu.physical_device, need.format, &properties);
        const VkFormatFeatureFlags missing = need.features & ~properties.optimalTilingFeatures;
        if (missing != 0)
            fail("lacks " + missingFeatures(missing) + " for " + need.name + " (VkFormat " +
                 std::to_string(int(need.format)) + ", " + need.use + ")");
    }
}

void checkBakeSetLimits(const GpuDevice& gpu, const BakeSetData& bake_set) {
    const VkPhysicalDeviceLimits& limits = gpu.limits();
    const std::string device = std::string("this device's (") + gpu.properties.deviceName + ") ";
    auto fail = [&](const std::string& field, const std::string& what) {
        throw RuntimeError(RuntimeErrorCode::kDevice, "bake set: " + field + ": " + what);
    };
    const uint32_t side = limits.maxImageDimension2D;
    const uint32_t lightmap = uint32_t(std::max(bake_set.manifest.building.lightmap_resolution, 0));
    if (lightmap > side)
        fail("building.lightmap_resolution", std::to_string(lightmap) + " is larger than " + device +
                                                 "maxImageDimension2D of " + std::to_string(side) +
                                                 ": bake with a smaller lightmap (site.json bake.texels_per_metre)");
    // The lightmaps are one array layer per slot; the ground's terms two layers per slot.
    const uint32_t ground_layers = uint32_t(2 * bake_set.slots.size());
    if (ground_layers > limits.maxImageArrayLayers)
        fail("slots", std::to_string(bake_set.slots.size()) + " slots need " + std::to_string(ground_layers) +
                          " array layers for the ground's terms, beyond " + device + "maxImageArrayLayers of " +
                          std::to_string(limits.maxImageArrayLayers) + ": bake fewer slots");
    const uint32_t columns = uint32_t(std::max(bake_set.ground_geometry.width, 0));
    const uint32_t rows = uint32_t(std::max(bake_set.ground_geometry.height, 0));
    if (std::max(columns, rows) > side)
        fail("ground_grid", std::to_string(columns) + " x " + std::to_string(rows) + " cells are more than " +
                                device + "maxImageDimension2D of " + std::to_string(side) +
                                " a side: bake a smaller ground region or larger cells (site.json ground)");
    for (size_t index = 0; index < bake_set.building.textures.size(); ++index) {
        const BakeSetTexture& texture = bake_set.building.textures[index];
        if (uint32_t(std::max({texture.width, texture.height, 0})) > side)
            fail("building.textures[" + std::to_string(index) + "]",
                 std::to_string(texture.width) + " x " + std::to_string(texture.height) + " is larger than " +
                     device + "maxImageDimension2D of " + std::to_string(side) +
                     ": bake with gusuku-bake bake --texture-size " + std::to_string(side) + " or less");
    }
    // 32-bit indices: the largest vertex index drawn must be within maxDrawIndexedIndexValue (2^24 - 1 without
    // the fullDrawIndexUint32 feature).
    const uint64_t vertices = bake_set.building.positions.size();
    if (vertices > 0 && vertices - 1 > limits.maxDrawIndexedIndexValue)
        fail("building", std::to_string(vertices) + " vertices, more than " + device +
                             "maxDrawIndexedIndexValue of " + std::to_string(limits.maxDrawIndexedIndexValue) +
                             " lets one indexed draw reach: simplify the building");
}

}  // namespace gusuku::runtime_detail
