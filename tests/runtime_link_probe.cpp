// A program linked against gusuku_runtime alone, as an AR app would link it. tests/runtime_link_check.cmake reads
// its dynamic section: the runtime must bring in Vulkan and the C++ runtime, never the I/O stack.
#include <cstdio>

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime_version.h"

int main() {
    std::printf("gusuku_runtime %s\n", gusuku::runtimeVersion());
    // Reaches the Vulkan helpers too, so the binary links what an app's use of the runtime links.
    const gusuku::GpuDevice no_device =
        gusuku::GpuDevice::describe(VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE, VK_NULL_HANDLE, 0);
    std::printf("memory types without a device: %u\n", no_device.memory_properties.memoryTypeCount);
    return 0;
}
