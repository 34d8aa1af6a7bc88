#pragma once
// Lightmap UVs (TEXCOORD_1) for the building's baked indirect irradiance: checking the ones a glTF brings,
// making our own charts when it brings none (or bad ones), finding which surface point each lightmap texel
// stands for, and dilating the baked texels so bilinear filtering at chart edges never reads black.
//
// Texel convention, shared by every function here: a lightmap of `resolution` x `resolution` texels covers
// uv1 in [0,1]^2; texel (x, y) covers u in [x, x+1] / resolution and v in [y, y+1] / resolution, its sample
// point is the centre ((x + 0.5) / resolution, (y + 0.5) / resolution), and it is stored at index
// y * resolution + x. v = 0 is row 0, the top row of the image, as glTF's texture coordinates have it.
//
// Coverage rule (the one rasterizeLightmapTexels and checkLightmapUvs share): a triangle covers a texel when
// the texel's centre lies inside it; a centre exactly on an edge belongs to exactly one of the two triangles
// sharing that edge (the edge is evaluated once, in a canonical vertex order, so the two sides agree bit for
// bit). A triangle that covers no centre at all (thin or tiny in UV) still claims the texel under its UV
// centroid, so every triangle gets lit; such a claim yields to any centre claim.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gusuku/maths/mesh.h"

