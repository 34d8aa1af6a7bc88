#pragma once
// What a bake reads: the list of input files (the site, its glTFs with the external buffers and images they
// name, the skies), used for the input hash and, through gusuku_bake/output_guard.h, to refuse an output folder
// that would overwrite an input.

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

}  // namespace gusuku::bake
