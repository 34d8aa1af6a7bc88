// gusuku-view's frame loop, the GPU-resident path an app runs (see view_frame_loop.h for the steps).

#include "view_frame_loop.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace gusuku::view {

namespace {

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw std::runtime_error(std::string("Vulkan: ") + what + " failed (" +
                                                       std::to_string(int(result)) + ")");
}

void imageBarrier(VkCommandBuffer commands, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags source_stage, VkAccessFlags source_access, VkPipelineStageFlags target_stage,
                  VkAccessFlags target_access) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = source_access;
    barrier.dstAccessMask = target_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(commands, source_stage, target_stage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

// The largest rectangle of the frame's aspect inside the window, centred (the rest is black).
VkOffset3D fitted(VkExtent2D window, uint32_t width, uint32_t height, VkOffset3D& origin) {
    uint32_t fit_width = window.width, fit_height = uint32_t(uint64_t(window.width) * height / width);
    if (fit_height > window.height) {
        fit_height = window.height;
        fit_width = uint32_t(uint64_t(window.height) * width / height);
    }
    fit_width = std::max(fit_width, 1u);
    fit_height = std::max(fit_height, 1u);
    origin = {int32_t((window.width - fit_width) / 2), int32_t((window.height - fit_height) / 2), 0};
    return {origin.x + int32_t(fit_width), origin.y + int32_t(fit_height), 1};
}

}  // namespace

FrameLoop::FrameLoop(const WindowDevice& window, Swapchain& swapchain, Runtime& runtime, uint32_t camera_width,
                     uint32_t camera_height)
    : window_(window), device_(window.device()), swapchain_(swapchain), runtime_(&runtime),
      camera_width_(camera_width), camera_height_(camera_height) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = window.gpu().queue_family_index;
    check(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    for (Slot& slot : slots_) createSlot(slot);
    createCameraImage();
}

FrameLoop::~FrameLoop() {
    vkDeviceWaitIdle(device_);
    for (Slot& slot : slots_) destroySlot(slot);
    if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
    if (readback_memory_) vkFreeMemory(device_, readback_memory_, nullptr);
    vkDestroyImage(device_, camera_image_, nullptr);
    vkFreeMemory(device_, camera_memory_, nullptr);
    vkDestroyCommandPool(device_, pool_, nullptr);
}

VkBuffer FrameLoop::makeBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkDeviceMemory& memory, void** mapped) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = usage;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(device_, &info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements needs;
    vkGetBufferMemoryRequirements(device_, buffer, &needs);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = needs.size;
    allocation.memoryTypeIndex = window_.gpu().findMemoryType(
        needs.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkAllocateMemory(device_, &allocation, nullptr, &memory), "vkAllocateMemory");
    check(vkBindBufferMemory(device_, buffer, memory, 0), "vkBindBufferMemory");
    check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, mapped), "vkMapMemory");
    return buffer;
}

void FrameLoop::createSlot(Slot& slot) {
    VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocation.commandPool = pool_;
    allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocation.commandBufferCount = 2;
    VkCommandBuffer buffers[2];
    check(vkAllocateCommandBuffers(device_, &allocation, buffers), "vkAllocateCommandBuffers");
    slot.upload = buffers[0];
    slot.present = buffers[1];
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // nothing in flight yet
    check(vkCreateFence(device_, &fence_info, nullptr, &slot.done), "vkCreateFence");
    VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    for (VkSemaphore* semaphore :
         {&slot.camera_ready, &slot.composite_ready, &slot.image_acquired, &slot.render_finished})
        check(vkCreateSemaphore(device_, &semaphore_info, nullptr, semaphore), "vkCreateSemaphore");
    slot.staging = makeBuffer(VkDeviceSize(camera_width_) * camera_height_ * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              slot.staging_memory, &slot.staging_bytes);
    slot.overlay = makeBuffer(VkDeviceSize(kOverlayMaxWidth) * kOverlayMaxHeight * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              slot.overlay_memory, &slot.overlay_bytes);
}

void FrameLoop::destroySlot(Slot& slot) {
    for (VkSemaphore semaphore : {slot.camera_ready, slot.composite_ready, slot.image_acquired, slot.render_finished})
        vkDestroySemaphore(device_, semaphore, nullptr);
    vkDestroyFence(device_, slot.done, nullptr);
    vkDestroyBuffer(device_, slot.staging, nullptr);
    vkFreeMemory(device_, slot.staging_memory, nullptr);
    vkDestroyBuffer(device_, slot.overlay, nullptr);
    vkFreeMemory(device_, slot.overlay_memory, nullptr);
}

