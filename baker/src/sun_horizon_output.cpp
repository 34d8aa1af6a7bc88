// The bake set's sun horizons file (sun_horizon_output.h).

#include "sun_horizon_output.h"

#include "gusuku/assets/atomic_file.h"
#include "gusuku/formats/sun_horizon_ktx2.h"
#include "gusuku_bake/sun_horizon_bake.h"

namespace gusuku::bake {

int writeSunHorizonFile(const std::string& output_dir, const BakeGeometry& geometry) {
    const int resolution = sunHorizonResolution(geometry.lightmap_resolution, geometry.effective_texels_per_metre);
    // The horizons' own texels over the same UVs (finer than the lightmap's), and their charts for the dilation.
    const std::vector<LightmapTexel> texels = rasterizeLightmapTexels(geometry.building, resolution);
    const std::vector<int32_t> reader_charts =
        lightmapTexelReaderCharts(geometry.building, lightmapUvCharts(geometry.building), resolution);
    const BakeSetSunHorizon horizon = bakeSunHorizons(geometry.cpuBvh(), texels, resolution, reader_charts,
                                                      kSunHorizonRadiusM, kTriangleFlagAlphaMasked);
    const std::vector<uint8_t> bytes = encodeSunHorizonKtx2(horizon);
    writeBytesAtomically(output_dir + "/" + kSunHorizonFile, bytes.data(), bytes.size());
    return resolution;
}

}  // namespace gusuku::bake
