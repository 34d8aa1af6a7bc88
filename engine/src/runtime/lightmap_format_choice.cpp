// The lightmaps' format (lightmap_format_choice.h), from the format table's rows.

#include "lightmap_format_choice.h"

#include <stdexcept>
#include <string>

#include "runtime_scene.h"

namespace gusuku::runtime_detail {
namespace {

// The table names Vulkan's feature bits without Vulkan's headers.
static_assert(formats::kFeatureSampledImage == VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT &&
              formats::kFeatureTransferDst == VK_FORMAT_FEATURE_TRANSFER_DST_BIT &&
              formats::kFeatureFilterLinear == VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
static_assert(formats::kAutoCEnum == int(LightmapFormat::kAuto));

// Why the bake set's blocks of `row` cannot be drawn as they are, or "" (and "" for the texel formats, which the
// runtime makes from the float lightmaps). The shaders multiply every stored lightmap texel by one irradiance
// scale (runtime_interface.h); the blocks were encoded at the pack's, so the two must agree (both 1 unless an
// irradiance exceeds 30000, which no bench site comes near).
std::string blocksProblem(const BakeSetData& bake_set, const formats::FormatRow& row) {
    if (!formats::isBlockCodec(row.codec)) return "";
    if (bake_set.slots.empty() || bake_set.slots[0].building_blocks.count(row.vk_format) == 0)
        return std::string("the bake set has no ") + row.name + " lightmaps (slots[0].building_blocks has no " +
               row.vk_name + ": load the runtime pack, which gusuku-bake writes them into)";
    const float runtime_scale = irradianceScaleOf(bake_set.slots);
    if (runtime_scale != bake_set.building_blocks_scale)
        return std::string("the bake set's ") + row.name + " lightmaps are stored at scale " +
               std::to_string(bake_set.building_blocks_scale) + ", not the runtime's irradiance scale " +
               std::to_string(runtime_scale);
    return "";
}

bool featureEnabled(const RuntimeOptions& options, formats::DeviceFeature feature) {
    switch (feature) {
        case formats::DeviceFeature::kAstcHdr: return options.texture_compression_astc_hdr;
        case formats::DeviceFeature::kAstcLdr: return options.texture_compression_astc_ldr;
        case formats::DeviceFeature::kCore: break;
    }
    return true;
}

// "textureCompressionASTC_HDR enabled on the device, and options.texture_compression_astc_hdr is false".
std::string featureMissing(formats::DeviceFeature feature) {
    return feature == formats::DeviceFeature::kAstcHdr
               ? "textureCompressionASTC_HDR enabled on the device, and options.texture_compression_astc_hdr is false"
               : "textureCompressionASTC_LDR enabled on the device, and options.texture_compression_astc_ldr is false";
}

}  // namespace

const formats::FormatRow& lightmapRow(LightmapFormat format) {
    const formats::FormatRow* row = formats::findLightmapFormat(int(format));
    if (row == nullptr) throw std::logic_error("lightmapRow: LightmapFormat " + std::to_string(int(format)) + " has no row");
    return *row;
}

bool deviceSamples(const GpuDevice& gpu, const formats::FormatRow& row) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, VkFormat(row.vk_format), &properties);
    return (properties.optimalTilingFeatures & row.format_features) == row.format_features;
}

LightmapFormat chooseLightmapFormat(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options) {
    if (options.lightmap_format == LightmapFormat::kAuto) {
        const formats::FormatRow* chosen = nullptr;
        for (const formats::FormatRow& row : formats::kFormatRows) {
            if (row.family != formats::FormatFamily::kLightmap || row.auto_rank == 0) continue;
            if (chosen != nullptr && chosen->auto_rank <= row.auto_rank) continue;
            // A core format is taken without a query: checkDeviceRequirements names what the device lacks.
            const bool usable = row.feature == formats::DeviceFeature::kCore ||
                                (featureEnabled(options, row.feature) && blocksProblem(bake_set, row).empty() &&
                                 deviceSamples(gpu, row));
            if (usable) chosen = &row;
        }
        return LightmapFormat(chosen->c_enum);
    }
    const formats::FormatRow& row = lightmapRow(options.lightmap_format);
    if (!featureEnabled(options, row.feature))
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           std::string("options.lightmap_format: ") + row.name + " needs " + featureMissing(row.feature));
    const std::string problem = blocksProblem(bake_set, row);
    if (!problem.empty())
        throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet,
                           std::string("options.lightmap_format: ") + row.name + ", but " + problem);
    return options.lightmap_format;
}

}  // namespace gusuku::runtime_detail
