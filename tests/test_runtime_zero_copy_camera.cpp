// The platform's zero-copy camera (runtime.h, RuntimeOptions::camera_ycbcr_image): the app's two-plane Y'CbCr
// VkImage (G8_B8R8_2PLANE_420_UNORM, what an imported AHardwareBuffer or CVPixelBuffer gives) sampled in place
// through a sampler Y'CbCr conversion gives the composite that the host-plane path gives for the same Y' and CbCr
// bytes, within one code everywhere (the building and the ground ratio included), for BT.601 and BT.709, narrow and
// full range, NV12 and NV21, and with the app's own conversion; a ring of images is read right as it cycles. The
// host-plane path is itself held to an independent CPU decode of the ITU formulas (test_runtime_camera_formats).
// On a device without samplerYcbcrConversion (lavapipe) the runtime refuses by name, and the matching cases skip
// saying so; ctest runs this file on SwiftShader too (tests/drivers/Drivers.cmake), which has the feature. The
// chroma differs from block to block, so a siting error shows: camera_sample.glsl sampling pixel centres instead
// of a quarter pixel in (SwiftShader sites chroma cosited) failed the match by 138-165 codes.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku/synthetic/synthetic_bakeset.h"
#include "test_msaa.h"

namespace gusuku {
namespace {

using testing::makeSyntheticBakeSet;
using testing::syntheticLocalTime;

constexpr uint32_t kWidth = 96, kHeight = 64;
constexpr VkFormat kTwoPlaneFormat = VK_FORMAT_G8_B8R8_2PLANE_420_UNORM;

RuntimeOptions optionsFor(CameraFormat format, YcbcrModel model, YcbcrRange range, bool zero_copy) {
    RuntimeOptions options;
    options.frame_width = kWidth;
    options.frame_height = kHeight;
    options.shadow_map_size = 256;
    options.camera_format = format;
    options.camera_ycbcr_model = model;
    options.camera_ycbcr_range = range;
    options.camera_ycbcr_image = zero_copy;
    options.msaa_samples = testing::testMsaaSamples();
    return options;
}

FrameInput frameLookingAtTheBuilding() {
    FrameInput frame;
    const double focal = 72.0;
    frame.intrinsics = {focal, focal, kWidth / 2.0, kHeight / 2.0, kWidth, kHeight};
    frame.pose = CameraPose::lookingAt({3, -12, 3}, {0, 0, 1});
    frame.utc_unix_seconds = syntheticLocalTime(15, 0);
    frame.weather = Weather::sunny();
    frame.exposure = 0.1f;
    return frame;
}

// Y' per pixel, and a chroma pair per 2 x 2 block that differs from its neighbours' (so a chroma sample taken from
// the wrong block shows), both within the range a camera delivers.
struct Planes {
    std::vector<uint8_t> luma, chroma;  // chroma: kWidth / 2 x kHeight / 2 pairs, in the camera format's order
};
Planes randomPlanes(uint32_t seed) {
    std::mt19937 random(seed);
    Planes planes;
    planes.luma.resize(size_t(kWidth) * kHeight);
    planes.chroma.resize(size_t(kWidth / 2) * (kHeight / 2) * 2);
    for (uint8_t& value : planes.luma) value = uint8_t(40 + random() % 180);
    for (uint8_t& value : planes.chroma) value = uint8_t(88 + random() % 81);
    return planes;
}

bool deviceSamplesYcbcr(const GpuDevice& gpu) {
    VkPhysicalDeviceSamplerYcbcrConversionFeatures ycbcr{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SAMPLER_YCBCR_CONVERSION_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &ycbcr;
    vkGetPhysicalDeviceFeatures2(gpu.physical_device, &features);
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, kTwoPlaneFormat, &properties);
    const VkFormatFeatureFlags siting =
        VK_FORMAT_FEATURE_MIDPOINT_CHROMA_SAMPLES_BIT | VK_FORMAT_FEATURE_COSITED_CHROMA_SAMPLES_BIT;
    return ycbcr.samplerYcbcrConversion && (properties.optimalTilingFeatures & siting) != 0 &&
           (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) != 0;
}

// What an app's imported camera buffer is to Vulkan: a two-plane image, here filled by a copy (the app's import
// would alias the platform's memory instead), left in SHADER_READ_ONLY_OPTIMAL.
class TwoPlaneImage {
public:
    TwoPlaneImage(VulkanContext& context, const Planes& planes) : device_(context.gpu().device) {
        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = kTwoPlaneFormat;
        info.extent = {kWidth, kHeight, 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        checkVk(vkCreateImage(device_, &info, nullptr, &image_), "vkCreateImage (two-plane camera)");
        VkMemoryRequirements requirements{};
        vkGetImageMemoryRequirements(device_, image_, &requirements);
        VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        allocate.allocationSize = requirements.size;
        allocate.memoryTypeIndex =
            context.gpu().findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        checkVk(vkAllocateMemory(device_, &allocate, nullptr, &memory_), "vkAllocateMemory (two-plane camera)");
        checkVk(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory (two-plane camera)");

        GpuBuffer staging(context.gpu(), planes.luma.size() + planes.chroma.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        staging.upload(planes.luma.data(), planes.luma.size());
        staging.upload(planes.chroma.data(), planes.chroma.size(), planes.luma.size());
        context.submitAndWait([&](VkCommandBuffer cmd) {
            recordImageLayoutTransition(cmd, image_, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                                        VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                                        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
            VkBufferImageCopy regions[2]{};
            regions[0].imageSubresource = {VK_IMAGE_ASPECT_PLANE_0_BIT, 0, 0, 1};
            regions[0].imageExtent = {kWidth, kHeight, 1};
            regions[1].bufferOffset = planes.luma.size();
            regions[1].imageSubresource = {VK_IMAGE_ASPECT_PLANE_1_BIT, 0, 0, 1};
            regions[1].imageExtent = {kWidth / 2, kHeight / 2, 1};
            vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 2, regions);
            recordImageLayoutTransition(cmd, image_, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                                        VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
        });
    }
    ~TwoPlaneImage() {
        vkDestroyImage(device_, image_, nullptr);
        vkFreeMemory(device_, memory_, nullptr);
    }
    TwoPlaneImage(const TwoPlaneImage&) = delete;
    TwoPlaneImage& operator=(const TwoPlaneImage&) = delete;
    VkImage handle() const { return image_; }

private:
    VkDevice device_;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
};

// One bake set for every runtime the file opens (making it is CPU time SwiftShader's runs can spare).
const BakeSetData& bakeSet() {
    static const BakeSetData bake_set = makeSyntheticBakeSet();
    return bake_set;
}

int largestDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    int largest = 0;
    for (size_t index = 0; index < a.size(); ++index) largest = std::max(largest, std::abs(int(a[index]) - int(b[index])));
    return largest;
}

class ZeroCopyCamera : public testing::GpuTest {
protected:
    void requireTheFeature() {
        if (!deviceSamplesYcbcr(context().gpu()))
            GTEST_SKIP() << context().deviceDescription() << " lacks samplerYcbcrConversion (or "
                         << "G8_B8R8_2PLANE_420_UNORM with midpoint or cosited chroma): the zero-copy camera is "
                            "refused there (RefusedByNameWithoutTheFeature); run it on SwiftShader "
                            "(ctest -R swiftshader_test_runtime_zero_copy_camera)";
    }
    std::vector<uint8_t> renderHostPlanes(const RuntimeOptions& options, const Planes& planes) {
        std::unique_ptr<Runtime> runtime = Runtime::open(context(), bakeSet(), options);
        FrameInput frame = frameLookingAtTheBuilding();
        frame.camera_luma = planes.luma.data();
        frame.camera_chroma = planes.chroma.data();
        std::vector<uint8_t> composite(size_t(kWidth) * kHeight * 4);
        runtime->renderFrame(frame, composite.data());
        return composite;
    }
    std::vector<uint8_t> renderImage(Runtime& runtime, VkImage image) {
        FrameInput frame = frameLookingAtTheBuilding();
        frame.camera_image = image;
        frame.camera_image_format = kTwoPlaneFormat;
        std::vector<uint8_t> composite(size_t(kWidth) * kHeight * 4);
        runtime.renderFrame(frame, composite.data());
        return composite;
    }
};

struct ZeroCopyCase {
    const char* name;
    CameraFormat format;
    YcbcrModel model;
    YcbcrRange range;
    bool app_conversion;  // the app's own conversion of model and range; the options say BT.601 narrow
};

class ZeroCopyCameraFormats : public ZeroCopyCamera, public ::testing::WithParamInterface<ZeroCopyCase> {};

// Each case opens two runtimes (each open and first frame costs about a second of CPU on SwiftShader), so one
// runtime of each case checks more than the match: a ring of three images cycled twice reads each image's own
// pixels (the views' sets are written once, as each is met), and a frame of host planes or another image format
// is refused naming the field. The app's conversion case proves the conversion is the one used: the options'
// model and range, left at BT.601 narrow, would give another composite.
TEST_P(ZeroCopyCameraFormats, MatchesTheHostPlanesWithinOneCode) {
    requireTheFeature();
    if (IsSkipped()) return;  // GTEST_SKIP in a helper returns from the helper only
    const ZeroCopyCase& test_case = GetParam();
    const VkDevice device = context().gpu().device;
    VkSamplerYcbcrConversion conversion = VK_NULL_HANDLE;
    RuntimeOptions options = optionsFor(test_case.format, test_case.model, test_case.range, true);
    if (test_case.app_conversion) {
        VkFormatProperties properties{};
        vkGetPhysicalDeviceFormatProperties(context().gpu().physical_device, kTwoPlaneFormat, &properties);
        VkSamplerYcbcrConversionCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_YCBCR_CONVERSION_CREATE_INFO};
        info.format = kTwoPlaneFormat;
        info.ycbcrModel = test_case.model == YcbcrModel::kBt709 ? VK_SAMPLER_YCBCR_MODEL_CONVERSION_YCBCR_709
                                                                : VK_SAMPLER_YCBCR_MODEL_CONVERSION_YCBCR_601;
        info.ycbcrRange = test_case.range == YcbcrRange::kFull ? VK_SAMPLER_YCBCR_RANGE_ITU_FULL
                                                               : VK_SAMPLER_YCBCR_RANGE_ITU_NARROW;
        info.xChromaOffset = info.yChromaOffset =
            (properties.optimalTilingFeatures & VK_FORMAT_FEATURE_MIDPOINT_CHROMA_SAMPLES_BIT)
                ? VK_CHROMA_LOCATION_MIDPOINT
                : VK_CHROMA_LOCATION_COSITED_EVEN;
        info.chromaFilter = VK_FILTER_NEAREST;
        ASSERT_EQ(vkCreateSamplerYcbcrConversion(device, &info, nullptr, &conversion), VK_SUCCESS);
        options = optionsFor(test_case.format, YcbcrModel::kBt601, YcbcrRange::kNarrow, true);
        options.camera_ycbcr_conversion = conversion;
        options.camera_ycbcr_chroma_filter = VK_FILTER_NEAREST;
    }
    std::vector<Planes> ring_planes;
    std::vector<std::unique_ptr<TwoPlaneImage>> ring;
    for (uint32_t seed : {11u, 12u, 13u}) {
        ring_planes.push_back(randomPlanes(seed));
        ring.push_back(std::make_unique<TwoPlaneImage>(context(), ring_planes.back()));
    }
    std::unique_ptr<Runtime> runtime = Runtime::open(context(), bakeSet(), options);
    std::vector<std::vector<uint8_t>> first_cycle;
    for (const auto& image : ring) first_cycle.push_back(renderImage(*runtime, image->handle()));
    for (size_t index = 0; index < ring.size(); ++index)
        EXPECT_EQ(renderImage(*runtime, ring[index]->handle()), first_cycle[index]) << "ring image " << index;
    EXPECT_GT(largestDifference(first_cycle[0], first_cycle[1]), 10) << "the ring's images should differ";

    const std::vector<uint8_t> from_host =
        renderHostPlanes(optionsFor(test_case.format, test_case.model, test_case.range, false), ring_planes[0]);
    EXPECT_LE(largestDifference(first_cycle[0], from_host), 1) << test_case.name;

    auto messageOf = [&](const FrameInput& frame) {
        try {
            runtime->renderFrame(frame, nullptr);
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), RuntimeErrorCode::kInvalidFrame);
            return std::string(error.what());
        }
        return std::string("(no error)");
    };
    FrameInput frame = frameLookingAtTheBuilding();
    frame.camera_luma = ring_planes[0].luma.data();
    frame.camera_chroma = ring_planes[0].chroma.data();
    EXPECT_NE(messageOf(frame).find("camera_image: null, but options.camera_ycbcr_image"), std::string::npos)
        << messageOf(frame);
    frame = frameLookingAtTheBuilding();
    frame.camera_image = ring[0]->handle();
    frame.camera_image_format = VK_FORMAT_R8G8B8A8_UNORM;
    EXPECT_NE(messageOf(frame).find("takes G8_B8R8_2PLANE_420_UNORM"), std::string::npos) << messageOf(frame);
    runtime.reset();  // the runtime's views go before the images and the conversion
    ring.clear();
    if (conversion != VK_NULL_HANDLE) vkDestroySamplerYcbcrConversion(device, conversion, nullptr);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ZeroCopyCameraFormats,
    ::testing::Values(
        ZeroCopyCase{"nv12_bt601_narrow", CameraFormat::kNv12, YcbcrModel::kBt601, YcbcrRange::kNarrow, false},
        ZeroCopyCase{"nv21_bt601_full", CameraFormat::kNv21, YcbcrModel::kBt601, YcbcrRange::kFull, false},
        ZeroCopyCase{"nv12_bt709_narrow", CameraFormat::kNv12, YcbcrModel::kBt709, YcbcrRange::kNarrow, false},
        ZeroCopyCase{"nv12_bt709_full_apps_conversion", CameraFormat::kNv12, YcbcrModel::kBt709, YcbcrRange::kFull,
                     true}),
    [](const ::testing::TestParamInfo<ZeroCopyCase>& info) { return std::string(info.param.name); });

// Options that cannot mean anything, on any device; and, on a device without the feature (lavapipe), the open
// refused naming the feature and what to do instead.
TEST_F(ZeroCopyCamera, RefusedByNameWithoutTheFeature) {
    auto openMessage = [&](const RuntimeOptions& options, RuntimeErrorCode expected) {
        try {
            Runtime::open(context(), bakeSet(), options);
        } catch (const RuntimeError& error) {
            EXPECT_EQ(error.code(), expected) << error.what();
            return std::string(error.what());
        }
        return std::string("(opened)");
    };
    RuntimeOptions rgba = optionsFor(CameraFormat::kRgba8, YcbcrModel::kBt601, YcbcrRange::kNarrow, true);
    EXPECT_NE(openMessage(rgba, RuntimeErrorCode::kInvalidFrame).find("options.camera_ycbcr_image: needs"),
              std::string::npos);
    RuntimeOptions filter = optionsFor(CameraFormat::kNv12, YcbcrModel::kBt601, YcbcrRange::kNarrow, true);
    filter.camera_ycbcr_chroma_filter = VK_FILTER_CUBIC_IMG;
    EXPECT_NE(openMessage(filter, RuntimeErrorCode::kInvalidFrame).find("options.camera_ycbcr_chroma_filter"),
              std::string::npos);
    if (deviceSamplesYcbcr(context().gpu()))
        GTEST_SKIP() << context().deviceDescription() << " has samplerYcbcrConversion: the refusal is tested on a "
                                                         "device without it (lavapipe)";
    const std::string message = openMessage(
        optionsFor(CameraFormat::kNv12, YcbcrModel::kBt709, YcbcrRange::kFull, true), RuntimeErrorCode::kDevice);
    EXPECT_NE(message.find("options.camera_ycbcr_image: "), std::string::npos) << message;
    EXPECT_NE(message.find("samplerYcbcrConversion"), std::string::npos) << message;
    EXPECT_NE(message.find("host planes"), std::string::npos) << message;
}

}  // namespace
}  // namespace gusuku
