// The zero-copy camera's device needs, conversion and sampler (camera_ycbcr.h).

#include "camera_ycbcr.h"

#include <string>

namespace gusuku::runtime_detail {

namespace {

VkFormatFeatureFlags optimalFeatures(const GpuDevice& gpu) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, kYcbcrCameraFormat, &properties);
    return properties.optimalTilingFeatures;
}

}  // namespace

void checkYcbcrCameraSupport(const GpuDevice& gpu, const RuntimeOptions& options) {
    const std::string device = std::string("this device (") + gpu.properties.deviceName + ") ";
    const std::string otherwise = ": give the camera as host planes (camera_luma, camera_chroma) with "
                                  "options.camera_ycbcr_image false";
    auto fail = [](const std::string& what) {
        throw RuntimeError(RuntimeErrorCode::kDevice, "options.camera_ycbcr_image: " + what);
    };
    // Conversions are Vulkan 1.1 core; a 1.0 instance cannot even ask for the feature.
    if (gpu.instance_api_version < VK_API_VERSION_1_1 || gpu.properties.apiVersion < VK_API_VERSION_1_1)
        fail("the sampler Y'CbCr conversion needs a Vulkan 1.1 instance and device (samplerYcbcrConversion)" +
             otherwise);
    VkPhysicalDeviceSamplerYcbcrConversionFeatures ycbcr{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SAMPLER_YCBCR_CONVERSION_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &ycbcr;
    vkGetPhysicalDeviceFeatures2(gpu.physical_device, &features);
    if (!ycbcr.samplerYcbcrConversion)
        fail(device + "lacks the samplerYcbcrConversion feature (Vulkan 1.1) the zero-copy camera samples with" +
             otherwise);
    const VkFormatFeatureFlags have = optimalFeatures(gpu);
    const std::string format = std::string(" for ") + kYcbcrCameraFormatName + " (optimal tiling)";
    if (!(have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) fail(device + "lacks SAMPLED_IMAGE" + format + otherwise);
    if (!(have & (VK_FORMAT_FEATURE_MIDPOINT_CHROMA_SAMPLES_BIT | VK_FORMAT_FEATURE_COSITED_CHROMA_SAMPLES_BIT)))
        fail(device + "lacks both MIDPOINT_CHROMA_SAMPLES and COSITED_CHROMA_SAMPLES" + format + otherwise);
    const bool linear = options.camera_ycbcr_conversion != VK_NULL_HANDLE &&
                        options.camera_ycbcr_chroma_filter == VK_FILTER_LINEAR;
    if (linear && !(have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_YCBCR_CONVERSION_LINEAR_FILTER_BIT))
        fail(device + "lacks SAMPLED_IMAGE_YCBCR_CONVERSION_LINEAR_FILTER" + format +
             ", which options.camera_ycbcr_chroma_filter LINEAR needs: make the conversion with VK_FILTER_NEAREST");
}

YcbcrCameraSampler::YcbcrCameraSampler(const GpuDevice& gpu, const RuntimeOptions& options) : device_(gpu.device) {
    try {
        conversion_ = options.camera_ycbcr_conversion;
        if (conversion_ != VK_NULL_HANDLE) {
            filter_ = options.camera_ycbcr_chroma_filter;
        } else {
            VkSamplerYcbcrConversionCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_YCBCR_CONVERSION_CREATE_INFO};
            info.format = kYcbcrCameraFormat;
            info.ycbcrModel = options.camera_ycbcr_model == YcbcrModel::kBt709
                                  ? VK_SAMPLER_YCBCR_MODEL_CONVERSION_YCBCR_709
                                  : VK_SAMPLER_YCBCR_MODEL_CONVERSION_YCBCR_601;
            info.ycbcrRange = options.camera_ycbcr_range == YcbcrRange::kFull ? VK_SAMPLER_YCBCR_RANGE_ITU_FULL
                                                                                : VK_SAMPLER_YCBCR_RANGE_ITU_NARROW;
            // G8_B8R8's plane 1 holds B (Cb) then R (Cr); NV21's bytes are Cr then Cb, so R and B swap.
            const bool swapped = options.camera_format == CameraFormat::kNv21;
            info.components = {swapped ? VK_COMPONENT_SWIZZLE_B : VK_COMPONENT_SWIZZLE_IDENTITY,
                               VK_COMPONENT_SWIZZLE_IDENTITY,
                               swapped ? VK_COMPONENT_SWIZZLE_R : VK_COMPONENT_SWIZZLE_IDENTITY,
                               VK_COMPONENT_SWIZZLE_IDENTITY};
            // Nearest chroma: camera_sample.glsl samples where either siting gives each 2 x 2 block its own
            // chroma sample, the host planes' rule, so the two routes give one composite.
            const VkChromaLocation siting = (optimalFeatures(gpu) & VK_FORMAT_FEATURE_MIDPOINT_CHROMA_SAMPLES_BIT)
                                                ? VK_CHROMA_LOCATION_MIDPOINT
                                                : VK_CHROMA_LOCATION_COSITED_EVEN;
            info.xChromaOffset = info.yChromaOffset = siting;
            info.chromaFilter = VK_FILTER_NEAREST;
            checkVk(vkCreateSamplerYcbcrConversion(device_, &info, nullptr, &own_conversion_),
                    "vkCreateSamplerYcbcrConversion (camera)");
            conversion_ = own_conversion_;
        }
        VkSamplerYcbcrConversionInfo conversion{VK_STRUCTURE_TYPE_SAMPLER_YCBCR_CONVERSION_INFO};
        conversion.conversion = conversion_;
        // Vulkan asks a conversion's sampler to filter as its chroma (no separate reconstruction filter is
        // assumed), clamp to the edge and take normalised coordinates.
        VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        sampler.pNext = &conversion;
        sampler.magFilter = sampler.minFilter = filter_;
        sampler.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
        sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        checkVk(vkCreateSampler(device_, &sampler, nullptr, &sampler_), "vkCreateSampler (camera, Y'CbCr)");
    } catch (...) {
        destroy();
        throw;
    }
}

YcbcrCameraSampler::~YcbcrCameraSampler() { destroy(); }

void YcbcrCameraSampler::destroy() noexcept {
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
    if (own_conversion_ != VK_NULL_HANDLE) vkDestroySamplerYcbcrConversion(device_, own_conversion_, nullptr);
    sampler_ = VK_NULL_HANDLE;
    own_conversion_ = conversion_ = VK_NULL_HANDLE;
}

}  // namespace gusuku::runtime_detail
