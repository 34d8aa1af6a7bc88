#include "mini_site.h"

#include <cmath>
#include <fstream>

#include <glm/matrix.hpp>

#include "gusuku/assets/gltf_loader.h"
#include "gusuku/assets/image.h"
#include "test_meshes.h"

namespace gusuku::testing {

namespace {

// Brighter towards the zenith, a dim ground below the horizon.
ImageRGBA gradientSky(int width, int height, const glm::vec3& zenith, const glm::vec3& horizon) {
    ImageRGBA sky = uniformSky(width, height, glm::vec3(0.0f));
    for (int y = 0; y < height; ++y) {
        const float elevation = 1.0f - 2.0f * (float(y) + 0.5f) / float(height);  // sin-ish, 1 at the top
        const glm::vec3 radiance = elevation > 0.0f ? glm::mix(horizon, zenith, elevation) : horizon * 0.2f;
        for (int x = 0; x < width; ++x) {
            float* texel = sky.texel(x, y);
            texel[0] = radiance.r, texel[1] = radiance.g, texel[2] = radiance.b;
        }
    }
    return sky;
}

// The SfM stand-in: a ground of many coplanar triangles (which an occluder needs few of) and a 1 m high wall,
// 1 m thick so that the ground grid's cells over it see its top, and near enough to lie inside the grid.
TriangleMesh sfmSite() {
    TriangleMesh site = emptyMesh(glm::vec3(0.4f));
    const float half = 12.0f, step = 0.5f;
    for (float y = -half; y < half; y += step)
        for (float x = -half; x < half; x += step)
            addQuad(site, {x, y, 0.0f}, {x + step, y, 0.0f}, {x + step, y + step, 0.0f}, {x, y + step, 0.0f});
    appendMesh(site, closedBox({-3.0f, -2.25f, 0.0f}, {3.0f, -1.25f, 1.0f}, false, glm::vec3(0.5f)));
    return site;
}

}  // namespace

std::string writeMiniSite(const std::string& dir, const MiniSiteOptions& options) {
    const TriangleMesh house = closedBox({-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 2.0f}, false, glm::vec3(0.7f, 0.6f, 0.5f));
    writeGlb(dir + "/building.glb", house, glm::inverse(enuFromGltfYUp()));
    writeHdr(dir + "/sky_sunny.hdr", gradientSky(128, 64, {0.3f, 0.5f, 1.0f}, {0.8f, 0.85f, 0.9f}));
    writeHdr(dir + "/sky_overcast.hdr", gradientSky(64, 32, {0.6f, 0.6f, 0.6f}, {0.3f, 0.3f, 0.3f}));
    if (options.with_sfm_mesh) writeGlb(dir + "/site.glb", sfmSite(), glm::inverse(enuFromGltfYUp()));
    std::ofstream site(dir + "/site.json");
    site << R"({
  "format": "gusuku-site/1",
  "site": {"name": "mini", "latitude_deg": 26.2856, "longitude_deg": 127.8008, "height_m": 160, "utc_offset": "+09:00"},
  "building": {"path": "building.glb", "enu_offset_m": [0, 0, 0]},)"
         << (options.with_sfm_mesh ? R"(
  "sfm_mesh": {"path": "site.glb", "scale": 1, "rotation_wxyz": [0.7071067811865476, 0.7071067811865476, 0, 0],
               "translation_enu_m": [0, 0, 0]},)"
                                   : "")
         << R"(
  "skies": {"sunny": {"path": "sky_sunny.hdr"}, "overcast": {"path": "sky_overcast.hdr"}},
  "bake": {"date": "2026-06-21", "slots": [{"name": "noon", "sky": "sunny", "local_time": "12:00"})"
         << (options.with_overcast_slot ? R"(, {"name": "cloudy", "sky": "overcast"})" : "") << R"(],
           "texels_per_metre": )"
         << options.texels_per_metre << R"(, "samples_per_texel": )" << options.samples_per_texel
         << R"(, "max_bounces": )" << options.max_bounces << R"(, "seed": 3, "ground_cell_m": 0.5}
}
)";
    return dir + "/site.json";
}

}  // namespace gusuku::testing
