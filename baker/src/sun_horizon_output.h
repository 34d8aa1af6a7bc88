#pragma once
// The bake set's sun horizons file (docs/bakeset.md, "Sun horizons"): traced over the building's lightmap UVs at
// sunHorizonResolution, written atomically as kSunHorizonFile. Private to the baker (bake_outputs.cpp).

#include <string>

#include "bake_geometry.h"

namespace gusuku::bake {

/// Traces and writes `output_dir`/kSunHorizonFile; returns its resolution. Cost: about 150 CPU rays a horizon
/// texel on every hardware thread.
int writeSunHorizonFile(const std::string& output_dir, const BakeGeometry& geometry);

}  // namespace gusuku::bake
