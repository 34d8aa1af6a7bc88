#pragma once
// Device limits lowered on purpose, so the code that reads them can be run at a smaller device's figures on this
// one. Every limit gusuku reads comes from GpuDevice::limits() (GpuDevice::describe fills it, VulkanContext's
// properties() copies it), and describe applies the clamp named by GUSUKU_CLAMP_LIMITS:
//   vulkan10      the Vulkan 1.0 specification's required minimum of each limit (maxima lowered, minima raised)
//   android2022   the Android Baseline 2022 profile's values (VP_ANDROID_baseline_2022, Vulkan-Profiles)
//   NAME=VALUE[,NAME=VALUE...]  single limits by their VkPhysicalDeviceLimits name (listed by deviceLimitNames)
// or a profile followed by single limits ("vulkan10,maxPerStageDescriptorStorageBuffers=16"). A clamp only
// ever lowers what the device offers (or raises an alignment): it cannot promise more than the device has.
// The Vulkan validation layer checks against the device's real limits, not the clamped ones.

#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace gusuku {

/// Lowers `limits` to `clamp` (the syntax above; empty: unchanged). Throws std::invalid_argument
/// "GUSUKU_CLAMP_LIMITS: ..." naming an unknown profile or limit, or a value that is not a number.
void clampDeviceLimits(VkPhysicalDeviceLimits& limits, const std::string& clamp);

/// clampDeviceLimits with the environment's GUSUKU_CLAMP_LIMITS (nothing when unset).
void clampDeviceLimitsFromEnvironment(VkPhysicalDeviceLimits& limits);

/// The limits a clamp can name, in VkPhysicalDeviceLimits order (the array limits by element: maxComputeWorkGroupCount[0]).
std::vector<std::string> deviceLimitNames();

/// One limit's value by name (as in deviceLimitNames), as a double; std::invalid_argument for an unknown name.
double deviceLimitValue(const VkPhysicalDeviceLimits& limits, const std::string& name);

}  // namespace gusuku
