#pragma once
// The bake set on the GPU: what gusuku_runtime uploads once when it opens (the building's vertices by material,
// its textures, the lightmaps and ground terms as texture arrays, the occluder). Private to gusuku_runtime.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "ground_sunlit.h"
#include "gusuku/formats/bakeset_data.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/gpu/gpu_image.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::runtime_detail {

/// The smallest buffer made: Vulkan buffers may not be empty, so an empty array (no occluder, no ground) still
/// gets a valid buffer to bind, of one vec4.
constexpr size_t kMinBufferBytes = 16;

/// The building's vertex layout (building_pass.cpp's vertex input): position, normal, base colour uv, lightmap uv.
struct BuildingVertex {
    float position[3];
    float normal[3];
    float base_colour_uv[2];
    float lightmap_uv[2];
};
static_assert(sizeof(BuildingVertex) == 40);

/// One draw of the building: a run of indices that share a material.
struct MaterialDraw {
    uint32_t first_index = 0;
    uint32_t index_count = 0;
    uint32_t material = 0;  ///< index into GpuScene::material_textures / base_colour_factors
};

struct GpuScene {
    GpuBuffer building_vertices;  ///< BuildingVertex, device-local
    GpuBuffer building_indices;   ///< uint32, sorted by material
    uint32_t building_index_count = 0;
    std::vector<MaterialDraw> draws;  ///< the opaque materials' first, then the alpha-masked ones'
    /// Indices [0, this) are of opaque materials (one depth-only draw in the shadow pass); the rest are of
    /// alpha-masked ones (drawn per material with the alpha test).
    uint32_t opaque_index_count = 0;
    /// Per material: the alpha cutoff of an alpha-masked material, or a negative value for an opaque one.
    std::vector<float> alpha_cutoffs;
    std::vector<glm::vec4> base_colour_factors;  ///< per material
    std::vector<int> material_texture;           ///< per material: index into textures, or -1 (white)
    std::vector<GpuImage> textures;              ///< RGBA8 or ASTC 6x6 sRGB base colour textures, full mip chains
    uint32_t astc_texture_count = 0;             ///< of textures, those made from the bake set's ASTC blocks
    GpuImage white_texture;                      ///< 1x1 white for materials without a texture
    GpuBuffer occluder_vertices;                 ///< vec3, device-local (may hold nothing)
    GpuBuffer occluder_indices;
    uint32_t occluder_index_count = 0;
    /// Quads of the ground grid (two triangles between neighbouring cell centres); each frame slot holds the
    /// indices of those chosen (only quads the building can change are drawn: ground_quads.h).
    uint32_t ground_quad_capacity = 0;
    /// Per cell (texel order): kCellNoGround, kCellGround, or kCellGroundChangedByBuilding (ground_quads.h); and
    /// the ground's height (ENU z). The CPU's copy, for choosing the quads to draw.
    std::vector<uint8_t> ground_cell_state;
    std::vector<float> ground_cell_height;
    std::vector<glm::vec3> ground_cell_normal;  ///< ENU, as ground_geometry holds it
    /// Per slot and cell, E_with and E_without as the GPU reads them (groundSlotLight), and the site's heights:
    /// which marked cells the frame's light leaves at a ratio of 1 (ground_sunlit.h).
    std::vector<float> ground_slot_light;
    SiteHeightTiles site_heights;
    GpuImage lightmaps;          ///< lightmapVkFormat array, one layer per slot, RGB / irradiance_scale
    /// RGBA16F array, layers 2 slot (with) and 2 slot + 1 (without), RGB / irradiance_scale. Alpha: 0 no ground,
    /// 1 ground; layer 0 only: 2 on ground where the building changes the baked light (any slot, above
    /// RuntimeOptions::ground_change_threshold).
    GpuImage ground_irradiance;
    GpuImage ground_geometry;    ///< RGBA32F: normal, height
    /// RGBA8 UNORM array of 2 layers: the building's sun horizons (gusuku/formats/sun_horizon.h), lightmap-sized;
    /// one texel of open horizons (zeros) when the bake set has none.
    GpuImage sun_horizon;
    std::vector<glm::vec3> slot_mean_indirect;  ///< per slot: mean E_ind over the building's valid texels
    float irradiance_scale = 1.0f;  ///< stored half-float values times this are the bake set's irradiance
    glm::dvec3 building_min{0.0}, building_max{0.0};  ///< ENU bounds
    glm::dvec3 receivers_min{0.0}, receivers_max{0.0};  ///< building and ground grid
    glm::dvec3 casters_min{1.0}, casters_max{-1.0};     ///< building and occluder (empty when min > max)
    double scene_radius_m = 1.0;  ///< half the diagonal of everything, for depth ranges
};

/// How a base-colour texture's mip chain is made: blits on the GPU (where R8G8B8A8_SRGB can be blitted with
/// linear filtering: canBlitMipChain), else a box filter on the CPU (srgb_mip_chain.h). Both filter in linear light.
enum class MipChainMaker { kGpuBlit, kCpuBoxFilter };

/// A base-colour texture (already checked: rgba8 holds width x height texels) as an R8G8B8A8_SRGB image with its
/// full mip chain, left in SHADER_READ_ONLY_OPTIMAL. Throws std::runtime_error on Vulkan failure.
/// `coverage_alpha` in (0, 1]: the texture is an alpha-masked material's, whose cutoff over its factor's alpha
/// this is; its chain is then made on the CPU whatever `maker` says, each level keeping level 0's coverage at
/// that alpha (boxFilteredSrgbMipLevels), which a blit cannot.
GpuImage uploadBaseColourTexture(const GpuDevice& gpu, const BakeSetTexture& texture, MipChainMaker maker,
                                 float coverage_alpha = -1.0f);

/// A texture's ASTC 6x6 blocks (already checked: texture.astc6x6_levels is its full chain) as a
/// VK_FORMAT_ASTC_6x6_SRGB_BLOCK image, each level as the bake made it, left in SHADER_READ_ONLY_OPTIMAL.
GpuImage uploadAstcBaseColourTexture(const GpuDevice& gpu, const BakeSetTexture& texture);

/// Whether the device samples and filters VK_FORMAT_ASTC_6x6_SRGB_BLOCK (optimal tiling, as a transfer
/// destination too). Only meaningful where the app enabled textureCompressionASTC_LDR.
bool deviceSamplesAstcLdr(const GpuDevice& gpu);

/// Uploads the bake set (already checked by findBakeSetProblem); change_threshold is
/// RuntimeOptions::ground_change_threshold; `astc_textures`: the textures with ASTC blocks are drawn from them
/// (RuntimeOptions::texture_compression_astc_ldr and deviceSamplesAstcLdr). Throws std::runtime_error on Vulkan
/// failure, RuntimeError kInvalidBakeSet for a texture held only as blocks when `astc_textures` is false.
GpuScene uploadScene(const GpuDevice& gpu, const BakeSetData& bake_set, float change_threshold,
                     LightmapFormat lightmap_format, bool astc_textures);

/// The Vulkan format that holds lightmaps in `format`, and its name for messages.
/// The scale the runtime stores lightmaps and ground terms at: the largest irradiance over 30000 (so it fits a
/// half float), or 1 when it is smaller. Stored values times it are the bake set's.
float irradianceScaleOf(const std::vector<BakeSetSlotImages>& slots);
/// The VkFormat of a resolved format (kAuto is resolved first: chooseLightmapFormat).
VkFormat lightmapVkFormat(LightmapFormat format);
const char* lightmapFormatName(LightmapFormat format);

}  // namespace gusuku::runtime_detail
