#pragma once
// A private folder for one fuzzing process: the input under test is written there (the loaders take paths), next
// to the files a site.json or a glTF may name, so references resolve and the loaders go past their file checks.

#include <cstddef>
#include <cstdint>
#include <string>

namespace gusuku::fuzz {

/// The folder, created on first use (mkdtemp under $TMPDIR or /tmp) with: building.glb, site.glb (placeholders),
/// sky.hdr, sky_overcast.exr (placeholders), buffer.bin (a triangle: 3 float3 positions, then 3 uint16 indices),
/// texture.png (a 2 x 2 RGBA PNG). Removed when the process exits.
const std::string& workFolder();

/// Writes `size` bytes to workFolder()/name and returns the path.
std::string writeInput(const std::string& name, const uint8_t* data, size_t size);

}  // namespace gusuku::fuzz
