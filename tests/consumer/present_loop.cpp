// The runtime's GPU-resident frame loop in a window, in its smallest form: what an app embedding gusuku copies.
// Installed as share/gusuku/examples/present_loop.cpp; gusuku-view's FrameLoop (bench/view/view_frame_loop.cpp in
// gusuku's sources) is the full version (camera uploads, resizing, screenshots). Build it against the package
// with GLFW: target_link_libraries(app PRIVATE gusuku::runtime gusuku::pack_loader glfw).
//   present_loop BAKESET/pack      (a runtime pack: `gusuku-bake bake` writes one into every bake set)
// Per frame, two in flight: the platform's camera writes the camera image and signals `camera_ready` (here a clear
// to grey stands in for it); Runtime::renderFrame samples the image in place, waits on `camera_ready`, signals
// `composite_ready` and reads nothing back; the app blits compositeImage() onto the acquired swapchain image,
// waiting on both, and presents. The app's own objects come first (openApp, openSwapchain, openCameraImage,
// openFrameSync); each frame is the three steps of drawFrame; closeAll destroys in reverse, the runtime first.
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <gusuku/pack_loader/runtime_pack.h>
#include <gusuku/runtime/runtime.h>

#define CHECK(call) do { if ((call) != VK_SUCCESS) { std::fprintf(stderr, "%s failed\n", #call); return false; } } while (0)

namespace {
constexpr uint32_t kWidth = 960, kHeight = 540, kInFlight = 2;  // the runtime's frames_in_flight is 2 as well

// The app's window, instance, device and queue (graphics, compute and present in one family).
struct App {
    GLFWwindow* window = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
};

// The swapchain (sRGB, as the composite is: the blit keeps its bytes) and its images.
struct Swapchain {
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkExtent2D extent{};
    std::vector<VkImage> images;
};

// The image the platform's camera writes each frame (an imported AHardwareBuffer or CVPixelBuffer on a phone).
struct CameraImage {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
};

// Per frame in flight: two command buffers (the camera's, the present's), a fence, four semaphores.
struct FrameSync {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer commands[2 * kInFlight]{};
    VkFence done[kInFlight]{};
    VkSemaphore camera_ready[kInFlight]{}, composite_ready[kInFlight]{}, acquired[kInFlight]{}, finished[kInFlight]{};
};

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

bool openApp(App& app) {
    if (!glfwInit()) return std::fprintf(stderr, "no display\n"), false;
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    app.window = glfwCreateWindow(int(kWidth), int(kHeight), "present_loop", nullptr, nullptr);
    uint32_t extension_count = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&extension_count);
    VkApplicationInfo application{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    application.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instance_info.pApplicationInfo = &application;
    instance_info.enabledExtensionCount = extension_count;
    instance_info.ppEnabledExtensionNames = extensions;
    CHECK(vkCreateInstance(&instance_info, nullptr, &app.instance));
    CHECK(glfwCreateWindowSurface(app.instance, app.window, nullptr, &app.surface));
    uint32_t count = 1;
    vkEnumeratePhysicalDevices(app.instance, &count, &app.physical);  // the first device; family 0 (check both in an app)
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
    CHECK(vkCreateDevice(app.physical, &device_info, nullptr, &app.device));
    vkGetDeviceQueue(app.device, 0, 0, &app.queue);
    return true;
}

bool openSwapchain(const App& app, Swapchain& out) {
    VkSurfaceCapabilitiesKHR caps;
    vkGetPhysicalDeviceSurfaceCapabilitiesKHR(app.physical, app.surface, &caps);
    out.extent = caps.currentExtent.width == UINT32_MAX ? VkExtent2D{kWidth, kHeight} : caps.currentExtent;
    VkSwapchainCreateInfoKHR swapchain_info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    swapchain_info.surface = app.surface;
    swapchain_info.minImageCount = caps.minImageCount + 1;
    swapchain_info.imageFormat = VK_FORMAT_B8G8R8A8_SRGB;
    swapchain_info.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    swapchain_info.imageExtent = out.extent;
    swapchain_info.imageArrayLayers = 1;
    swapchain_info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    swapchain_info.preTransform = caps.currentTransform;
    swapchain_info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    swapchain_info.presentMode = VK_PRESENT_MODE_FIFO_KHR;
    CHECK(vkCreateSwapchainKHR(app.device, &swapchain_info, nullptr, &out.swapchain));
    uint32_t count = 0;
    vkGetSwapchainImagesKHR(app.device, out.swapchain, &count, nullptr);
    out.images.resize(count);
    vkGetSwapchainImagesKHR(app.device, out.swapchain, &count, out.images.data());
    return true;
}

bool openCameraImage(const App& app, CameraImage& out) {
    VkImageCreateInfo camera_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    camera_info.imageType = VK_IMAGE_TYPE_2D;
    camera_info.format = VK_FORMAT_R8G8B8A8_UNORM;
    camera_info.extent = {kWidth, kHeight, 1};
    camera_info.mipLevels = camera_info.arrayLayers = 1;
    camera_info.samples = VK_SAMPLE_COUNT_1_BIT;
    camera_info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    CHECK(vkCreateImage(app.device, &camera_info, nullptr, &out.image));
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(app.device, out.image, &needs);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = needs.size;
    while (!(needs.memoryTypeBits >> allocation.memoryTypeIndex & 1)) ++allocation.memoryTypeIndex;  // any it takes
    CHECK(vkAllocateMemory(app.device, &allocation, nullptr, &out.memory));
    CHECK(vkBindImageMemory(app.device, out.image, out.memory, 0));
    return true;
}

bool openFrameSync(const App& app, FrameSync& out) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    CHECK(vkCreateCommandPool(app.device, &pool_info, nullptr, &out.pool));
    VkCommandBufferAllocateInfo command_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    command_info.commandPool = out.pool;
    command_info.commandBufferCount = 2 * kInFlight;
    CHECK(vkAllocateCommandBuffers(app.device, &command_info, out.commands));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (uint32_t slot = 0; slot < kInFlight; ++slot) {
        CHECK(vkCreateFence(app.device, &fence_info, nullptr, &out.done[slot]));
        for (VkSemaphore* semaphore : {&out.camera_ready[slot], &out.composite_ready[slot], &out.acquired[slot],
                                       &out.finished[slot]})
            CHECK(vkCreateSemaphore(app.device, &semaphore_info, nullptr, semaphore));
    }
    return true;
}

