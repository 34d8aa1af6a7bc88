// The runtime on the app's own device keeps the promises runtime.h makes to an AR app, each under validation:
//   - a temporary GpuDevice is safe (the runtime copies it);
//   - GPU-resident frames (no output bytes) with frames_in_flight 2 and 3, each signalling a binary semaphore
//     the app waits on before copying compositeImage() in its own submission, give the composites the
//     host-bytes path gives for the same frames, byte for byte;
//   - a timeline semaphore the frame waits on holds the frame back until the app signals it, and the value the
//     frame signals arrives with the composite written.

#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app_owned_device.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"
#include "test_msaa.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 160, kHeight = 120;
constexpr size_t kFrameBytes = size_t(kWidth) * kHeight * 4;

RuntimeOptions smallOptions(uint32_t frames_in_flight = 2) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 512;
    options.frames_in_flight = frames_in_flight;
    options.msaa_samples = testing::testMsaaSamples();
    return options;
}

std::vector<uint8_t> noiseImage(uint32_t seed) {
    std::vector<uint8_t> image(kFrameBytes);
    std::mt19937 random(seed);
    for (size_t index = 0; index < image.size(); ++index) image[index] = index % 4 == 3 ? 255 : uint8_t(random());
    return image;
}

// Frame `index` of a short sequence: the camera walks and the sun moves, so every frame differs.
FrameInput frameNumber(int index, const std::vector<uint8_t>& camera) {
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = {120.0, 120.0, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = CameraPose::lookingAt({3.0 + 0.3 * index, -12, 3}, {0, 0, 1});
    frame.utc_unix_seconds = syntheticLocalTime(14, 0) + 600.0 * index;
    frame.weather = Weather::sunny();
    frame.exposure = 0.1f;
    return frame;
}

// The app side: its command pool, and a submission that waits on `wait` (a binary semaphore, or a timeline one
// at wait_value) and copies `image` (TRANSFER_SRC_OPTIMAL) into `buffer`.
class AppQueue {
public:
    explicit AppQueue(testing::AppOwnedDevice& app) : app_(app) {
        VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = app.queue_family;
        vkCreateCommandPool(app.device, &pool, nullptr, &pool_);
    }
    ~AppQueue() {
        vkDeviceWaitIdle(app_.device);
        for (VkSemaphore semaphore : semaphores_) vkDestroySemaphore(app_.device, semaphore, nullptr);
        vkDestroyCommandPool(app_.device, pool_, nullptr);
    }
    VkSemaphore makeSemaphore(bool timeline) {
        VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        if (timeline) info.pNext = &type;
        VkSemaphore semaphore = VK_NULL_HANDLE;
        vkCreateSemaphore(app_.device, &info, nullptr, &semaphore);
        semaphores_.push_back(semaphore);
        return semaphore;
    }
    void copyAfter(VkSemaphore wait, const uint64_t* wait_value, VkImage image, const GpuBuffer& buffer) {
        VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        allocate.commandPool = pool_;
        allocate.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        vkAllocateCommandBuffers(app_.device, &allocate, &cmd);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cmd, &begin);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {kWidth, kHeight, 1};
        vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.handle(), 1, &region);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
        vkEndCommandBuffer(cmd);
        const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
        timeline.waitSemaphoreValueCount = 1;
        timeline.pWaitSemaphoreValues = wait_value;
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        if (wait_value != nullptr) submit.pNext = &timeline;
        submit.waitSemaphoreCount = 1;
        submit.pWaitSemaphores = &wait;
        submit.pWaitDstStageMask = &stage;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        std::lock_guard<std::mutex> lock(app_.queue_mutex);
        vkQueueSubmit(app_.queue, 1, &submit, VK_NULL_HANDLE);
    }

private:
    testing::AppOwnedDevice& app_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::vector<VkSemaphore> semaphores_;
};

GpuDevice describe(testing::AppOwnedDevice& app) {
    return GpuDevice::describe(app.instance, app.physical_device, app.device, app.queue, app.queue_family,
                               &app.queue_mutex, app.api_version);
}

// Each mode needs only what it uses: on a Vulkan 1.0 instance (no subgroup query allowed) the runtime opens,
// the default frame (colour match off) equals the headless one, and a frame asking for a match is refused by name.
TEST(RuntimeAppDevicePromises, AVulkan10InstanceRendersTheDefaultFrame) {
    testing::AppOwnedDevice app(VK_API_VERSION_1_0);
    {
        const std::vector<uint8_t> camera = noiseImage(3);
        std::vector<uint8_t> expected(kFrameBytes), composite(kFrameBytes);
        Runtime::openHeadless(makeSyntheticBakeSet(), smallOptions())->renderFrame(frameNumber(2, camera),
                                                                                     expected.data());
        std::unique_ptr<Runtime> runtime = Runtime::open(describe(app), makeSyntheticBakeSet(), smallOptions());
        runtime->renderFrame(frameNumber(2, camera), composite.data());
        EXPECT_EQ(composite, expected);
        FrameInput matched = frameNumber(2, camera);
        matched.colour_match = ColourMatch::kPaper;
        try {
            runtime->renderFrame(matched, composite.data());
            ADD_FAILURE() << "a colour match on a Vulkan 1.0 instance should be refused";
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
            EXPECT_NE(std::string(error.what()).find("colour_match: needs subgroup arithmetic"), std::string::npos)
                << error.what();
        }
    }
    app.destroyDevice();
    for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
}

