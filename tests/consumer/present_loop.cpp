// The runtime's GPU-resident frame loop in a window, in its smallest form: what an app embedding gusuku copies.
// Installed as share/gusuku/examples/present_loop.cpp; gusuku-view's FrameLoop (bench/view/view_frame_loop.cpp in
// gusuku's sources) is the full version (camera uploads, resizing, screenshots). Build it against the package
// with GLFW: target_link_libraries(app PRIVATE gusuku::runtime gusuku::pack_loader glfw).
//   present_loop BAKESET/pack      (a runtime pack: `gusuku-bake bake` writes one into every bake set)
// Per frame, two in flight: the platform's camera writes the camera image and signals `camera_ready` (here a clear
// to grey stands in for it); Runtime::renderFrame samples the image in place, waits on `camera_ready`, signals
// `composite_ready` and reads nothing back; the app blits compositeImage() onto the acquired swapchain image,
// waiting on both, and presents.
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <gusuku/pack_loader/runtime_pack.h>
#include <gusuku/runtime/runtime.h>

#define CHECK(call) do { if ((call) != VK_SUCCESS) { std::fprintf(stderr, "%s failed\n", #call); return 1; } } while (0)

namespace {
constexpr uint32_t kWidth = 960, kHeight = 540, kInFlight = 2;  // the runtime's frames_in_flight is 2 as well

void barrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags source,
             VkAccessFlags target) {
    VkImageMemoryBarrier info{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    info.srcAccessMask = source;
    info.dstAccessMask = target;
    info.oldLayout = from;
    info.newLayout = to;
    info.srcQueueFamilyIndex = info.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    info.image = image;
    info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &info);
}
}  // namespace

