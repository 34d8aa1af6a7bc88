#pragma once
// A bake other engines can show (`gusuku-bake export`, docs/export.md): the bake set's building.glb with one slot's
// lightmap embedded as a PNG and bound to every material's TEXCOORD_1 through the MOZ_lightmap extension (read by
// Mozilla Hubs and three.js's GLTFLightMapLoaderExtension as linear irradiance times `intensity`), and the slot's
// sun as a KHR_lights_punctual directional light in the same units.

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::bake {

/// The name of the glTF extension the export binds the lightmap with.
inline constexpr const char* kLightmapExtension = "MOZ_lightmap";

/// A lightmap in 8 bits as MOZ_lightmap's readers decode it: the texture is linear (no sRGB curve; three.js
/// forces LinearSRGBColorSpace on it) and the irradiance is byte / 255 * intensity per channel. The scale is the
/// largest RGB value of the lightmap, so nothing clips and every channel decodes within half a step,
/// intensity / 510, of the baked value (linearLightmapMaxError); a texel under 1/255 of the brightest decodes to
/// 0 or one step.
struct LinearLightmap8 {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgb8;  ///< width * height * 3 bytes, row 0 at the top (as the EXR and glTF's uv origin)
    double intensity = 1.0;     ///< MOZ_lightmap.intensity: irradiance of byte 255; 1 when the map is all 0
};

/// Quantises RGB of a bake set lightmap (alpha, the valid-texel flag, is not kept: the dilated RGB is what a
/// viewer filters). std::invalid_argument when the image's size and texel count disagree.
LinearLightmap8 quantiseLightmapLinear8(const BakeSetImage& lightmap);

/// The largest |decoded - baked| of any channel of quantiseLightmapLinear8 at this intensity: half a step.
inline double linearLightmapMaxError(double intensity) { return intensity / 510.0; }

struct LightmapExportReport {
    std::string output_path;
    std::string slot;
    int lightmap_width = 0, lightmap_height = 0;
    double intensity = 1.0;        ///< MOZ_lightmap.intensity written
    size_t materials = 0;          ///< materials that got the extension (all of building.glb's)
    bool sun_light = false;        ///< a KHR_lights_punctual directional light was written (sunny slot, sun up)
    /// Of the texels the bake traced (alpha 1), the share whose brightest channel is under 25.5 steps, where
    /// 8 bits cost more than 2 % relative error (linearLightmapMaxError over the value).
    double coarse_valid_texel_fraction = 0.0;
    uint64_t bytes = 0;            ///< the .glb's size
};

/// Writes `output_path` (a .glb) from the bake set in `bakeset_folder` (read and checked whole by loadBakeSet) and
/// its slot `slot_name`. Everything is checked before anything is written, and the file is written atomically
/// (temporary name, then rename), so a refusal leaves no file. Throws InputError on one line naming the input:
/// a missing or bad bake set (loadBakeSet's errors), "FOLDER/manifest.json: /slots: no slot 'X' (its slots: ...)",
/// a building.glb primitive without TEXCOORD_1, an output that is not a .glb or is a directory, one the output
/// guard refuses (gusuku_bake/output_guard.h: an input the manifest lists, or a file inside any bake set or
/// pack), and an output that cannot be written ("OUT: cannot write: ...").
LightmapExportReport exportLightmappedGlb(const std::string& bakeset_folder, const std::string& slot_name,
                                          const std::string& output_path);

}  // namespace gusuku::bake
