// The runtime's device requirements (device_requirements.h).

#include "device_requirements.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "camera_input.h"
#include "colour_statistics_pass.h"
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
        {camera.plane0, sampled, "the camera's first plane format", "the camera"},
    };
    if (camera.plane1 != VK_FORMAT_UNDEFINED) needs.push_back({camera.plane1, sampled, "R8G8_UNORM", "the camera's chroma"});
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

}  // namespace gusuku::runtime_detail
