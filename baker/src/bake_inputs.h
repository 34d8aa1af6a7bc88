#pragma once
// What a bake reads, and where it may write: the list of input files (the site, its glTFs with the external
// buffers and images they name, the skies), used for the input hash and to refuse an output folder that would
// overwrite an input.

#include <string>
#include <vector>

#include "gusuku/assets/site.h"

namespace gusuku::bake {

/// Files a .gltf or .glb names by URI (buffers, images), resolved against its folder and lexically normal;
/// embedded data: URIs and GLB-internal buffers are skipped. Throws InputError when the file cannot be read or
/// its JSON is not a glTF.
std::vector<std::string> gltfExternalFiles(const std::string& gltf_path);

/// Every file a bake of `site` reads, in a fixed order without duplicates: site.json, the building glTF and
/// its external files, the SfM glTF and its external files, the sunny sky, the overcast sky.
std::vector<std::string> bakeInputFiles(const SiteConfig& site);

/// Throws InputError(output_dir, "-o", problem) when output_dir is one of `inputs` or a folder holding one
/// (at any depth, symbolic links resolved), so a bake never overwrites what it reads. Touches nothing.
void refuseOutputHoldingInputs(const std::string& output_dir, const std::vector<std::string>& inputs);

}  // namespace gusuku::bake
