#include "edge_pixels.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/mesh.h"
#include "gusuku_bake/bvh.h"

namespace gusuku::bench {

std::vector<int32_t> buildingMaterialPerPixel(const BakeSetData& bake_set, const CameraPose& pose,
                                              const CameraIntrinsics& intrinsics, uint32_t width, uint32_t height) {
    // The building's triangles first, then the occluder's: an index below the building's count is the building.
    TriangleMesh scene;
    scene.positions = bake_set.building.positions;
    scene.indices = bake_set.building.indices;
    const size_t building_triangles = scene.indices.size() / 3;
    const uint32_t first = uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), bake_set.occluder.positions.begin(), bake_set.occluder.positions.end());
    for (uint32_t index : bake_set.occluder.indices) scene.indices.push_back(first + index);
    const bake::Bvh bvh = bake::buildBvh(scene, std::vector<uint32_t>(scene.indices.size() / 3, 0u));
    std::vector<int32_t> material(size_t(width) * height, -1);
    const glm::vec3 origin(pose.position_enu);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::dvec3 camera_ray((x + 0.5 - intrinsics.cx) / intrinsics.fx,
                                        (y + 0.5 - intrinsics.cy) / intrinsics.fy, 1.0);
            const glm::vec3 direction(glm::normalize(pose.camera_to_enu * camera_ray));
            const auto hit = bake::traceClosestCpu(bvh, origin, direction, 1e30f);
            if (!hit || hit->triangle_index >= building_triangles) continue;
            const std::vector<uint32_t>& materials = bake_set.building.triangle_material;
            material[size_t(y) * width + x] =
                hit->triangle_index < materials.size() ? int32_t(materials[hit->triangle_index]) : 0;
        }
    return material;
}

std::vector<uint8_t> edgePixelMask(const std::vector<int32_t>& material, uint32_t width, uint32_t height) {
    std::vector<uint8_t> edges(material.size(), 0);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const int32_t centre = material[size_t(y) * width + x];
            bool differs = false, building = centre >= 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const long nx = long(x) + dx, ny = long(y) + dy;
                    if (nx < 0 || ny < 0 || nx >= long(width) || ny >= long(height)) continue;
                    const int32_t other = material[size_t(ny) * width + size_t(nx)];
                    differs |= other != centre;
                    building |= other >= 0;
                }
            edges[size_t(y) * width + x] = differs && building;
        }
    return edges;
}

std::vector<uint8_t> flatBuildingMask(const std::vector<int32_t>& material, const std::vector<uint8_t>& edges) {
    std::vector<uint8_t> flat(material.size(), 0);
    for (size_t i = 0; i < material.size(); ++i) flat[i] = material[i] >= 0 && !edges[i];
    return flat;
}

double luminanceRatio(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                      const std::vector<uint8_t>& mask) {
    double frame_sum = 0.0, truth_sum = 0.0;
    auto luminance = [](const uint8_t* pixel) {
        return luminanceRec709(glm::dvec3(srgbDecode(pixel[0] / 255.0), srgbDecode(pixel[1] / 255.0),
                                          srgbDecode(pixel[2] / 255.0)));
    };
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) {
            frame_sum += luminance(&frame[4 * i]);
            truth_sum += luminance(&truth[4 * i]);
        }
    return truth_sum > 0.0 ? frame_sum / truth_sum : NAN;
}

}  // namespace gusuku::bench
