// The limits clamp (gusuku/gpu/device_limits.h) against the figures it was written from: the Vulkan 1.0
// specification's table of required limits and the Android Baseline 2022 profile (KhronosGroup/Vulkan-Profiles,
// profiles/VP_ANDROID_baseline_2022.json), pinned here by hand so a typo in the table shows; a clamp lowers and
// never raises; the environment reaches GpuDevice::describe; bad clamps are refused by name.
#include <cstdlib>
#include <algorithm>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/device_limits.h"
#include "gusuku/gpu/gpu_device.h"

namespace gusuku {
namespace {

// A device above every profile: each maximum huge, each alignment 1, every sample count.
VkPhysicalDeviceLimits generousLimits() {
    VkPhysicalDeviceLimits limits{};
    limits.maxImageDimension1D = limits.maxImageDimension2D = limits.maxImageDimension3D = 1u << 30;
    limits.maxImageDimensionCube = limits.maxImageArrayLayers = limits.maxTexelBufferElements = 1u << 30;
    limits.maxUniformBufferRange = limits.maxStorageBufferRange = 0xffffffffu;
    limits.maxPushConstantsSize = 4096;
    limits.maxMemoryAllocationCount = limits.maxSamplerAllocationCount = 0xffffffffu;
    limits.bufferImageGranularity = 1;
    limits.maxBoundDescriptorSets = 32;
    limits.maxPerStageDescriptorSamplers = limits.maxPerStageDescriptorUniformBuffers = 1u << 20;
    limits.maxPerStageDescriptorStorageBuffers = limits.maxPerStageDescriptorSampledImages = 1u << 20;
    limits.maxPerStageDescriptorStorageImages = limits.maxPerStageDescriptorInputAttachments = 1u << 20;
    limits.maxPerStageResources = limits.maxDescriptorSetSamplers = limits.maxDescriptorSetUniformBuffers = 1u << 20;
    limits.maxDescriptorSetUniformBuffersDynamic = limits.maxDescriptorSetStorageBuffers = 1u << 20;
    limits.maxDescriptorSetStorageBuffersDynamic = limits.maxDescriptorSetSampledImages = 1u << 20;
    limits.maxDescriptorSetStorageImages = limits.maxDescriptorSetInputAttachments = 1u << 20;
    limits.maxVertexInputAttributes = limits.maxVertexInputBindings = 64;
    limits.maxVertexInputAttributeOffset = limits.maxVertexInputBindingStride = 1u << 20;
    limits.maxVertexOutputComponents = limits.maxFragmentInputComponents = 256;
    limits.maxFragmentOutputAttachments = limits.maxFragmentCombinedOutputResources = 1u << 20;
    limits.maxComputeSharedMemorySize = 1u << 20;
    for (int axis = 0; axis < 3; ++axis) {
        limits.maxComputeWorkGroupCount[axis] = 0xffffffffu;
        limits.maxComputeWorkGroupSize[axis] = 1024;
    }
    limits.maxComputeWorkGroupInvocations = 1024;
    limits.maxDrawIndexedIndexValue = limits.maxDrawIndirectCount = 0xffffffffu;
    limits.maxSamplerLodBias = 16.0f;
    limits.maxSamplerAnisotropy = 16.0f;
    limits.maxViewports = 16;
    limits.maxViewportDimensions[0] = limits.maxViewportDimensions[1] = 1u << 20;
    limits.minTexelBufferOffsetAlignment = limits.minUniformBufferOffsetAlignment = 1;
    limits.minStorageBufferOffsetAlignment = limits.nonCoherentAtomSize = 1;
    limits.maxFramebufferWidth = limits.maxFramebufferHeight = limits.maxFramebufferLayers = 1u << 20;
    const VkSampleCountFlags every = 0x7f;
    limits.framebufferColorSampleCounts = limits.framebufferDepthSampleCounts = every;
    limits.framebufferStencilSampleCounts = limits.framebufferNoAttachmentsSampleCounts = every;
    limits.sampledImageColorSampleCounts = limits.sampledImageIntegerSampleCounts = every;
    limits.sampledImageDepthSampleCounts = limits.sampledImageStencilSampleCounts = every;
    limits.storageImageSampleCounts = every;
    limits.maxColorAttachments = 8;
    limits.maxSampleMaskWords = 4;
    return limits;
}

TEST(DeviceLimits, Vulkan10GivesTheSpecificationsRequiredMinimum) {
    VkPhysicalDeviceLimits limits = generousLimits();
    clampDeviceLimits(limits, "vulkan10");
    // Vulkan 1.0 specification, "Required Limits".
    EXPECT_EQ(limits.maxImageDimension2D, 4096u);
    EXPECT_EQ(limits.maxImageArrayLayers, 256u);
    EXPECT_EQ(limits.maxTexelBufferElements, 65536u);
    EXPECT_EQ(limits.maxUniformBufferRange, 16384u);
    EXPECT_EQ(limits.maxStorageBufferRange, 134217728u);
    EXPECT_EQ(limits.maxPushConstantsSize, 128u);
    EXPECT_EQ(limits.maxBoundDescriptorSets, 4u);
    EXPECT_EQ(limits.maxPerStageDescriptorSamplers, 16u);
    EXPECT_EQ(limits.maxPerStageDescriptorStorageBuffers, 4u);
    EXPECT_EQ(limits.maxPerStageDescriptorSampledImages, 16u);
    EXPECT_EQ(limits.maxPerStageResources, 128u);
    EXPECT_EQ(limits.maxDescriptorSetStorageBuffers, 24u);
    EXPECT_EQ(limits.maxFragmentCombinedOutputResources, 4u);
    EXPECT_EQ(limits.maxComputeSharedMemorySize, 16384u);
    EXPECT_EQ(limits.maxComputeWorkGroupCount[0], 65535u);
    EXPECT_EQ(limits.maxComputeWorkGroupInvocations, 128u);
    EXPECT_EQ(limits.maxComputeWorkGroupSize[2], 64u);
    EXPECT_EQ(limits.maxDrawIndexedIndexValue, (1u << 24) - 1);
    EXPECT_EQ(limits.maxSamplerLodBias, 2.0f);
    EXPECT_EQ(limits.maxViewportDimensions[0], 4096u);
    EXPECT_EQ(limits.maxFramebufferWidth, 4096u);
    EXPECT_EQ(limits.framebufferColorSampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT));
    EXPECT_EQ(limits.storageImageSampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
    EXPECT_EQ(limits.minStorageBufferOffsetAlignment, 256u);
    EXPECT_EQ(limits.bufferImageGranularity, 131072u);
}

TEST(DeviceLimits, Android2022GivesTheProfilesValues) {
    VkPhysicalDeviceLimits limits = generousLimits();
    clampDeviceLimits(limits, "android2022");
    // VP_ANDROID_baseline_2022.json's VkPhysicalDeviceLimits.
    EXPECT_EQ(limits.maxImageDimension2D, 8192u);
    EXPECT_EQ(limits.maxTexelBufferElements, 65536u);
    EXPECT_EQ(limits.maxUniformBufferRange, 65536u);
    EXPECT_EQ(limits.maxStorageBufferRange, 268435456u);
    EXPECT_EQ(limits.maxPerStageDescriptorSamplers, 128u);
    EXPECT_EQ(limits.maxPerStageDescriptorStorageBuffers, 35u);
    EXPECT_EQ(limits.maxPerStageResources, 79u);
    EXPECT_EQ(limits.maxComputeSharedMemorySize, 32768u);
    EXPECT_EQ(limits.maxComputeWorkGroupCount[0], 65536u);
    EXPECT_EQ(limits.maxComputeWorkGroupSize[2], 128u);
    EXPECT_EQ(limits.maxSamplerAnisotropy, 1.0f);
    EXPECT_EQ(limits.maxFramebufferWidth, 8192u);
    EXPECT_EQ(limits.minUniformBufferOffsetAlignment, 64u);
    EXPECT_EQ(limits.nonCoherentAtomSize, 64u);
}

TEST(DeviceLimits, AClampLowersAndNeverRaises) {
    VkPhysicalDeviceLimits limits{};
    limits.maxImageDimension2D = 1000;       // below both profiles
    limits.minStorageBufferOffsetAlignment = 1024;  // coarser than both
    limits.framebufferColorSampleCounts = VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_8_BIT;
    clampDeviceLimits(limits, "vulkan10");
    EXPECT_EQ(limits.maxImageDimension2D, 1000u);
    EXPECT_EQ(limits.minStorageBufferOffsetAlignment, 1024u);
    EXPECT_EQ(limits.framebufferColorSampleCounts, VkSampleCountFlags(VK_SAMPLE_COUNT_1_BIT));
    clampDeviceLimits(limits, "maxImageDimension2D=5000,maxImageDimension2D=640");
    EXPECT_EQ(limits.maxImageDimension2D, 640u);
    EXPECT_EQ(deviceLimitValue(limits, "maxImageDimension2D"), 640.0);
}

TEST(DeviceLimits, BadClampsAreRefusedByName) {
    VkPhysicalDeviceLimits limits = generousLimits();
    auto message = [&](const std::string& clamp) {
        try {
            clampDeviceLimits(limits, clamp);
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message("vulkan11"), "GUSUKU_CLAMP_LIMITS: vulkan11: not vulkan10, android2022 or NAME=VALUE");
    EXPECT_EQ(message("maxWidgets=3"),
              "GUSUKU_CLAMP_LIMITS: maxWidgets: not a limit gusuku can clamp (gusuku/gpu/device_limits.h lists them)");
    EXPECT_EQ(message("maxImageDimension2D=big"),
              "GUSUKU_CLAMP_LIMITS: maxImageDimension2D=big: the value is not a number >= 0");
    EXPECT_EQ(message("maxImageDimension2D="),
              "GUSUKU_CLAMP_LIMITS: maxImageDimension2D=: the value is not a number >= 0");
    EXPECT_EQ(message(""), "accepted");
}

class DeviceLimitsOnDevice : public testing::GpuTest {};

TEST_F(DeviceLimitsOnDevice, DescribeAppliesTheEnvironmentsClamp) {
    const VulkanContext& vulkan = context();
    ASSERT_EQ(setenv("GUSUKU_CLAMP_LIMITS", "vulkan10,maxTexelBufferElements=1000", 1), 0);
    const GpuDevice clamped = GpuDevice::describe(vulkan.instance(), vulkan.physicalDevice(), vulkan.device(),
                                                  vulkan.queue(), vulkan.queueFamily());
    ASSERT_EQ(setenv("GUSUKU_CLAMP_LIMITS", "vulkan11", 1), 0);
    EXPECT_THROW(GpuDevice::describe(vulkan.instance(), vulkan.physicalDevice(), vulkan.device(), vulkan.queue(),
                                     vulkan.queueFamily()),
                 std::invalid_argument);
    ASSERT_EQ(unsetenv("GUSUKU_CLAMP_LIMITS"), 0);
    const GpuDevice plain = GpuDevice::describe(vulkan.instance(), vulkan.physicalDevice(), vulkan.device(),
                                                vulkan.queue(), vulkan.queueFamily());
    EXPECT_EQ(clamped.limits().maxTexelBufferElements, std::min(1000u, plain.limits().maxTexelBufferElements));
    EXPECT_EQ(clamped.limits().maxStorageBufferRange, std::min(134217728u, plain.limits().maxStorageBufferRange));
    EXPECT_EQ(plain.limits().maxTexelBufferElements, vulkan.gpu().limits().maxTexelBufferElements);
}

}  // namespace
}  // namespace gusuku