void FrameLoop::createCameraImage() {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = VK_FORMAT_R8G8B8A8_UNORM;  // sRGB bytes: the runtime reads them as sRGB (runtime.h)
    info.extent = {camera_width_, camera_height_, 1};
    info.mipLevels = info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device_, &info, nullptr, &camera_image_), "vkCreateImage");
    VkMemoryRequirements needs;
    vkGetImageMemoryRequirements(device_, camera_image_, &needs);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = needs.size;
    allocation.memoryTypeIndex =
        window_.gpu().findMemoryType(needs.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(device_, &allocation, nullptr, &camera_memory_), "vkAllocateMemory");
    check(vkBindImageMemory(device_, camera_image_, camera_memory_, 0), "vkBindImageMemory");
}

void FrameLoop::setCamera(const std::vector<uint8_t>& rgba8) {
    if (rgba8.size() != size_t(camera_width_) * camera_height_ * 4)
        throw std::invalid_argument("FrameLoop::setCamera: the frame is not the camera image's size");
    pending_camera_ = rgba8;
}

void FrameLoop::waitIdle() { check(vkDeviceWaitIdle(device_), "vkDeviceWaitIdle"); }

// The staging buffer into the camera image. The frames before this one may still read the image: the first
// barrier's source scope (every command submitted earlier on the queue) orders this write after their reads.
void FrameLoop::recordCameraUpload(const Slot& slot) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(slot.upload, &begin), "vkBeginCommandBuffer");
    imageBarrier(slot.upload, camera_image_,
                 camera_written_ ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {camera_width_, camera_height_, 1};
    vkCmdCopyBufferToImage(slot.upload, slot.staging, camera_image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    // The layout the frame reads it in (FrameInput::camera_image_layout); camera_ready carries the write to it.
    imageBarrier(slot.upload, camera_image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_SHADER_READ_BIT);
    check(vkEndCommandBuffer(slot.upload), "vkEndCommandBuffer");
    camera_written_ = true;
}

void FrameLoop::ensureReadback(VkDeviceSize bytes) {
    if (readback_size_ >= bytes) return;
    if (readback_) vkDestroyBuffer(device_, readback_, nullptr);
    if (readback_memory_) vkFreeMemory(device_, readback_memory_, nullptr);
    readback_ = makeBuffer(bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, readback_memory_, &readback_bytes_);
    readback_size_ = bytes;
}

// The composite blitted onto the swapchain image, fitted and letterboxed; then, for a screenshot, the image copied
// into the read-back buffer; then the image handed to the presentation engine.
void FrameLoop::recordPresent(const Slot& slot, VkImage target, bool read_back) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(slot.present, &begin), "vkBeginCommandBuffer");
    const VkExtent2D extent = swapchain_.extent();
    // The previous contents are not needed (UNDEFINED); image_acquired is waited on at the transfer stage.
    imageBarrier(slot.present, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    const VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(slot.present, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &whole);
    imageBarrier(slot.present, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    // The composite is in TRANSFER_SRC_OPTIMAL (runtime.h); composite_ready, waited on at the transfer stage,
    // makes the runtime's writes visible to this read.
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(camera_width_), int32_t(camera_height_), 1};
    blit.dstOffsets[1] = fitted(extent, camera_width_, camera_height_, blit.dstOffsets[0]);
    const bool same_size = blit.dstOffsets[1].x - blit.dstOffsets[0].x == int32_t(camera_width_) &&
                           blit.dstOffsets[1].y - blit.dstOffsets[0].y == int32_t(camera_height_);
    vkCmdBlitImage(slot.present, runtime_->compositeImage(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, same_size ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    if (read_back) {
        imageBarrier(slot.present, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyImageToBuffer(slot.present, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_, 1, &region);
        VkBufferMemoryBarrier to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        to_host.buffer = readback_;
        to_host.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(slot.present, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr,
                             1, &to_host, 0, nullptr);
    }
    // The overlay's copy goes after the blit's writes (and the read-back's read): back to a copy target.
    const VkImageLayout now = read_back ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    imageBarrier(slot.present, target, now, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 read_back ? VK_ACCESS_TRANSFER_READ_BIT : VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    recordOverlay(slot, target);
    imageBarrier(slot.present, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
    check(vkEndCommandBuffer(slot.present), "vkEndCommandBuffer");
}

// The overlay's pixels into this slot's buffer (the slot's fence was waited on: the GPU is done with it), then
// copied onto the image's top-left; the image is a copy target (TRANSFER_DST_OPTIMAL) here.
void FrameLoop::recordOverlay(const Slot& slot, VkImage target) {
    const VkExtent2D extent = swapchain_.extent();
    const uint32_t width = std::min({overlay_.width, kOverlayMaxWidth, extent.width});
    const uint32_t height = std::min({overlay_.height, kOverlayMaxHeight, extent.height});
    if (width == 0 || height == 0) return;
    for (uint32_t row = 0; row < height; ++row)
        std::memcpy(static_cast<uint8_t*>(slot.overlay_bytes) + size_t(row) * width * 4,
                    overlay_.rgba8.data() + size_t(row) * overlay_.width * 4, size_t(width) * 4);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyBufferToImage(slot.present, slot.overlay, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

bool FrameLoop::drawFrame(const FrameInput& frame_in, FrameInfo& info, Screenshot* screenshot) {
    const GpuDevice& gpu = window_.gpu();
    Slot& slot = slots_[frame_index_ % kFramesInFlight];
    // 1. This slot's last frame is done: its command buffers, semaphores and staging buffer are free.
    check(vkWaitForFences(device_, 1, &slot.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");

    // 2. A new camera frame: into the staging buffer, then (on the GPU) into the camera image.
    FrameInput frame = frame_in;
    VkPipelineStageFlags camera_wait_stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
    if (!pending_camera_.empty()) {
        std::memcpy(slot.staging_bytes, pending_camera_.data(), pending_camera_.size());
        pending_camera_.clear();
        recordCameraUpload(slot);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &slot.upload;
        submit.signalSemaphoreCount = 1;
        submit.pSignalSemaphores = &slot.camera_ready;
        check(gpu.submitToQueue(submit, VK_NULL_HANDLE), "vkQueueSubmit (camera)");
        frame.sync.wait_count = 1;
        frame.sync.wait_semaphores = &slot.camera_ready;
        frame.sync.wait_stages = &camera_wait_stage;
    }
    if (!camera_written_) throw std::logic_error("FrameLoop::drawFrame: no camera frame was given (setCamera)");

    // 3. The runtime's frame, GPU-resident: the camera image sampled in place, no output bytes, no wait.
    frame.camera_image = camera_image_;
    frame.camera_image_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    frame.camera_image_format = VK_FORMAT_R8G8B8A8_UNORM;
    frame.sync.signal_count = 1;
    frame.sync.signal_semaphores = &slot.composite_ready;
    info = runtime_->renderFrame(frame, nullptr);

    // 4. A swapchain image to draw on. Out of date: composite_ready is still consumed (a signalled semaphore no
    // one waits on cannot be signalled again), and the caller makes a new swapchain.
    uint32_t image_index = 0;
    VkResult acquired = vkAcquireNextImageKHR(device_, swapchain_.handle(), UINT64_MAX, slot.image_acquired,
                                              VK_NULL_HANDLE, &image_index);
    check(vkResetFences(device_, 1, &slot.done), "vkResetFences");
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
        VkSubmitInfo consume{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        consume.waitSemaphoreCount = 1;
        consume.pWaitSemaphores = &slot.composite_ready;
        consume.pWaitDstStageMask = &stage;
        check(gpu.submitToQueue(consume, slot.done), "vkQueueSubmit");
        ++frame_index_;
        return false;
    }
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");
    if (screenshot) ensureReadback(VkDeviceSize(swapchain_.extent().width) * swapchain_.extent().height * 4);
    recordPresent(slot, swapchain_.image(image_index), screenshot != nullptr);
    const VkSemaphore waits[] = {slot.image_acquired, slot.composite_ready};
    const VkPipelineStageFlags wait_stages[] = {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT};
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 2;
    submit.pWaitSemaphores = waits;
    submit.pWaitDstStageMask = wait_stages;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &slot.present;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &slot.render_finished;
    check(gpu.submitToQueue(submit, slot.done), "vkQueueSubmit (present)");

    // 5. Present once the blit is done.
    VkSwapchainKHR swapchain = swapchain_.handle();
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &slot.render_finished;
    present.swapchainCount = 1;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &image_index;
    const VkResult presented = vkQueuePresentKHR(gpu.queue, &present);
    ++frame_index_;
    if (screenshot) {
        check(vkWaitForFences(device_, 1, &slot.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        *screenshot = readScreenshot();
    }
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
        acquired == VK_SUBOPTIMAL_KHR)
        return false;
    check(presented, "vkQueuePresentKHR");
    return true;
}

Screenshot FrameLoop::readScreenshot() const {
    Screenshot shot;
    shot.width = swapchain_.extent().width;
    shot.height = swapchain_.extent().height;
    shot.rgba8.resize(size_t(shot.width) * shot.height * 4);
    std::memcpy(shot.rgba8.data(), readback_bytes_, shot.rgba8.size());
    if (swapchain_.format() == VK_FORMAT_B8G8R8A8_SRGB)
        for (size_t pixel = 0; pixel < shot.rgba8.size(); pixel += 4) std::swap(shot.rgba8[pixel], shot.rgba8[pixel + 2]);
    return shot;
}

}  // namespace gusuku::view
