#pragma once
// gusuku-view's window and the Vulkan device it draws with: what an app owns and hands to the runtime. A GLFW
// window, an instance with the surface extensions GLFW asks for (and the Khronos validation layer when
// GUSUKU_VALIDATION=1, its messages printed and counted), one device with a queue that does graphics, compute
// and presents to the window's surface, and VK_KHR_swapchain.

#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"

struct GLFWwindow;

namespace gusuku::view {

class WindowDevice {
public:
    /// Opens a width x height window titled `title` and the device. std::runtime_error naming what is missing
    /// (no display, no Vulkan device that can present to it, the validation layer asked for but absent).
    WindowDevice(uint32_t width, uint32_t height, const std::string& title);
    ~WindowDevice();
    WindowDevice(const WindowDevice&) = delete;
    WindowDevice& operator=(const WindowDevice&) = delete;

    GLFWwindow* window() const { return window_; }
    VkSurfaceKHR surface() const { return surface_; }
    /// What Runtime::open takes: the app's instance, physical device, device and queue (gpu_device.h).
    const GpuDevice& gpu() const { return gpu_; }
    VkDevice device() const { return gpu_.device; }
    /// "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string deviceName() const { return gpu_.properties.deviceName; }
    /// Validation messages seen so far (0 without validation).
    static uint32_t validationMessageCount();

private:
    void createInstance();
    void pickDevice();
    void createDevice();
    void release() noexcept;

    GLFWwindow* window_ = nullptr;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    bool sampler_anisotropy_ = false;
    GpuDevice gpu_;
};

}  // namespace gusuku::view
