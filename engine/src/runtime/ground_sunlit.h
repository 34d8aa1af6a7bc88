#pragma once
// Which ground cells the building's baked light changes yet leave every pixel of the ground ratio at exactly 1 in
// this frame's light (issue 44 item 5): the bake marks a cell (kCellGroundChangedByBuilding) when the building
// changes its light WITHOUT the sun by more than RuntimeOptions::ground_change_threshold in ANY slot, but in sun
// the sun's light is several times the sky's on open ground, so on most of those cells the ratio
//   (E_with + E_sun) / (E_without + E_sun)
// stays within the shader's pass-through threshold of 1, where it writes exactly 1 (the camera's own byte). Those
// cells need not make their quads drawn. The check (per slot in use, per channel, at the cell centre):
//   |E_with - E_without| < t (E_without + E_sun),   E_sun a lower bound of the frame's sun on the cell,
// is linear in the values the GPU interpolates (and the slots' blend is a convex combination of them), so it holds
// at every fragment of a quad whose four corners hold it: provided the site's shadow map surely reads lit there
// (E_sun's visibility 1). That is proved on the CPU by a march towards the sun over a max-height map of the site's
// occluder, wide enough to cover the quad's fragments and the shadow filter's texels. Private to gusuku_runtime.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "ground_quads.h"

namespace gusuku::runtime_detail {

/// Tiles of kSiteTilesPerCell x kSiteTilesPerCell per ground cell, each holding the highest point of the site's
/// occluder over its square (each triangle's plane at the square's corners, capped at the triangle's top: never
/// below the mesh), and the highest point of any part outside the grid.
constexpr int kSiteTilesPerCell = 2;
struct SiteHeightTiles {
    int columns = 0, rows = 0;            ///< tiles west to east, SOUTH to north (row 0 at the grid's south edge)
    double tile_m = 0.0;
    std::vector<float> max_z;             ///< row-major; -1e30 where no triangle reaches
    float outside_max_z = -1e30f;         ///< over the occluder's parts beyond the grid
    float top_z = -1e30f;                 ///< the highest of all
};

/// Built once at open (a few milliseconds on a real site).
SiteHeightTiles siteHeightTiles(const GroundGrid& grid, std::span<const glm::vec3> positions,
                                std::span<const uint32_t> indices);

/// What the site's shadow test forgives (ground.frag: one bilinear compare tap of the site's map, at the point's
/// depth less the slope-scaled bias): an occluder point Q shades a ground point P only when Q lies within
/// kSiteTapReachTexels of P's ray towards the sun (the 2 x 2 texels the tap reads: their centres lie within
/// sqrt(2) texels of the point) and nearer the sun than P by more than the bias,
///   bias_texels texel_m (1 + min(tan(angle between normal and sun), 10))   (runtime_shadow_coordinates.glsl),
/// of which the CPU counts on kSiteBiasFraction (float depth and interpolation take less than the rest). The
/// slope's share is what keeps the ground's own surface within the tap's reach from shading it.
constexpr double kSiteTapReachTexels = 1.45;
constexpr double kSiteBiasFraction = 0.9;
struct SiteShadowTest {
    double texel_m = 0.0;      ///< the site map's texel for the rounded sun (fitShadowMap)
    double bias_texels = 0.0;  ///< RuntimeOptions::shadow_bias_texels
};
/// The bias (metres towards the sun) the CPU counts on for a vertex with this normal.
double siteShadowBiasM(const SiteShadowTest& test, const glm::dvec3& normal, const glm::dvec3& shadow_sun);

/// Whether the site's occluder surely leaves lit (visibility 1 in the site's map) every point of the ground the
/// cell's quads draw nearer this cell than any other corner (the square of one cell around its centre, no lower
/// than the lowest of the cell and its neighbours), for the sun shadow_sun (unit, towards the sun, z > 0).
bool groundCellSurelySunlit(const GroundCells& cells, const SiteHeightTiles& tiles, size_t column, size_t row,
                            const glm::dvec3& shadow_sun, const SiteShadowTest& test);

/// The light a choice is made for.
struct PassThroughLight {
    int slots[3] = {-1, -1, -1};      ///< the frame's blend (SlotBlend): -1 or a weight of 0, not in use
    float weights[3] = {0.0f, 0.0f, 0.0f};
    bool sun_shines = false;
    glm::dvec3 shadow_sun{0.0, 0.0, 1.0};    ///< the shadow maps' rounded sun (unit, towards the sun)
    glm::dvec3 sun_irradiance_floor{0.0};    ///< a lower bound of the frame's E_sun on a plane facing the sun
    double cosine_slack = 0.001;             ///< the frame's cosine is at least the rounded sun's less this
    SiteShadowTest site_shadow;              ///< for the rounded sun's fit of the maps
    float pass_through_threshold = 0.0f;     ///< FrameUniforms::pass_through_threshold
};

/// Per slot, per cell: E_with rgb then E_without rgb (6 floats) in the bake set's units, as the GPU reads them
/// (rounded to half floats at the runtime's scale, then times it).
std::vector<float> groundSlotLight(std::span<const std::span<const float>> with_rgba,
                                   std::span<const std::span<const float>> without_rgba, float inverse_scale);

/// Writes pass_through (one entry per cell): 1 where the cell is marked kCellGroundChangedByBuilding but holds
/// the check above in every slot in use; 0 elsewhere (and everywhere when the weights sum above 1).
void markPassThroughCells(const GroundCells& cells, std::span<const float> slot_light, const SiteHeightTiles& tiles,
                          const PassThroughLight& light, std::span<uint8_t> pass_through);

}  // namespace gusuku::runtime_detail
