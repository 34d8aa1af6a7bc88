#pragma once
// The window's swapchain: made for the surface's current size, made again when the window is resized (or the
// driver says the old one is out of date). An sRGB format, so the runtime's sRGB composite is blitted onto it
// byte for byte; usage TRANSFER_DST (the blit) and TRANSFER_SRC (screenshots); FIFO (every driver has it, and it
// paces the loop to the display).

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace gusuku::view {

class Swapchain {
public:
    Swapchain(VkPhysicalDevice physical_device, VkDevice device, VkSurfaceKHR surface);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    /// (Re)creates it at the surface's size (`fallback` where the surface leaves the size to the swapchain). The
    /// caller has waited for the GPU to finish with the old images. False when the surface has no area (a
    /// minimised window): nothing to draw until it has.
    bool recreate(VkExtent2D fallback);

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    VkImage image(uint32_t index) const { return images_[index]; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    /// How many times it was made (1 after the first).
    uint32_t generation() const { return generation_; }

private:
    VkPhysicalDevice physical_device_;
    VkDevice device_;
    VkSurfaceKHR surface_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{0, 0};
    std::vector<VkImage> images_;
    uint32_t generation_ = 0;
};

}  // namespace gusuku::view