int main(int argc, char** argv) try {
    if (argc != 2) return std::fprintf(stderr, "usage: present_loop BAKESET/pack\n"), 2;
    const gusuku::BakeSetData bake_set = gusuku::loadRuntimePack(argv[1]);
    // The app's window, instance, device and queue (graphics, compute and present in one family).
    if (!glfwInit()) return std::fprintf(stderr, "no display\n"), 1;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    GLFWwindow* window = glfwCreateWindow(int(kWidth), int(kHeight), "present_loop", nullptr, nullptr);
    uint32_t extension_count = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&extension_count);
    VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &application;
    instance_info.enabledExtensionCount = extension_count;
    instance_info.ppEnabledExtensionNames = extensions;
    VkInstance instance;
    CHECK(vkCreateInstance(&instance_info, nullptr, &instance));
    VkSurfaceKHR surface;
    CHECK(glfwCreateWindowSurface(instance, window, nullptr, &surface));
    uint32_t count = 1;
    VkPhysicalDevice physical;
    vkEnumeratePhysicalDevices(instance, &count, &physical);  // the first device; family 0 (check both in an app)
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    device_info.enabledExtensionCount = 1;
    device_info.ppEnabledExtensionNames = &swapchain_extension;
    VkDevice device;
    CHECK(vkCreateDevice(physical, &device_info, nullptr, &device));
    VkQueue queue;
    vkGetDeviceQueue(device, 0, 0, &queue);

    // The runtime on the app's device.
    gusuku::RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    std::unique_ptr<gusuku::Runtime> runtime =
        gusuku::Runtime::open(gusuku::GpuDevice::describe(instance, physical, device, queue, 0), bake_set, options);

    // The swapchain (sRGB, as the composite is: the blit keeps its bytes) and the camera image.
    VkSurfaceCapabilitiesKHR caps;
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps);
    VkSwapchainCreateInfoKHR swapchain_info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    swapchain_info.surface = surface;
    swapchain_info.minImageCount = caps.minImageCount + 1;
    swapchain_info.imageFormat = VK_FORMAT_B8G8R8A8_SRGB;
    swapchain_info.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    swapchain_info.imageExtent = caps.currentExtent.width == UINT32_MAX ? VkExtent2D{kWidth, kHeight} : caps.currentExtent;
    swapchain_info.imageArrayLayers = 1;
    swapchain_info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    swapchain_info.preTransform = caps.currentTransform;
    swapchain_info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    swapchain_info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    VkSwapchainKHR swapchain;
    CHECK(vkCreateSwapchainKHR(device, &swapchain_info, nullptr, &swapchain));
    std::vector<VkImage> images(8);
    count = 8;
    vkGetSwapchainImagesKHR(device, swapchain, &count, images.data());
    VkImageCreateInfo camera_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    camera_info.imageType = VK_IMAGE_TYPE_2D;
    camera_info.format = VK_FORMAT_R8G8B8A8_UNORM;
    camera_info.extent = {kWidth, kHeight, 1};
    camera_info.mipLevels = camera_info.arrayLayers = 1;
    camera_info.samples = VK_SAMPLE_COUNT_1_BIT;
    camera_info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImage camera;
    CHECK(vkCreateImage(device, &camera_info, nullptr, &camera));
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(device, camera, &needs);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = needs.size;
    while (!(needs.memoryTypeBits >> allocation.memoryTypeIndex & 1)) ++allocation.memoryTypeIndex;  // any it takes
    VkDeviceMemory camera_memory;
    CHECK(vkAllocateMemory(device, &allocation, nullptr, &camera_memory));
    CHECK(vkBindImageMemory(device, camera, camera_memory, 0));

    // Per frame in flight: two command buffers, a fence, four semaphores.
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    VkCommandPool pool;
    CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool));
    VkCommandBuffer commands[2 * kInFlight];
    VkCommandBufferAllocateInfo command_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = pool;
    command_info.commandBufferCount = 2 * kInFlight;
    CHECK(vkAllocateCommandBuffers(device, &command_info, commands));
    VkFence done[kInFlight];
    VkSemaphore camera_ready[kInFlight], composite_ready[kInFlight], acquired[kInFlight], finished[kInFlight];
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t slot = 0; slot < kInFlight; ++slot) {
        CHECK(vkCreateFence(device, &fence_info, nullptr, &done[slot]));
        for (VkSemaphore* semaphore : {&camera_ready[slot], &composite_ready[slot], &acquired[slot], &finished[slot]})
            CHECK(vkCreateSemaphore(device, &semaphore_info, nullptr, semaphore));
    }

    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    const VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    const VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
    const VkPipelineStageFlags stages[2] = {transfer, transfer};
    for (uint64_t frame = 0; !glfwWindowShouldClose(window); ++frame) {
        glfwPollEvents();
        const uint32_t slot = uint32_t(frame % kInFlight);
        vkWaitForFences(device, 1, &done[slot], VK_TRUE, UINT64_MAX);  // this slot's last frame is done
        vkResetFences(device, 1, &done[slot]);
        // 1. The camera writes its image and signals camera_ready (a phone's camera would; a clear stands in).
        VkCommandBuffer camera_commands = commands[2 * slot], present_commands = commands[2 * slot + 1];
        vkBeginCommandBuffer(camera_commands, &begin);
        barrier(camera_commands, camera, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                VK_ACCESS_TRANSFER_WRITE_BIT);
        const VkClearColorValue grey{{0.5f, 0.5f, 0.5f, 1.0f}};
        vkCmdClearColorImage(camera_commands, camera, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &whole);
        barrier(camera_commands, camera, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
        vkEndCommandBuffer(camera_commands);
        VkSubmitInfo camera_submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        camera_submit.commandBufferCount = 1;
        camera_submit.pCommandBuffers = &camera_commands;
        camera_submit.signalSemaphoreCount = 1;
        camera_submit.pSignalSemaphores = &camera_ready[slot];
        CHECK(vkQueueSubmit(queue, 1, &camera_submit, VK_NULL_HANDLE));
        // 2. The runtime's frame: the camera image in place, the app's semaphores, no read-back.
        gusuku::FrameInput input;
        input.camera_image = camera;
        input.sync.wait_count = 1;
        input.sync.wait_semaphores = &camera_ready[slot];
        input.sync.signal_count = 1;
        input.sync.signal_semaphores = &composite_ready[slot];
        input.intrinsics = gusuku::CameraIntrinsics::fromFieldOfView(kWidth, kHeight, 60.0);
        input.pose = gusuku::CameraPose::lookingAt({25.0 * std::sin(frame * 0.01), -25.0 * std::cos(frame * 0.01), 6.0},
                                                   {0.0, 0.0, 2.0});  // a slow walk around the site's origin
        input.utc_unix_seconds = 1782010800.0;  // 2026-06-21T03:00Z
        input.colour_match = gusuku::ColourMatch::kOff;
        runtime->renderFrame(input, nullptr);
        // 3. The composite onto the swapchain image, after both semaphores; then present.
        uint32_t index = 0;
        CHECK(vkAcquireNextImageKHR(device, swapchain, UINT64_MAX, acquired[slot], VK_NULL_HANDLE, &index));
        vkBeginCommandBuffer(present_commands, &begin);
        barrier(present_commands, images[index], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                VK_ACCESS_TRANSFER_WRITE_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int32_t(kWidth), int32_t(kHeight), 1};
        blit.dstOffsets[1] = {int32_t(swapchain_info.imageExtent.width), int32_t(swapchain_info.imageExtent.height), 1};
        vkCmdBlitImage(present_commands, runtime->compositeImage(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        barrier(present_commands, images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                VK_ACCESS_TRANSFER_WRITE_BIT, 0);
        vkEndCommandBuffer(present_commands);
        const VkSemaphore waits[2] = {acquired[slot], composite_ready[slot]};
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.waitSemaphoreCount = 2;
        submit.pWaitSemaphores = waits;
        submit.pWaitDstStageMask = stages;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &present_commands;
        submit.signalSemaphoreCount = 1;
        submit.pSignalSemaphores = &finished[slot];
        CHECK(vkQueueSubmit(queue, 1, &submit, done[slot]));
        VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        present.waitSemaphoreCount = 1;
        present.pWaitSemaphores = &finished[slot];
        present.swapchainCount = 1;
        present.pSwapchains = &swapchain;
        present.pImageIndices = &index;
        CHECK(vkQueuePresentKHR(queue, &present));  // a resized window ends the example: see gusuku-view
    }
    vkDeviceWaitIdle(device);
    runtime.reset();  // before the device; then the app's own objects
    for (uint32_t slot = 0; slot < kInFlight; ++slot) {
        vkDestroyFence(device, done[slot], nullptr);
        for (VkSemaphore semaphore : {camera_ready[slot], composite_ready[slot], acquired[slot], finished[slot]})
            vkDestroySemaphore(device, semaphore, nullptr);
    }
    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyImage(device, camera, nullptr);
    vkFreeMemory(device, camera_memory, nullptr);
    vkDestroySwapchainKHR(device, swapchain, nullptr);
    vkDestroyDevice(device, nullptr);
    vkDestroySurfaceKHR(instance, surface, nullptr);
    vkDestroyInstance(instance, nullptr);
    glfwDestroyWindow(window);
    glfwTerminate();
    return 0;
} catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
}
