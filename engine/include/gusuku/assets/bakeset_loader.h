#pragma once
// Reads a bake set folder (docs/bakeset.md) into the in-memory BakeSetData the runtime draws from
// (gusuku/formats/bakeset_data.h). Part of gusuku_assets (glTF, OpenEXR and JSON readers); an app that holds its bake
// set some other way fills BakeSetData itself and never links this.

#include <string>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

/// Loads folder/manifest.json (readBakeSetManifest: format gusuku-bakeset/1 only, strict) and every file it
/// names:
///   - building.glb through loadGltf, back into ENU (glTF (x, y, z) = ENU (x, z, -y)): positions, normals, uv0,
///     uv1 (TEXCOORD_1, required), indices, a material per triangle, materials (base colour factor, texture),
///     textures as 8-bit RGBA (RGB sRGB-encoded with srgbEncode, alpha linear, both rounded to nearest);
///   - occluder.glb when the manifest names one: positions (coincident corners welded) and indices, ENU;
///   - ground_geometry.exr and each slot's three EXRs as float RGBA, row 0 at the top, at the manifest's sizes.
/// File names in the manifest must be plain names inside the folder (no '/', no "..").
/// Every problem is an InputError on one line, FILE: FIELD: PROBLEM: no manifest; the manifest's own errors
/// (a wrong format version, a missing field); a file the manifest names that is missing ("/slots/2/
/// building_irradiance: ..."); an EXR whose size is not the manifest's (naming the expected size); a NaN,
/// infinite or (irradiance RGB) negative texel, naming the first one as "texel (x, y) channel C"; a building.glb
/// without TEXCOORD_1 or without triangles; an occluder whose triangle count is not the manifest's; then
/// whatever findBakeSetProblem (gusuku/formats/bakeset_validate.h) finds, as "FOLDER: FIELD: PROBLEM". Nothing is
/// half-loaded: it returns a complete, consistent BakeSetData or throws.
/// A partial set (a manifest with "partial", one slot of a split bake) is refused as
/// "FOLDER/manifest.json: /partial: ...", naming its slot: join partial sets with `gusuku-bake merge` first.
/// The manifest's input paths are not needed to load (the set's own files are named relative to the folder);
/// resolve them with resolveBakeSetInputPath.
BakeSetData loadBakeSet(const std::string& folder);

/// A partial set (one slot of a split bake, for `gusuku-bake merge`), read and checked exactly as loadBakeSet
/// reads a whole one: every file the manifest names, at the manifest's sizes, every texel finite and every
/// irradiance >= 0. A manifest without "partial" is refused as "FOLDER/manifest.json: /partial: missing ...".
BakeSetData loadPartialBakeSet(const std::string& folder);

/// An input path of `manifest` (BakeSetInput::path, BakeSetSlot::sky_map), read from `folder`, as a path to
/// open: an absolute path as it is; a relative one joined to the folder (symbolic links in the folder's path
/// resolved first, so ".." climbs from where the files are) and made lexically normal; in an older manifest
/// (input_paths_relative_to_folder false) a relative path as it is, relative to where its bake ran.
std::string resolveBakeSetInputPath(const std::string& folder, const BakeSetManifest& manifest,
                                    const std::string& path);

/// What a bake set in `folder` records for an input at `path`: the path relative to the folder (both with
/// symbolic links resolved where they exist, then ".." where needed), or the absolute path when no relative
/// one exists. The inverse of resolveBakeSetInputPath: resolving the result from the same folder opens the same
/// file, and a bake set moved together with its inputs still finds them.
std::string bakeSetRelativeInputPath(const std::string& folder, const std::string& path);

}  // namespace gusuku
