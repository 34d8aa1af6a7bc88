#pragma once
// The platform's zero-copy camera (runtime.h, RuntimeOptions::camera_ycbcr_image; docs/runtime.md, "The zero-copy
// camera"): the app's two-plane Y'CbCr image (an imported AHardwareBuffer or CVPixelBuffer) read in place through
// a sampler Y'CbCr conversion. This holds what the device must have for it and the conversion and immutable
// sampler, made once when the runtime opens (a frame makes none). Private to gusuku_runtime.

#include <string>

#include <vulkan/vulkan.h>

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// The format of the app's camera images: two planes, Y' and interleaved Cb Cr at half size each way.
constexpr VkFormat kYcbcrCameraFormat = VK_FORMAT_G8_B8R8_2PLANE_420_UNORM;
constexpr const char* kYcbcrCameraFormatName = "G8_B8R8_2PLANE_420_UNORM";
/// Descriptors one combined image sampler with a conversion may take in a pool: at most one per plane (the
/// driver's combinedImageSamplerDescriptorCount, never above the format's three planes).
constexpr uint32_t kMaxYcbcrDescriptorsPerSampler = 3;

/// Throws RuntimeError kDevice naming what the device lacks for the zero-copy camera: Vulkan 1.1 (instance and
/// device), the samplerYcbcrConversion feature, and G8_B8R8_2PLANE_420_UNORM sampled with optimal tiling, with
/// midpoint or cosited chroma samples, and filtered linearly by a conversion where options say linear.
void checkYcbcrCameraSupport(const GpuDevice& gpu, const RuntimeOptions& options);

/// The conversion (the app's, options.camera_ycbcr_conversion, or one made here from the options' model, range
/// and chroma order, nearest chroma, midpoint siting where the format has it, else cosited) and the sampler that
/// carries it, immutable in the camera's set layout. Destroys what it made, never the app's conversion.
class YcbcrCameraSampler {
public:
    YcbcrCameraSampler(const GpuDevice& gpu, const RuntimeOptions& options);
    ~YcbcrCameraSampler();
    YcbcrCameraSampler(const YcbcrCameraSampler&) = delete;
    YcbcrCameraSampler& operator=(const YcbcrCameraSampler&) = delete;

    VkSamplerYcbcrConversion conversion() const { return conversion_; }
    const VkSampler* sampler() const { return &sampler_; }  // a pointer, as pImmutableSamplers takes it
    bool filtersLinearly() const { return filter_ == VK_FILTER_LINEAR; }

private:
    void destroy() noexcept;

    VkDevice device_;
    VkSamplerYcbcrConversion own_conversion_ = VK_NULL_HANDLE;
    VkSamplerYcbcrConversion conversion_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
    VkFilter filter_ = VK_FILTER_NEAREST;
};

}  // namespace gusuku::runtime_detail
