#pragma once
// gusuku-view's frame loop: the GPU-resident path an AR app runs, and the example to copy (docs/runtime.md, "The
// frame on the GPU"). Per frame, with two frames in flight:
//   1. wait for this slot's fence (its semaphores and staging buffer are free again);
//   2. when a new camera frame came, copy it into the app's camera VkImage and signal `camera_ready`;
//   3. Runtime::renderFrame with no output bytes: the camera in as that image (sampled in place), waiting on
//      `camera_ready`, signalling `composite_ready`; nothing is read back and nothing waits;
//   4. acquire a swapchain image (`image_acquired`), blit Runtime::compositeImage() onto it (scaled to fit,
//      letterboxed), submit waiting on both semaphores, signal `render_finished` and the slot's fence;
//   5. present, waiting on `render_finished`.
// The camera here is a still background uploaded from host bytes; a phone's camera image would come with its
// own acquire semaphore, waited on in step 3 instead of `camera_ready`.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "gusuku/runtime/runtime.h"
#include "view_device.h"
#include "view_overlay.h"
#include "view_swapchain.h"

namespace gusuku::view {

/// The window's pixels of one presented frame, RGBA8 (sRGB), row 0 at the top.
struct Screenshot {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;
};

class FrameLoop {
public:
    /// Frames the app records while the GPU works on the previous one; the runtime's own frames_in_flight is the
    /// same (RuntimeOptions' default), so neither waits on the other.
    static constexpr uint32_t kFramesInFlight = 2;

    /// A loop presenting `runtime`'s composites (camera_width x camera_height, the runtime's frame size) to the
    /// swapchain. The runtime may be replaced (setRuntime) after waitIdle().
    FrameLoop(const WindowDevice& window, Swapchain& swapchain, Runtime& runtime, uint32_t camera_width,
              uint32_t camera_height);
    ~FrameLoop();
    FrameLoop(const FrameLoop&) = delete;
    FrameLoop& operator=(const FrameLoop&) = delete;

    /// The next frame's camera (width x height x 4 bytes, sRGB RGBA): copied into the camera image by the next
    /// drawFrame, on the GPU, after the frames that read the old one.
    void setCamera(const std::vector<uint8_t>& rgba8);

    /// The overlay copied onto the top-left of each presented image from the next drawFrame on, clipped to
    /// kOverlayMaxWidth x kOverlayMaxHeight and to the window; an empty image draws none. It goes on after a
    /// screenshot's read-back, so screenshots hold the composite alone.
    void setOverlay(OverlayImage overlay) { overlay_ = std::move(overlay); }
    static constexpr uint32_t kOverlayMaxWidth = 1024, kOverlayMaxHeight = 160;

    /// Draws and presents one frame; `frame` is complete but for the camera and the semaphores, which this adds.
    /// False when the swapchain is out of date (the caller recreates it and calls again). With `screenshot` set,
    /// also reads the presented image back (a fence wait; for tests and F12 only).
    bool drawFrame(const FrameInput& frame, FrameInfo& info, Screenshot* screenshot = nullptr);

    /// Blocks until the GPU has finished every frame submitted (before a swapchain or runtime is replaced).
    void waitIdle();
    void setRuntime(Runtime& runtime) { runtime_ = &runtime; }
    VkImage cameraImage() const { return camera_image_; }

private:
    struct Slot {
        VkCommandBuffer upload = VK_NULL_HANDLE, present = VK_NULL_HANDLE;
        VkFence done = VK_NULL_HANDLE;  ///< signalled when the slot's last present submission finished
        VkSemaphore camera_ready = VK_NULL_HANDLE, composite_ready = VK_NULL_HANDLE;
        VkSemaphore image_acquired = VK_NULL_HANDLE, render_finished = VK_NULL_HANDLE;
        VkBuffer staging = VK_NULL_HANDLE;  ///< the camera bytes on their way to the camera image
        VkDeviceMemory staging_memory = VK_NULL_HANDLE;
        void* staging_bytes = nullptr;
        VkBuffer overlay = VK_NULL_HANDLE;  ///< the overlay's pixels for this slot's present
        VkDeviceMemory overlay_memory = VK_NULL_HANDLE;
        void* overlay_bytes = nullptr;
    };
    void createSlot(Slot& slot);
    void destroySlot(Slot& slot);
    void createCameraImage();
    void recordCameraUpload(const Slot& slot);
    void recordPresent(const Slot& slot, VkImage swapchain_image, bool read_back);
    void recordOverlay(const Slot& slot, VkImage swapchain_image);
    void ensureReadback(VkDeviceSize bytes);
    Screenshot readScreenshot() const;
    VkBuffer makeBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage, VkDeviceMemory& memory, void** mapped);

    const WindowDevice& window_;
    VkDevice device_;
    Swapchain& swapchain_;
    Runtime* runtime_;
    uint32_t camera_width_, camera_height_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<Slot, kFramesInFlight> slots_;
    uint32_t frame_index_ = 0;
    VkImage camera_image_ = VK_NULL_HANDLE;  ///< R8G8B8A8_UNORM holding sRGB bytes, SAMPLED | TRANSFER_DST
    VkDeviceMemory camera_memory_ = VK_NULL_HANDLE;
    bool camera_written_ = false;       ///< the image holds a frame (its layout is SHADER_READ_ONLY_OPTIMAL)
    std::vector<uint8_t> pending_camera_;  ///< a camera frame for the next drawFrame to upload (empty: none)
    VkBuffer readback_ = VK_NULL_HANDLE;
    VkDeviceMemory readback_memory_ = VK_NULL_HANDLE;
    void* readback_bytes_ = nullptr;
    VkDeviceSize readback_size_ = 0;
    OverlayImage overlay_;
};

}  // namespace gusuku::view
