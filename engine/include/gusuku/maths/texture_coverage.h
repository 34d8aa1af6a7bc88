#pragma once
// Which alpha each base-colour texture's mip chain keeps its coverage at (gusuku/maths/srgb_mip_chain.h): one
// rule for the runtime, which makes RGBA8 chains at load, and the bake, which makes the ASTC chains the pack holds.

#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku {

/// One value per texture of `mesh`: an alpha-masked material's cutoff over its base colour factor's alpha, for
/// a texture such a material reads (the first such material's, should two with different cutoffs share it),
/// else -1 (the plain box filter). Materials whose factor alpha is not above 0 or whose texture index is out of
/// range are skipped.
std::vector<float> textureCoverageAlphas(const BakeSetMesh& mesh);

}  // namespace gusuku
