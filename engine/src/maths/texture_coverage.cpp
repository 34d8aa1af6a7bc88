// Each texture's coverage-keeping alpha (gusuku/maths/texture_coverage.h).

#include "gusuku/maths/texture_coverage.h"

namespace gusuku {

std::vector<float> textureCoverageAlphas(const BakeSetMesh& mesh) {
    std::vector<float> coverage_alpha(mesh.textures.size(), -1.0f);
    for (const BakeSetMaterial& material : mesh.materials) {
        const int texture = material.base_color_texture;
        if (!material.alpha_masked || texture < 0 || size_t(texture) >= coverage_alpha.size() ||
            coverage_alpha[texture] > 0.0f || !(material.base_color_factor.a > 0.0f))
            continue;
        coverage_alpha[texture] = material.alpha_cutoff / material.base_color_factor.a;
    }
    return coverage_alpha;
}

}  // namespace gusuku
