#pragma once
// The composite's edge pixels (issue 44 item 3): those within one pixel of the building's silhouette or of a
// boundary between two of its materials, found by casting each pixel's centre ray on the CPU against the bake
// set's building (its triangles' materials) and occluder (the site's surfaces, which hide it); and the luminance
// of a frame over the truth's there, beside the same over the building's other pixels.

#include <cstdint>
#include <vector>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/runtime/runtime.h"

namespace gusuku::bench {

/// Per pixel (row 0 at the top), the material of the building triangle the centre ray meets first, or -1 (the
/// site's occluder first, or nothing).
std::vector<int32_t> buildingMaterialPerPixel(const BakeSetData& bake_set, const CameraPose& pose,
                                              const CameraIntrinsics& intrinsics, uint32_t width, uint32_t height);

/// 1 where a pixel's 3 x 3 neighbourhood holds two different values and one of them is the building's (>= 0).
std::vector<uint8_t> edgePixelMask(const std::vector<int32_t>& material, uint32_t width, uint32_t height);

/// 1 on the building's pixels that are not edge pixels.
std::vector<uint8_t> flatBuildingMask(const std::vector<int32_t>& material, const std::vector<uint8_t>& edges);

/// Sum over the mask of the frame's linear Rec.709 luminance over the truth's (both sRGB RGBA8); NaN on an empty mask.
double luminanceRatio(const std::vector<uint8_t>& frame, const std::vector<uint8_t>& truth,
                      const std::vector<uint8_t>& mask);

}  // namespace gusuku::bench
