#pragma once
// Everything geometric a bake needs, loaded once: the building (with lightmap UVs, its own or generated), its
// lightmap texels, the site mesh (or a flat stand-in), the combined trace scene and the ground grid.

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/maths/mesh.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bvh.h"
#include "gusuku_bake/ground_grid.h"
#include "gusuku_bake/lightmap_uv.h"
#include "gusuku_bake/trace_scene.h"

namespace gusuku::bake {

struct BakeGeometry {
    TriangleMesh building;                 ///< ENU, with uv1
    std::string lightmap_uv_source;        ///< "TEXCOORD_1 from the glTF" or "generated charts (...)"
    int lightmap_resolution = 0;
    double effective_texels_per_metre = 0.0;
    std::vector<LightmapTexel> texels;     ///< the building's lightmap texels
    std::vector<uint32_t> texel_chart;     ///< per texel, its uv1 chart (lightmapUvCharts), for the filter
    /// per lightmap texel (resolution^2), the chart whose lookups read it (lightmapTexelReaderCharts), for dilation
    std::vector<int32_t> texel_reader_chart;
    bool site_mesh_is_stand_in = false;    ///< no sfm_mesh in site.json: a flat ground plane was used
    TraceScene scene;                      ///< building + site, with its BVH (scene.bvh, never null here)
    GroundRegion ground_region;
    std::vector<GroundCell> ground_cells;
    std::vector<std::string> warnings;

    /// The scene's BVH, for the ground grid and visibility on the CPU; the tracers upload the same one.
    const Bvh& cpuBvh() const { return *scene.bvh; }
};

/// Loads and prepares. lowest_sun_elevation_deg sizes the ground grid (negative: overcast only). The building's
/// textures are decoded to fit building_texture_size (what building.glb keeps for the runtime; the tracers
/// downsample them again to their own max_texture_size when they upload the scene), the site mesh's to
/// max_texture_size. Bad input throws InputError naming the file and field. With storage_buffer_limit_bytes (the
/// device's, storageBufferLimitBytes; 0: not checked here), a texel density whose lightmap's query points would
/// pass it for certain is refused before the charts are made (bake_preflight's deviceLimitProblems checks the
/// exact sizes after).
BakeGeometry prepareBakeGeometry(const SiteConfig& site, double lowest_sun_elevation_deg, int max_texture_size,
                                 int building_texture_size, uint64_t storage_buffer_limit_bytes = 0);

/// The site's SfM mesh placed as site.json says, or, when it names none, the bake's flat grey stand-in ground:
/// a square 4 x the building's largest extent (at least 10 m) from the origin each way, with a warning saying so.
/// One function for the bake and the camera (camera_frame.h), so both see the same ground.
TriangleMesh loadSiteMeshOrStandIn(const SiteConfig& site, const Bounds3& building_bounds, int max_texture_size,
                                   std::vector<std::string>& warnings, bool& is_stand_in);

}  // namespace gusuku::bake