TEST(RuntimeAppDevicePromises, ATemporaryGpuDeviceIsCopied) {
    testing::AppOwnedDevice app;
    {
        const std::vector<uint8_t> camera = noiseImage(2);
        std::vector<uint8_t> expected(kFrameBytes), composite(kFrameBytes);
        Runtime::openHeadless(makeSyntheticBakeSet(), smallOptions())->renderFrame(frameNumber(0, camera),
                                                                                     expected.data());
        // The device description lives on the heap and is wiped and freed before the first frame.
        auto temporary = std::make_unique<GpuDevice>(describe(app));
        std::unique_ptr<Runtime> runtime = Runtime::open(*temporary, makeSyntheticBakeSet(), smallOptions());
        std::memset(static_cast<void*>(temporary.get()), 0, sizeof(GpuDevice));
        temporary.reset();
        runtime->renderFrame(frameNumber(0, camera), composite.data());
        EXPECT_EQ(composite, expected);
    }
    app.destroyDevice();
    for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
}

class RuntimeInFlight : public ::testing::TestWithParam<uint32_t> {};

TEST_P(RuntimeInFlight, ResidentFramesWithSemaphoresGiveTheHostPathsComposites) {
    constexpr int kFrames = 6;
    testing::AppOwnedDevice app;
    {
        const GpuDevice gpu = describe(app);
        const std::vector<uint8_t> camera = noiseImage(4);
        std::unique_ptr<Runtime> reference = Runtime::open(gpu, makeSyntheticBakeSet(), smallOptions(1));
        std::unique_ptr<Runtime> runtime = Runtime::open(gpu, makeSyntheticBakeSet(), smallOptions(GetParam()));
        AppQueue app_queue(app);
        std::vector<GpuBuffer> copies;
        for (int index = 0; index < kFrames; ++index) copies.emplace_back(gpu, kFrameBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        for (int index = 0; index < kFrames; ++index) {
            const VkSemaphore done = app_queue.makeSemaphore(false);
            FrameInput frame = frameNumber(index, camera);
            frame.sync.signal_count = 1;
            frame.sync.signal_semaphores = &done;
            runtime->renderFrame(frame, nullptr);
            app_queue.copyAfter(done, nullptr, runtime->compositeImage(), copies[size_t(index)]);
        }
        runtime->waitIdle();
        vkDeviceWaitIdle(app.device);
        for (int index = 0; index < kFrames; ++index) {
            std::vector<uint8_t> expected(kFrameBytes);
            reference->renderFrame(frameNumber(index, camera), expected.data());
            EXPECT_EQ(copies[size_t(index)].downloadVector<uint8_t>(kFrameBytes), expected) << "frame " << index;
        }
    }
    app.destroyDevice();
    for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
}

INSTANTIATE_TEST_SUITE_P(FramesInFlight, RuntimeInFlight, ::testing::Values(2u, 3u));

TEST(RuntimeAppDevicePromises, TimelineSemaphoresOrderTheFrame) {
    testing::AppOwnedDevice app(VK_API_VERSION_1_2, true);
    {
        const GpuDevice gpu = describe(app);
        const std::vector<uint8_t> camera = noiseImage(6);
        std::unique_ptr<Runtime> runtime = Runtime::open(gpu, makeSyntheticBakeSet(), smallOptions());
        AppQueue app_queue(app);
        const VkSemaphore timeline = app_queue.makeSemaphore(true);
        const uint64_t camera_ready = 1, composite_done = 2;
        FrameInput frame = frameNumber(1, camera);
        frame.sync.wait_count = 1;
        frame.sync.wait_semaphores = &timeline;
        frame.sync.wait_values = &camera_ready;
        frame.sync.signal_count = 1;
        frame.sync.signal_semaphores = &timeline;
        frame.sync.signal_values = &composite_done;
        runtime->renderFrame(frame, nullptr);  // returns at once: the GPU waits, the host does not
        GpuBuffer copy(gpu, kFrameBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        app_queue.copyAfter(timeline, &composite_done, runtime->compositeImage(), copy);
        uint64_t value = 99;
        vkGetSemaphoreCounterValue(app.device, timeline, &value);
        EXPECT_EQ(value, 0u) << "the frame must not run before the app signals the camera ready";
        VkSemaphoreSignalInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
        signal.semaphore = timeline;
        signal.value = camera_ready;
        vkSignalSemaphore(app.device, &signal);
        VkSemaphoreWaitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO};
        wait.semaphoreCount = 1;
        wait.pSemaphores = &timeline;
        wait.pValues = &composite_done;
        EXPECT_EQ(vkWaitSemaphores(app.device, &wait, 10'000'000'000ull), VK_SUCCESS);
        vkDeviceWaitIdle(app.device);
        std::vector<uint8_t> expected(kFrameBytes);
        frame.sync = {};
        runtime->renderFrame(frame, expected.data());
        EXPECT_EQ(copy.downloadVector<uint8_t>(kFrameBytes), expected);
    }
    app.destroyDevice();
    for (const std::string& message : app.messages()) ADD_FAILURE() << "validation: " << message;
}

}  // namespace
}  // namespace gusuku