namespace gusuku::bake {

/// Side of a square lightmap holding the mesh's world surface at `texels_per_metre`:
/// ceil(sqrt(area_m2 * texels_per_metre^2 * kLightmapPackingOverhead)), rounded UP to a multiple of 4 and
/// clamped to [4, max_resolution] (rounded DOWN to a multiple of 4 when the cap is hit). The overhead allows
/// for chart rectangles, shelf packing and padding; when the charts still do not fit, generateLightmapCharts
/// lowers the density and says so. O(triangles). Throws InputError when texels_per_metre is not finite and
/// positive, max_resolution < 4, or an index is out of range.
inline constexpr double kLightmapPackingOverhead = 2.0;
int chooseLightmapResolution(const TriangleMesh& mesh, double texels_per_metre, int max_resolution = 2048);

/// The mesh's surface area, m^2 (its positions in metres): the sum of its triangles' areas, skipping any that is
/// not finite. O(triangles). Indices must be in range.
double meshSurfaceAreaM2(const TriangleMesh& mesh);

/// What checkLightmapUvs found. Counts are of triangles unless named texels.
struct UvCheckReport {
    int resolution = 0;
    size_t triangle_count = 0;
    size_t outside_unit_square = 0;  ///< triangles with a uv1 outside [0,1] (or not finite)
    size_t degenerate = 0;           ///< triangles whose uv1 area is below 1e-6 texel^2 (they claim one texel)
    size_t chart_count = 0;          ///< groups of triangles connected through shared uv1 edges
    size_t overlapping_texels = 0;   ///< texel centres claimed by two charts, or twice within one chart (a fold)
    size_t overlapping_triangles = 0;  ///< triangles that take part in such a claim
    /// Texels whose area two different charts both touch (by more than 1e-3 of a texel) without either
    /// necessarily owning its centre: bilinear filtering there mixes two charts. A warning, not a failure.
    size_t shared_edge_texels = 0;
    bool ok = false;      ///< has uv1, nothing outside [0,1], no overlapping texels
    std::string message;  ///< one line for an error or warning: the verdict and the non-zero counts
};

/// Checks mesh.uv1 for use as a lightmap at `resolution` (coverage rule above). Charts are found by
/// connecting triangles that share an edge in uv1 (both end points equal in uv1 to 2^-24), so triangles
/// sharing an edge within one chart are never flagged; only centre claims count as overlap, so charts that
/// merely come closer than a texel are reported in shared_edge_texels instead. Degenerate triangles are
/// counted but take no part in the overlap count. A mesh without uv1 (or with a uv1 count that does not
/// match its vertices) is reported not ok. O(triangles + texels covered); allocates resolution^2 ints.
/// Throws InputError when resolution < 1 or > 16384, or an index is out of range.
UvCheckReport checkLightmapUvs(const TriangleMesh& mesh, int resolution);

/// The chart of every triangle as checkLightmapUvs finds them (triangles joined through edges whose end points
/// coincide in uv1), numbered from 0; a triangle with a non-finite uv1 is a chart of its own. The lightmap
/// filter's chart stop (lightmap_denoise.h). O(triangles). Throws InputError without usable uv1.
std::vector<uint32_t> lightmapUvCharts(const TriangleMesh& mesh);

/// Empty texels the bake adds around each chart's bilinear read set: none. Charts are packed so that no texel is
/// read by two charts (lightmap_charts.cpp), which is all the runtime's bilinear lookups (no mip levels) and
/// dilateLightmapWithinCharts need; a positive padding grows every read set by that many texels.
inline constexpr int kLightmapPaddingTexels = 0;

/// The result of generateLightmapCharts.
struct LightmapCharts {
    /// The input mesh with has_uv1 = true. Triangle i is input triangle i (same material, same winding);
    /// vertices are duplicated where a chart seam crosses them; positions, normals and uv0 are copied unchanged.
    TriangleMesh mesh;
    double texels_per_metre = 0.0;  ///< density actually used: the requested one, or lower if it did not fit
    int resolution = 0;             ///< side of the square lightmap the uv1 are laid out for
    size_t chart_count = 0;
    std::vector<uint32_t> triangle_chart;  ///< chart index of every triangle
};

/// Makes lightmap charts for `mesh` at `texels_per_metre` in a `resolution`^2 lightmap.
/// - Positions are welded within 1e-6 of the bounding-box diagonal (glTF splits vertices at normal and uv0
///   seams). A chart grows from a seed (largest triangles first) across welded edges that a neighbour runs in
///   the opposite direction (a consistently wound surface; on non-manifold edges every such pair), while the
///   neighbour's normal stays within 40 degrees of the seed's. Each joining triangle is unfolded flat about the
///   edge it joins across (its lengths and angles kept; the seed lies on its own plane), so a chart's uv1 area is
///   its world area at the density, curved or not; a corner the chart already holds within 1e-3 texel is that
///   point. A triangle whose unfolding would overlap the chart's triangles by more than 1e-4 texel (duplicated
///   faces, folds, a ramp passing over itself) is left for a later chart, so no chart overlaps itself. Degenerate
///   triangles (zero area or collapsed by welding) join the chart of a triangle sharing one of their vertices.
/// - Charts meeting across edges of up to 90 degrees are joined by unfolding one about the longest edge they
///   share (a rigid move: the density is kept; the seam's other corners that land within 1e-3 texel become one
///   with their partners, the others stay cut), longest seams first, when the joined chart overlaps nothing of
///   itself, its padded smallest rectangle at the requested density saves at least a quarter of the smaller
///   chart's, and it takes at most 1/16 of all the charts' padded texels (bigger pieces pack worse). A thin
///   beam's four faces become one strip with one gutter. Texels across such an edge are neighbours in uv1.
/// - Each chart is rotated in its plane to the smallest bounding rectangle (5 degree steps) and scaled to texels.
/// - Charts are skyline-packed by the shape of the texels they touch (lightmap_pack.cpp: largest perimeter first,
///   four quarter turns, small charts into the holes left under bigger ones), each with `padding_texels` empty
///   texels on every side of the texels its triangles touch, so at least 2 * padding_texels empty texels
///   separate two charts. Inside its frame a chart is either offset so its edges stay clear of rows of texel
///   centres (coverage is then stable under float noise: a 1 m face at 8 texels/m covers 8 x 8 centres), or, per
///   axis, spanned: stretched (never shrunk by more than 0.5 %, so its density is the requested one or higher) to
///   end a hundredth of a texel inside a row of centres at each end, so it reads no texel it does not trace (the
///   same face spans 9 x 9 centres, all traced); each chart takes the frame that traces most for its reads. If the rectangles do not fit, the
///   density is lowered uniformly (bisection) until they do; texels_per_metre reports it.
/// About linear in triangles (hash maps for welding, adjacency and overlap tests). Throws InputError for a mesh without triangles, an index out of range, a position
/// that is not finite, a bad density, resolution or padding, or when even a one-texel footprint per chart
/// cannot fit.
LightmapCharts generateLightmapCharts(const TriangleMesh& mesh, double texels_per_metre, int resolution,
                                      int padding_texels = kLightmapPaddingTexels);

/// generateLightmapCharts in the smallest square lightmap that holds the charts at the full density: the side
/// is a multiple of 4 (at most max_resolution, rounded down to 4) within 1.6 % of the smallest at which they
/// pack, found by growing from the touched area's bound and bisecting (under ten packings); only when max_resolution cannot hold them is the density lowered. LightmapCharts::resolution says the
/// side chosen. Throws as generateLightmapCharts.
LightmapCharts generateLightmapChartsInSmallestLightmap(const TriangleMesh& mesh, double texels_per_metre,
                                                        int max_resolution,
                                                        int padding_texels = kLightmapPaddingTexels);

/// One lightmap texel that stands for a point on the building.
struct LightmapTexel {
    int x = 0;
    int y = 0;
    uint32_t triangle = 0;         ///< index of the triangle that owns the texel
    glm::vec3 position{0.0f};      ///< ENU metres: the texel centre mapped through the triangle (clamped into it)
    glm::vec3 shading_normal{0.0f};    ///< interpolated vertex normal, normalised (geometric if that is zero)
    glm::vec3 geometric_normal{0.0f};  ///< unit normal of the triangle from its counter-clockwise winding
};

/// Every texel the mesh's uv1 covers (coverage rule above), one triangle per texel, sorted by y then x.
/// When two triangles claim one centre (overlapping UVs, or a centre on a shared vertex), the one whose
/// clipped area inside the texel is larger wins; fallback (centroid) claims yield to centre claims. A texel
/// taken by a fallback claim maps to the point of the triangle nearest its centre in uv1, so positions always
/// lie on the triangle. Triangles with zero world area are skipped. uv1 outside [0,1] is clipped away.
/// Throws InputError when the mesh has no uv1, an index is out of range, or resolution is out of [1, 16384].
std::vector<LightmapTexel> rasterizeLightmapTexels(const TriangleMesh& mesh_with_uv1, int resolution);

/// A point of a texel's footprint where irradiance is traced (the texel stands for the mean over its area).
struct LightmapFootprintPoint {
    glm::vec3 position{0.0f};        ///< ENU metres, on the triangle under the sub-point
    glm::vec3 shading_normal{0.0f};  ///< interpolated vertex normal there, normalised (geometric if zero)
    glm::vec3 geometric_normal{0.0f};  ///< unit normal of that triangle from its counter-clockwise winding
    /// Share of its texel's mean: 1 / (covered sub-points * slots that repeat this sub-point). The weights of one
    /// texel's slots sum to 1, so each covered sub-point counts equally however many slots repeat it.
    float weight = 0.0f;
};

/// Every texel's footprint as grid_side^2 trace points ("slots"): texel i of the texel list owns slots
/// [i * K, (i + 1) * K), K = grid_side^2.
struct LightmapFootprint {
    int grid_side = 1;
    std::vector<LightmapFootprintPoint> points;
    size_t pointsPerTexel() const { return size_t(grid_side) * size_t(grid_side); }
};

/// The sub-point grid for a per-texel sample budget: the largest side in {4, 2} whose side^2 slots each get the
/// same whole number of samples, at least min_samples_per_slot of them (so the total number of rays stays
/// samples_per_texel per texel and each slot has the rays to be judged valid or not), and whose
/// texel_count * side^2 points stay within max_points (a device's storage buffer limit); else 1 (the texel
/// centre alone, the texel point of rasterizeLightmapTexels). The default of 20 is 2 / the bake's back-face
/// threshold of 0.1: a valid slot then needs 3 stray back-face hits to be called invalid, and a slot half inside
/// a wall (half its rays on a back face) shows at least 3 but for a chance under 1e-4. 512 samples: 16 slots of
/// 32; 128: 4 of 32; 64 and fewer: the centre.
int footprintGridSide(uint32_t samples_per_texel, size_t texel_count = 0, size_t max_points = SIZE_MAX,
                      uint32_t min_samples_per_slot = 20);

/// Spreads each texel over its footprint: K = grid_side^2 sub-points inside the texel square at an n-rooks
/// pattern (the K sub-points have K distinct u and K distinct v, each at (k + 0.5) / K of the texel, and one
/// sits in each cell of the grid_side^2 grid), shifted toroidally by an offset drawn per texel from `seed`
/// (Cranley-Patterson rotation), so the mean over slots is an unbiased estimate of the area mean over the
/// texel and deterministic per seed. A sub-point counts where a triangle with world area covers it (the
/// coverage rule above; the texel's owning triangle first, then the others in index order), at that triangle's
/// interpolated position and normal (offset along the ray as the centre point is). Slots whose sub-point falls
/// on no triangle repeat the covered ones in turn (same position, another random stream), so every texel
/// keeps its full sample budget; a texel none of whose sub-points is covered (a thin triangle's fallback
/// claim) uses its centre point in every slot. grid_side 1 gives exactly the texels' centre points.
/// O(triangles' texel rectangles * K); allocates resolution^2 ints. Throws InputError for grid_side outside
/// [1, 8] or what rasterizeLightmapTexels refuses.
LightmapFootprint lightmapTexelFootprints(const TriangleMesh& mesh_with_uv1, int resolution,
                                          const std::vector<LightmapTexel>& texels, int grid_side, uint32_t seed);

/// The slots of texel `texel` whose sums stand for it: a slot is invalid when its w / samples_per_slot exceeds
/// max_invalid_fraction (the bake's back-face rule); the texel is invalid when its invalid slots hold more than
/// half its weight; a valid texel keeps its valid slots, an invalid one its invalid slots. Bit k stands for slot
/// texel * K + k (K = pointsPerTexel() <= 64). The one rule texelSumsFromFootprint and the denoiser's
/// texelLuminanceVarianceFromFootprint both fold by. Call with samples_per_slot > 0 and slot_sums matching.
uint64_t keptFootprintSlots(const LightmapFootprint& footprint, const std::vector<glm::vec4>& slot_sums, size_t texel,
                            uint32_t samples_per_slot, float max_invalid_fraction);

/// Combines the running sums traced at a footprint's slots (vec4 per slot: irradiance sum xyz and an
/// invalid-sample count w, both over samples_per_slot samples) into one sum per texel over K *
/// samples_per_slot samples, so what reads per-texel sums divides by the texel's full sample count as before.
/// A slot is invalid when its w / samples_per_slot exceeds max_invalid_fraction (the bake's back-face rule, so
/// a double-sided part's inside and a one-sided one's count alike); a texel is invalid when the invalid slots
/// hold more than half its weight (most of its footprint is inside). A valid texel's sum is the weighted mean of
/// its valid slots (geometry inside walls does not darken it), an invalid texel's the mean of its invalid slots
/// (so it stays invalid under the same threshold). The verdicts need footprintGridSide's samples per slot.
/// Throws InputError when the sums do not match the footprint.
std::vector<glm::vec4> texelSumsFromFootprint(const LightmapFootprint& footprint,
                                              const std::vector<glm::vec4>& slot_sums, uint32_t samples_per_slot,
                                              float max_invalid_fraction);

/// Fills empty texels from their neighbours, `iterations` rings deep, so bilinear filtering at chart edges
/// reads the chart's own values instead of black. A texel is valid when its alpha > 0. Each iteration, every
/// invalid texel with at least one valid 8-neighbour (valid at the start of that iteration) gets the plain
/// average of those neighbours' RGBA (so it becomes valid, with alpha the neighbours' mean alpha). Valid texels
/// never change. Stops early when nothing changes. O(iterations * resolution^2). Throws InputError when the
/// vector does not hold resolution^2 texels.
void dilateLightmap(std::vector<glm::vec4>& rgba_texels, int resolution, int iterations);

/// Per lightmap texel, the chart whose bilinear lookups read it (some point of one of its triangles gives the texel's
/// centre a weight above zero, conservatively by 2e-3 texel for float uv1): the chart's index, kNoReaderChart when
/// no chart reads it, kSharedReaderChart when two do (a glTF's own UVs may; generated charts never). triangle_chart
/// is lightmapUvCharts' numbering. O(texels the triangles read). Throws InputError as rasterizeLightmapTexels does,
/// or when triangle_chart does not hold one chart per triangle.
inline constexpr int32_t kNoReaderChart = -1;
inline constexpr int32_t kSharedReaderChart = -2;
std::vector<int32_t> lightmapTexelReaderCharts(const TriangleMesh& mesh_with_uv1,
                                               const std::vector<uint32_t>& triangle_chart, int resolution);

/// dilateLightmap that keeps charts apart: a texel one chart reads (reader_charts, lightmapTexelReaderCharts) is
/// filled only from valid neighbours that chart also reads, so no chart's light reaches another chart's lookups even
/// where their read texels touch; a texel no chart (or two charts) reads is filled from any valid neighbour, as
/// dilateLightmap does. Throws InputError when the vectors do not hold resolution^2 texels.
void dilateLightmapWithinCharts(std::vector<glm::vec4>& rgba_texels, const std::vector<int32_t>& reader_charts,
                                int resolution, int iterations);

}  // namespace gusuku::bake
