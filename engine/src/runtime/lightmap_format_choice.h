#pragma once
// Which format the runtime holds the lightmaps in (RuntimeOptions::lightmap_format, docs/runtime.md "Lightmap
// formats"). Private to gusuku_runtime.

#include "gusuku/gpu/gpu_device.h"
#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// Whether the device samples and filters VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK (optimal tiling, as a transfer
/// destination too). Only meaningful where the app enabled textureCompressionASTC_HDR.
bool deviceSamplesAstcHdr(const GpuDevice& gpu);

/// options.lightmap_format with kAuto resolved: kAstc4x4Hdr when options.texture_compression_astc_hdr, the device
/// samples the format, and the bake set (already checked) has ASTC blocks at the runtime's irradiance scale; else
/// kE5b9g9r9. A forced kAstc4x4Hdr that cannot be honoured throws RuntimeError: kDevice without the feature,
/// kInvalidBakeSet without the blocks or at another scale (the device's format support is checked by
/// checkDeviceRequirements like any format's). Other formats are returned as they are.
LightmapFormat chooseLightmapFormat(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options);

}  // namespace gusuku::runtime_detail
