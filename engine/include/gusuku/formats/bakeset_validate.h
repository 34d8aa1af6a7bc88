#pragma once
// Is an in-memory bake set (gusuku/formats/bakeset_data.h) consistent enough for the runtime to upload and draw? The
// runtime checks it when it opens (an app may fill BakeSetData itself); gusuku_assets' loadBakeSet checks what
// it read with the same function. gusuku_maths: glm and the standard library only.

#include <optional>
#include <string>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

/// The first problem found, as one line "FIELD: PROBLEM" (FIELD as a C++ path into BakeSetData, e.g.
/// "slots[2].building: 199 x 200 texels, the manifest says lightmap_resolution 200"), or nothing when the data
/// is consistent. Checked, in this order:
///   - the manifest: at least one slot; lightmap_resolution and the ground grid's columns, rows and cell_m > 0; each sunny slot's sun
///     direction a finite unit vector; a present sun's irradiance finite and >= 0;
///   - the building: at least one triangle; indices a multiple of 3 and in range; normals, uv0 and uv1 one per
///     position; one material per triangle, naming an existing material; each material's texture -1 or an
///     existing texture; each texture's size > 0 with width * height * 4 bytes; positions, normals, uvs and
///     colour factors finite;
///   - the occluder: indices a multiple of 3 and in range, positions finite; its triangle count the manifest's
///     occluder.triangles when the manifest names one;
///   - ground_geometry: columns x rows texels, every value finite;
///   - ground_albedo (optional: older bake sets have none): present exactly when the manifest names
///     ground_grid.albedo; then columns x rows texels, finite, RGB >= 0;
///   - slots: one per manifest slot; building lightmap_resolution^2, ground_with and ground_without columns x
///     rows; every texel finite and RGB >= 0 (irradiance), naming the first bad texel as "texel (x, y) channel C"
///     (x the column, y the row from the top).
/// Every image's rgba must hold width * height * 4 floats. The scan is linear in the data's size.
std::optional<std::string> findBakeSetProblem(const BakeSetData& bake_set);

}  // namespace gusuku
