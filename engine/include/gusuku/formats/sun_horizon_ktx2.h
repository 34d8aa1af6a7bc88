#pragma once
// The sun horizons' file (gusuku/formats/sun_horizon.h, docs/bakeset.md "Sun horizons"): one KTX2 image of
// VK_FORMAT_R8G8B8A8_UNORM (format_table.h's "rgba8 data" row), width x 2 height texels, layer 0's rows above
// layer 1's, so the one-image container of ktx2.h holds both layers. The bake set and the runtime pack hold the
// same bytes.

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/formats/sun_horizon.h"

namespace gusuku {

/// The file's bytes. std::invalid_argument for an empty or malformed horizon (findBakeSetProblem's rules).
std::vector<uint8_t> encodeSunHorizonKtx2(const BakeSetSunHorizon& horizon);

/// Reads what encodeSunHorizonKtx2 writes; `file` names it in errors. InputError(file, FIELD, PROBLEM) for
/// anything decodeKtx2 refuses, a height that is not twice the width, or a side outside
/// [kMinSunHorizonResolution, kMaxSunHorizonResolution].
BakeSetSunHorizon decodeSunHorizonKtx2(const uint8_t* bytes, size_t size, const std::string& file);

}  // namespace gusuku
