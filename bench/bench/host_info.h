#pragma once
// What the bench's frame times were measured on: the CPU model, the threads lavapipe uses, the device and its
// driver (Mesa and LLVM versions, from VkPhysicalDeviceDriverProperties; vulkan_context.h).

#include <string>

namespace gusuku::bench {

struct HostInfo {
    std::string cpu_model;       ///< /proc/cpuinfo's first "model name", "unknown" when absent
    unsigned logical_cpus = 0;   ///< std::thread::hardware_concurrency
    unsigned lavapipe_threads = 0;  ///< LP_NUM_THREADS when set, else the logical CPUs (llvmpipe's default)
    std::string device;          ///< the Vulkan device, type, API version and driver info
};

HostInfo describeHost(const std::string& device_description);

}  // namespace gusuku::bench