// 1. The camera writes its image and signals camera_ready (a phone's camera would; a clear to grey stands in).
bool writeCamera(const App& app, const CameraImage& camera, VkCommandBuffer commands, VkSemaphore camera_ready) {
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    const VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkBeginCommandBuffer(commands, &begin);
    barrier(commands, camera.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
            VK_ACCESS_TRANSFER_WRITE_BIT);
    const VkClearColorValue grey{{0.5f, 0.5f, 0.5f, 1.0f}};
    vkCmdClearColorImage(commands, camera.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &grey, 1, &whole);
    barrier(commands, camera.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
            VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkEndCommandBuffer(commands);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &camera_ready;
    CHECK(vkQueueSubmit(app.queue, 1, &submit, VK_NULL_HANDLE));
    return true;
}

// 2. The runtime's frame: the camera image in place, the app's semaphores, no read-back.
void renderComposite(gusuku::Runtime& runtime, const CameraImage& camera, const FrameSync& sync, uint32_t slot,
                     uint64_t frame) {
    gusuku::FrameInput input;
    input.camera_image = camera.image;
    input.sync.wait_count = 1;
    input.sync.wait_semaphores = &sync.camera_ready[slot];
    input.sync.signal_count = 1;
    input.sync.signal_semaphores = &sync.composite_ready[slot];
    input.intrinsics = gusuku::CameraIntrinsics::fromFieldOfView(kWidth, kHeight, 60.0);
    input.pose = gusuku::CameraPose::lookingAt({25.0 * std::sin(frame * 0.01), -25.0 * std::cos(frame * 0.01), 6.0},
                                               {0.0, 0.0, 2.0});  // a slow walk around the site's origin
    input.utc_unix_seconds = 1782010800.0;  // 2026-06-21T03:00Z
    input.colour_match = gusuku::ColourMatch::kOff;
    runtime.renderFrame(input, nullptr);
}

// 3. The composite onto the swapchain image, after both semaphores; then present.
bool presentComposite(const App& app, const Swapchain& swapchain, const FrameSync& sync, uint32_t slot,
                      VkImage composite) {
    uint32_t index = 0;
    CHECK(vkAcquireNextImageKHR(app.device, swapchain.swapchain, UINT64_MAX, sync.acquired[slot], VK_NULL_HANDLE,
                                &index));
    VkCommandBuffer commands = sync.commands[2 * slot + 1];
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(commands, &begin);
    barrier(commands, swapchain.images[index], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
            VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(kWidth), int32_t(kHeight), 1};
    blit.dstOffsets[1] = {int32_t(swapchain.extent.width), int32_t(swapchain.extent.height), 1};
    vkCmdBlitImage(commands, composite, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain.images[index],
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    barrier(commands, swapchain.images[index], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
            VK_ACCESS_TRANSFER_WRITE_BIT, 0);
    vkEndCommandBuffer(commands);
    const VkSemaphore waits[2] = {sync.acquired[slot], sync.composite_ready[slot]};
    const VkPipelineStageFlags stages[2] = {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT};
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 2;
    submit.pWaitSemaphores = waits;
    submit.pWaitDstStageMask = stages;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &sync.finished[slot];
    CHECK(vkQueueSubmit(app.queue, 1, &submit, sync.done[slot]));
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &sync.finished[slot];
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain.swapchain;
    present.pImageIndices = &index;
    CHECK(vkQueuePresentKHR(app.queue, &present));  // a resized window ends the example: see gusuku-view
    return true;
}

bool drawFrame(const App& app, gusuku::Runtime& runtime, const Swapchain& swapchain, const CameraImage& camera,
               const FrameSync& sync, uint64_t frame) {
    const uint32_t slot = uint32_t(frame % kInFlight);
    vkWaitForFences(app.device, 1, &sync.done[slot], VK_TRUE, UINT64_MAX);  // this slot's last frame is done
    vkResetFences(app.device, 1, &sync.done[slot]);
    if (!writeCamera(app, camera, sync.commands[2 * slot], sync.camera_ready[slot])) return false;
    renderComposite(runtime, camera, sync, slot, frame);
    return presentComposite(app, swapchain, sync, slot, runtime.compositeImage());
}

// The runtime before the device it runs on; then the app's own objects in reverse order (null handles are skipped).
void closeAll(App& app, std::unique_ptr<gusuku::Runtime>& runtime, Swapchain& swapchain, CameraImage& camera,
              FrameSync& sync) {
    if (app.device) vkDeviceWaitIdle(app.device);
    runtime.reset();
    if (app.device) {
        for (uint32_t slot = 0; slot < kInFlight; ++slot) {
            vkDestroyFence(app.device, sync.done[slot], nullptr);
            for (VkSemaphore semaphore : {sync.camera_ready[slot], sync.composite_ready[slot], sync.acquired[slot],
                                          sync.finished[slot]})
                vkDestroySemaphore(app.device, semaphore, nullptr);
        }
        vkDestroyCommandPool(app.device, sync.pool, nullptr);
        vkDestroyImage(app.device, camera.image, nullptr);
        vkFreeMemory(app.device, camera.memory, nullptr);
        vkDestroySwapchainKHR(app.device, swapchain.swapchain, nullptr);
        vkDestroyDevice(app.device, nullptr);
    }
    if (app.instance) {
        vkDestroySurfaceKHR(app.instance, app.surface, nullptr);
        vkDestroyInstance(app.instance, nullptr);
    }
    if (app.window) glfwDestroyWindow(app.window);
    glfwTerminate();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) return std::fprintf(stderr, "usage: present_loop BAKESET/pack\n"), 2;
    App app;
    Swapchain swapchain;
    CameraImage camera;
    FrameSync sync;
    std::unique_ptr<gusuku::Runtime> runtime;
    bool ok = false;
    try {
        const gusuku::BakeSetData bake_set = gusuku::loadRuntimePack(argv[1]);
        ok = openApp(app);
        if (ok) {  // the runtime on the app's device
            gusuku::RuntimeOptions options;
            options.frame_width = kWidth;
            options.frame_height = kHeight;
            runtime = gusuku::Runtime::open(
                gusuku::GpuDevice::describe(app.instance, app.physical, app.device, app.queue, 0), bake_set, options);
        }
        ok = ok && openSwapchain(app, swapchain) && openCameraImage(app, camera) && openFrameSync(app, sync);
        for (uint64_t frame = 0; ok && !glfwWindowShouldClose(app.window); ++frame) {
            glfwPollEvents();
            ok = drawFrame(app, *runtime, swapchain, camera, sync, frame);
        }
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s\n", error.what());
        ok = false;
    }
    closeAll(app, runtime, swapchain, camera, sync);
    return ok ? 0 : 1;
}
