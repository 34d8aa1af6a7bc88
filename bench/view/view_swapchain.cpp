// The window's swapchain (see view_swapchain.h).

#include "view_swapchain.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace gusuku::view {

namespace {

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string("Vulkan: ") + what + " failed (" +
                                                       std::to_string(int(result)) + ")");
}

// An 8-bit sRGB format: the composite (R8G8B8A8_SRGB) blits onto it without changing a code value.
VkSurfaceFormatKHR srgbFormat(VkPhysicalDevice physical_device, VkSurfaceKHR surface) {
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical_device, surface, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(physical_device, surface, &count, formats.data());
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB})
        for (const VkSurfaceFormatKHR& format : formats)
            if (format.format == wanted && format.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return format;
    throw std::runtime_error("Vulkan: the window's surface offers no B8G8R8A8_SRGB or R8G8B8A8_SRGB format");
}

}  // namespace

Swapchain::Swapchain(VkPhysicalDevice physical_device, VkDevice device, VkSurfaceKHR surface)
    : physical_device_(physical_device), device_(device), surface_(surface) {}

Swapchain::~Swapchain() {
    if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
}

bool Swapchain::recreate(VkExtent2D fallback) {
    VkSurfaceCapabilitiesKHR capabilities{};
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical_device_, surface_, &capabilities),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = capabilities.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent.width = std::clamp(fallback.width, capabilities.minImageExtent.width, capabilities.maxImageExtent.width);
        extent.height =
            std::clamp(fallback.height, capabilities.minImageExtent.height, capabilities.maxImageExtent.height);
    }
    if (extent.width == 0 || extent.height == 0) return false;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((capabilities.supportedUsageFlags & usage) != usage)
        throw std::runtime_error("Vulkan: the window's swapchain images cannot be blitted to and read back");
    const VkSurfaceFormatKHR format = srgbFormat(physical_device_, surface_);
    uint32_t image_count = std::max(capabilities.minImageCount + 1, 3u);  // room for two frames in flight
    if (capabilities.maxImageCount) image_count = std::min(image_count, capabilities.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = image_count;
    info.imageFormat = format.format;
    info.imageColorSpace = format.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = capabilities.currentTransform;
    info.compositeAlpha = (capabilities.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VkCompositeAlphaFlagBitsKHR(capabilities.supportedCompositeAlpha &
                                                            -capabilities.supportedCompositeAlpha);
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    check(vkCreateSwapchainKHR(device_, &info, nullptr, &created), "vkCreateSwapchainKHR");
    if (swapchain_) vkDestroySwapchainKHR(device_, swapchain_, nullptr);
    swapchain_ = created;
    format_ = format.format;
    extent_ = extent;
    uint32_t count = 0;
    vkGetSwapchainImagesKHR(device_, swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(device_, swapchain_, &count, images_.data());
    ++generation_;
    return true;
}

}  // namespace gusuku::view
