// Device limits lowered to a profile's or a named value (gusuku/gpu/device_limits.h).

#include "gusuku/gpu/device_limits.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <type_traits>

namespace gusuku {
namespace {

// How a clamp moves a limit: a maximum only down, an alignment or granularity only up (a coarser one is the
// stricter), sample-count flags to the bits both have.
enum class Direction { Lower, Raise, Flags };

// One limit: its name, where it lives, and its value in the Vulkan 1.0 specification's table of required limits
// (the smallest a conformant device may report) and in the Android Baseline 2022 profile
// (KhronosGroup/Vulkan-Profiles, profiles/VP_ANDROID_baseline_2022.json). Limits gusuku has no use for
// (tessellation, geometry, sparse, clip distances, timestamps) are left out.
struct LimitEntry {
    const char* name;
    Direction direction;
    double vulkan10;
    double android2022;
    double (*get)(const VkPhysicalDeviceLimits&);
    void (*set)(VkPhysicalDeviceLimits&, double);
};

#define GUSUKU_LIMIT(member, direction, vulkan10, android2022)                                                     \
    LimitEntry {                                                                                                    \
        #member, Direction::direction, double(vulkan10), double(android2022),                                       \
            [](const VkPhysicalDeviceLimits& l) { return double(l.member); },                                       \
            [](VkPhysicalDeviceLimits& l, double v) { l.member = static_cast<std::remove_reference_t<decltype(l.member)>>(v); }             \
    }

constexpr VkSampleCountFlags k1And4 = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT;

const std::vector<LimitEntry>& limitTable() {
    static const std::vector<LimitEntry> table = {
        GUSUKU_LIMIT(maxImageDimension1D, Lower, 4096, 16384),
        GUSUKU_LIMIT(maxImageDimension2D, Lower, 4096, 8192),
        GUSUKU_LIMIT(maxImageDimension3D, Lower, 256, 4096),
        GUSUKU_LIMIT(maxImageDimensionCube, Lower, 4096, 8192),
        GUSUKU_LIMIT(maxImageArrayLayers, Lower, 256, 256),
        GUSUKU_LIMIT(maxTexelBufferElements, Lower, 65536, 65536),
        GUSUKU_LIMIT(maxUniformBufferRange, Lower, 16384, 65536),
        GUSUKU_LIMIT(maxStorageBufferRange, Lower, 1u << 27, 1u << 28),
        GUSUKU_LIMIT(maxPushConstantsSize, Lower, 128, 128),
        GUSUKU_LIMIT(maxMemoryAllocationCount, Lower, 4096, 4294967295u),
        GUSUKU_LIMIT(maxSamplerAllocationCount, Lower, 4000, 16384),
        GUSUKU_LIMIT(bufferImageGranularity, Raise, 131072, 4096),
        GUSUKU_LIMIT(maxBoundDescriptorSets, Lower, 4, 4),
        GUSUKU_LIMIT(maxPerStageDescriptorSamplers, Lower, 16, 128),
        GUSUKU_LIMIT(maxPerStageDescriptorUniformBuffers, Lower, 12, 12),
        GUSUKU_LIMIT(maxPerStageDescriptorStorageBuffers, Lower, 4, 35),
        GUSUKU_LIMIT(maxPerStageDescriptorSampledImages, Lower, 16, 16),
        GUSUKU_LIMIT(maxPerStageDescriptorStorageImages, Lower, 4, 8),
        GUSUKU_LIMIT(maxPerStageDescriptorInputAttachments, Lower, 4, 4),
        GUSUKU_LIMIT(maxPerStageResources, Lower, 128, 79),
        GUSUKU_LIMIT(maxDescriptorSetSamplers, Lower, 96, 768),
        GUSUKU_LIMIT(maxDescriptorSetUniformBuffers, Lower, 72, 72),
        GUSUKU_LIMIT(maxDescriptorSetUniformBuffersDynamic, Lower, 8, 8),
        GUSUKU_LIMIT(maxDescriptorSetStorageBuffers, Lower, 24, 72),
        GUSUKU_LIMIT(maxDescriptorSetStorageBuffersDynamic, Lower, 4, 4),
        GUSUKU_LIMIT(maxDescriptorSetSampledImages, Lower, 96, 96),
        GUSUKU_LIMIT(maxDescriptorSetStorageImages, Lower, 24, 48),
        GUSUKU_LIMIT(maxDescriptorSetInputAttachments, Lower, 4, 4),
        GUSUKU_LIMIT(maxVertexInputAttributes, Lower, 16, 16),
        GUSUKU_LIMIT(maxVertexInputBindings, Lower, 16, 16),
        GUSUKU_LIMIT(maxVertexInputAttributeOffset, Lower, 2047, 2047),
        GUSUKU_LIMIT(maxVertexInputBindingStride, Lower, 2048, 2048),
        GUSUKU_LIMIT(maxVertexOutputComponents, Lower, 64, 128),
        GUSUKU_LIMIT(maxFragmentInputComponents, Lower, 64, 128),
        GUSUKU_LIMIT(maxFragmentOutputAttachments, Lower, 4, 4),
        GUSUKU_LIMIT(maxFragmentCombinedOutputResources, Lower, 4, 47),
        GUSUKU_LIMIT(maxComputeSharedMemorySize, Lower, 16384, 32768),
        GUSUKU_LIMIT(maxComputeWorkGroupCount[0], Lower, 65535, 65536),
        GUSUKU_LIMIT(maxComputeWorkGroupCount[1], Lower, 65535, 65536),
        GUSUKU_LIMIT(maxComputeWorkGroupCount[2], Lower, 65535, 65536),
        GUSUKU_LIMIT(maxComputeWorkGroupInvocations, Lower, 128, 128),
        GUSUKU_LIMIT(maxComputeWorkGroupSize[0], Lower, 128, 128),
        GUSUKU_LIMIT(maxComputeWorkGroupSize[1], Lower, 128, 128),
        GUSUKU_LIMIT(maxComputeWorkGroupSize[2], Lower, 64, 128),
        GUSUKU_LIMIT(maxDrawIndexedIndexValue, Lower, (1u << 24) - 1, 4294967295u),
        GUSUKU_LIMIT(maxDrawIndirectCount, Lower, 1, 1),
        GUSUKU_LIMIT(maxSamplerLodBias, Lower, 2, 15.9961),
        // 16 where the samplerAnisotropy feature is on; 1 is the floor of a device without it.
        GUSUKU_LIMIT(maxSamplerAnisotropy, Lower, 1, 1),
        GUSUKU_LIMIT(maxViewports, Lower, 1, 1),
        GUSUKU_LIMIT(maxViewportDimensions[0], Lower, 4096, 8192),
        GUSUKU_LIMIT(maxViewportDimensions[1], Lower, 4096, 8192),
        GUSUKU_LIMIT(minTexelBufferOffsetAlignment, Raise, 256, 256),
        GUSUKU_LIMIT(minUniformBufferOffsetAlignment, Raise, 256, 64),
        GUSUKU_LIMIT(minStorageBufferOffsetAlignment, Raise, 256, 256),
        GUSUKU_LIMIT(maxFramebufferWidth, Lower, 4096, 8192),
        GUSUKU_LIMIT(maxFramebufferHeight, Lower, 4096, 8192),
        GUSUKU_LIMIT(maxFramebufferLayers, Lower, 256, 256),
        GUSUKU_LIMIT(framebufferColorSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(framebufferDepthSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(framebufferStencilSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(framebufferNoAttachmentsSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(maxColorAttachments, Lower, 4, 4),
        GUSUKU_LIMIT(sampledImageColorSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(sampledImageIntegerSampleCounts, Flags, VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_1_BIT),
        GUSUKU_LIMIT(sampledImageDepthSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(sampledImageStencilSampleCounts, Flags, k1And4, k1And4),
        GUSUKU_LIMIT(storageImageSampleCounts, Flags, VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_1_BIT),
        GUSUKU_LIMIT(maxSampleMaskWords, Lower, 1, 1),
        GUSUKU_LIMIT(nonCoherentAtomSize, Raise, 256, 64),
    };
    return table;
}

#undef GUSUKU_LIMIT

const LimitEntry& entryNamed(const std::string& name) {
    for (const LimitEntry& entry : limitTable())
        if (name == entry.name) return entry;
    throw std::invalid_argument("GUSUKU_CLAMP_LIMITS: " + name +
                                ": not a limit gusuku can clamp (gusuku/gpu/device_limits.h lists them)");
}

void clampOne(VkPhysicalDeviceLimits& limits, const LimitEntry& entry, double value) {
    const double device = entry.get(limits);
    switch (entry.direction) {
        case Direction::Lower: entry.set(limits, std::min(device, value)); break;
        case Direction::Raise: entry.set(limits, std::max(device, value)); break;
        case Direction::Flags: entry.set(limits, double(uint32_t(device) & uint32_t(value))); break;
    }
}

}  // namespace

void clampDeviceLimits(VkPhysicalDeviceLimits& limits, const std::string& clamp) {
    size_t start = 0;
    while (start < clamp.size()) {
        size_t end = clamp.find(',', start);
        if (end == std::string::npos) end = clamp.size();
        const std::string item = clamp.substr(start, end - start);
        start = end + 1;
        if (item.empty()) continue;
        if (item == "vulkan10" || item == "android2022") {
            for (const LimitEntry& entry : limitTable())
                clampOne(limits, entry, item == "vulkan10" ? entry.vulkan10 : entry.android2022);
            continue;
        }
        const size_t equals = item.find('=');
        if (equals == std::string::npos)
            throw std::invalid_argument("GUSUKU_CLAMP_LIMITS: " + item +
                                        ": not vulkan10, android2022 or NAME=VALUE");
        const LimitEntry& entry = entryNamed(item.substr(0, equals));
        const std::string text = item.substr(equals + 1);
        char* parsed_end = nullptr;
        const double value = std::strtod(text.c_str(), &parsed_end);
        if (text.empty() || parsed_end == nullptr || *parsed_end != '\0' || !(value >= 0.0))
            throw std::invalid_argument("GUSUKU_CLAMP_LIMITS: " + item + ": the value is not a number >= 0");
        clampOne(limits, entry, value);
    }
}

void clampDeviceLimitsFromEnvironment(VkPhysicalDeviceLimits& limits) {
    if (const char* clamp = std::getenv("GUSUKU_CLAMP_LIMITS")) clampDeviceLimits(limits, clamp);
}

std::vector<std::string> deviceLimitNames() {
    std::vector<std::string> names;
    for (const LimitEntry& entry : limitTable()) names.push_back(entry.name);
    return names;
}

double deviceLimitValue(const VkPhysicalDeviceLimits& limits, const std::string& name) {
    return entryNamed(name).get(limits);
}

}  // namespace gusuku
