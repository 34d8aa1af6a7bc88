// The lightmaps' format (lightmap_format_choice.h).

#include "lightmap_format_choice.h"

#include <string>

#include "runtime_scene.h"

namespace gusuku::runtime_detail {
namespace {

// Why the bake set's ASTC blocks cannot be drawn as they are, or nothing. The shaders multiply every stored
// lightmap texel by one irradiance scale (runtime_interface.h); the blocks were encoded at the pack's, so the two
// must agree (both 1 unless an irradiance exceeds 30000, which no bench site comes near).
std::string astcBlocksProblem(const BakeSetData& bake_set) {
    if (bake_set.slots.empty() || bake_set.slots[0].building_astc.empty())
        return "the bake set has no ASTC lightmaps (slots[0].building_astc is empty: load the runtime pack, which "
               "gusuku-bake writes them into)";
    const float runtime_scale = irradianceScaleOf(bake_set.slots);
    if (runtime_scale != bake_set.building_astc_scale)
        return "the bake set's ASTC lightmaps are stored at scale " + std::to_string(bake_set.building_astc_scale) +
               ", not the runtime's irradiance scale " + std::to_string(runtime_scale);
    return "";
}

}  // namespace

bool deviceSamplesAstcHdr(const GpuDevice& gpu) {
    VkFormatProperties properties{};
    vkGetPhysicalDeviceFormatProperties(gpu.physical_device, VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK, &properties);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                        VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    return (properties.optimalTilingFeatures & needed) == needed;
}

LightmapFormat chooseLightmapFormat(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options) {
    if (options.lightmap_format == LightmapFormat::kAuto)
        return options.texture_compression_astc_hdr && astcBlocksProblem(bake_set).empty() && deviceSamplesAstcHdr(gpu)
                   ? LightmapFormat::kAstc4x4Hdr
                   : LightmapFormat::kE5b9g9r9;
    if (options.lightmap_format != LightmapFormat::kAstc4x4Hdr) return options.lightmap_format;
    if (!options.texture_compression_astc_hdr)
        throw RuntimeError(RuntimeErrorCode::kDevice,
                           "options.lightmap_format: astc 4x4 hdr needs textureCompressionASTC_HDR enabled on the "
                           "device, and options.texture_compression_astc_hdr is false");
    const std::string problem = astcBlocksProblem(bake_set);
    if (!problem.empty())
        throw RuntimeError(RuntimeErrorCode::kInvalidBakeSet, "options.lightmap_format: astc 4x4 hdr, but " + problem);
    return LightmapFormat::kAstc4x4Hdr;
}

}  // namespace gusuku::runtime_detail
