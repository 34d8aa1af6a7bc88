#pragma once
// A bake set held in memory: what gusuku_runtime draws from. The app (or gusuku_assets' loadBakeSet, which reads
// a bake set folder, docs/bakeset.md) fills it; the runtime copies what it needs to the GPU when it opens and
// keeps no pointer into it. Plain data, glm and the standard library only, so the runtime holds it without the
// I/O stack. Frame and units as in the manifest: site ENU metres, irradiance per linear Rec.709 channel in the
// bake set's units (sky radiance units times steradians).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/formats/bakeset_manifest.h"
#include "gusuku/formats/sun_horizon.h"

namespace gusuku {

/// An 8-bit texture: RGB sRGB-encoded, A linear, row 0 at the top, width * height * 4 bytes.
struct BakeSetTexture {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba8;
    /// The same texture as ASTC 6x6 sRGB blocks (VK_FORMAT_ASTC_6x6_SRGB_BLOCK), its full mip chain made at bake
    /// time (element k is level k), as a runtime pack holds it for devices that sample ASTC LDR; empty when the
    /// bake set has none (the EXR bake set, or a pack written before them). A pack may hold only these, with
    /// rgba8 empty: such a texture draws only where the runtime takes ASTC (docs/runtime.md, "Textures").
    std::vector<std::vector<uint8_t>> astc6x6_levels;
};

struct BakeSetMaterial {
    glm::vec4 base_color_factor{1.0f};  ///< linear RGBA, multiplies the texture
    int base_color_texture = -1;        ///< index into BakeSetMesh::textures, -1 for none
    /// glTF alphaMode MASK (gusuku/maths/mesh.h, Material): the runtime discards fragments whose base colour
    /// alpha (factor times texture) is below alpha_cutoff, in the building's pass and its shadow map. False:
    /// opaque, alpha ignored.
    bool alpha_masked = false;
    float alpha_cutoff = 0.5f;  ///< in [0, 1]; read only when alpha_masked
};

/// The building as the runtime draws it: ENU metres, counter-clockwise front faces, one material per triangle.
struct BakeSetMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   ///< unit, per vertex
    std::vector<glm::vec2> uv0;       ///< base colour texture coordinates, per vertex
    std::vector<glm::vec2> uv1;       ///< lightmap coordinates in [0, 1], per vertex
    std::vector<uint32_t> indices;    ///< three per triangle
    std::vector<uint32_t> triangle_material;  ///< one per triangle
    std::vector<BakeSetMaterial> materials;
    std::vector<BakeSetTexture> textures;
};

/// The real site's surfaces for depth only (so real walls hide the building), simplified to what occlusion needs.
struct BakeSetOccluder {
    std::vector<glm::vec3> positions;  ///< ENU metres
    std::vector<uint32_t> indices;     ///< three per triangle
};

/// A float RGBA image, row 0 at the top, width * height * 4 floats (the EXR's layout).
struct BakeSetImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;
};

/// One slot's baked light. building: lightmap_resolution^2, RGB = E_ind, A = 1 on traced texels.
/// ground_with / ground_without: the ground grid's columns x rows, RGB = sky-and-bounce irradiance with and
/// without the building, A = 1 where ground exists.
struct BakeSetSlotImages {
    BakeSetImage building;
    BakeSetImage ground_with;
    BakeSetImage ground_without;
    /// Optional: `building`'s RGB in block formats (the lightmap rows of gusuku/formats/format_table.h with a
    /// pack_suffix: ASTC HDR, alpha 1), encoded at bake time, which a device that samples them draws
    /// as they are (RuntimeOptions::lightmap_format), keyed by the row's vk_format. Each holds the row's
    /// block_bytes for each started block of the lightmap, blocks row by row from the top; the decoded RGB times
    /// BakeSetData::building_blocks_scale is `building`'s. Empty: none (the runtime then uses E5B9G9R9). The
    /// runtime pack carries them; loadBakeSet (the EXRs) leaves them empty.
    std::map<uint32_t, std::vector<uint8_t>> building_blocks;
};

struct BakeSetData {
    BakeSetManifest manifest;
    BakeSetMesh building;
    BakeSetOccluder occluder;               ///< may be empty (no SfM mesh)
    BakeSetImage ground_geometry;           ///< columns x rows: RGB unit normal (ENU), A height (ENU z, metres)
    /// columns x rows: RGB linear albedo of the ground, A 1 where there is ground; empty (0 x 0) when the manifest
    /// names no ground_grid.albedo (an older bake set).
    BakeSetImage ground_albedo;
    std::vector<BakeSetSlotImages> slots;   ///< one per manifest.slots entry, same order
    /// The building's sun horizons, lightmap-sized (gusuku/formats/sun_horizon.h): the small features' shadows the
    /// shadow map cannot resolve. Empty when the manifest names no building.sun_horizon (an older bake set): the
    /// runtime then reads every horizon as open (visibility 1).
    BakeSetSunHorizon building_sun_horizon;
    /// The slots' building_blocks, decoded, times this are the bake set's irradiance (the pack's lightmap_scale).
    float building_blocks_scale = 1.0f;
};

}  // namespace gusuku
