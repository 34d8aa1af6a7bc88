#pragma once
// Which format the runtime holds the lightmaps in (RuntimeOptions::lightmap_format, docs/runtime.md "Lightmap
// formats"), read from the format table's lightmap rows (gusuku/formats/format_table.h). Private to
// gusuku_runtime.

#include "gusuku/formats/format_table.h"
#include "gusuku/gpu/gpu_device.h"
#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// The table's row of a resolved format (kAuto is resolved first: chooseLightmapFormat). std::logic_error for
/// kAuto or a value no row has (RuntimeImpl checks options.lightmap_format before anything reads it).
const formats::FormatRow& lightmapRow(LightmapFormat format);

/// Whether the device offers the row's format_features for its format (optimal tiling). For a format behind a
/// device feature (ASTC) only meaningful where the app enabled that feature.
bool deviceSamples(const GpuDevice& gpu, const formats::FormatRow& row);

/// options.lightmap_format with kAuto resolved: the lightmap row of lowest auto_rank whose device feature the app
/// enabled (RuntimeOptions::texture_compression_astc_hdr), whose format the device samples, and whose blocks the
/// bake set (already checked) carries at the runtime's irradiance scale; E5B9G9R9 (rank 2) always qualifies. A
/// forced format that cannot be honoured throws RuntimeError: kDevice without its device feature,
/// kInvalidBakeSet without its blocks or at another scale (the device's format support is checked by
/// checkDeviceRequirements like any format's). Other formats are returned as they are.
LightmapFormat chooseLightmapFormat(const GpuDevice& gpu, const BakeSetData& bake_set, const RuntimeOptions& options);

}  // namespace gusuku::runtime_detail
