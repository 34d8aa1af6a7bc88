#pragma once
// pack.bin, the runtime pack's geometry (docs/bakeset.md, "The runtime pack"): the building as the runtime draws
// it (gusuku::BakeSetMesh without its textures' texels, which are texture_<n>.ktx2), the occluder, and the scale
// of the pack's lightmaps. A documented little-endian binary in place of the glb, so that a phone reads it with
// the standard library alone: a glb's JSON chunk and its PNG/JPEG textures would need a JSON reader and two image
// decoders. Standard library and glm only.
//
// Layout (every number little-endian; f32 IEEE 754):
//   8 bytes   "GSKPACK1", or "GSKPACK2" when a material is alpha-masked (then each material also has an f32 alpha
//             cutoff after its texture: negative for an opaque material, else in [0, 1]; the writer writes
//             GSKPACK1 while all are opaque, so an opaque pack's bytes are those of before)
//   f32       lightmap_scale: the lightmaps' stored RGB times this is the bake set's irradiance (a power of 2, >= 1)
//   u32 x 10  counts: positions, normals, uv0, uv1, indices, triangle materials, materials, textures,
//             occluder positions, occluder indices
//   f32 x 3 per position, f32 x 3 per normal, f32 x 2 per uv0, f32 x 2 per uv1, u32 per index,
//   u32 per triangle material, (f32 x 4 base colour factor, i32 texture or -1) per material,
//   (u32 width, u32 height) per texture, f32 x 3 per occluder position, u32 per occluder index
// and nothing after. normals, uv0 and uv1 are empty or one per position.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

struct PackGeometry {
    float lightmap_scale = 1.0f;
    BakeSetMesh building;  ///< textures hold width and height only; their texels come from texture_<n>.ktx2
    BakeSetOccluder occluder;
};

std::vector<uint8_t> encodePackGeometry(const PackGeometry& geometry);

/// Reads pack.bin; `file` names it in errors. InputError(file, field, problem) for: a wrong magic, a count whose
/// arrays would not fit the file, bytes left over, a count that disagrees with another (normals, uvs, triangle
/// materials), an index or material outside its range, a texture index outside [-1, textures), a texture side
/// of 0 or above 16384, a non-finite number, a lightmap_scale that is not a power of 2 >= 1.
PackGeometry decodePackGeometry(const uint8_t* bytes, size_t size, const std::string& file);

}  // namespace gusuku
