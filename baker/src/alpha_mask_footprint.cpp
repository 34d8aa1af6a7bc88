// narrowAlphaMaskFlags (gusuku_bake/alpha_mask_footprint.h): a summed-area table of "may be a hole" texels per
// masked material, one rectangle query (split where it wraps) per flagged triangle, and where its bounds hold a
// hole, the triangle itself against each hole's read square.

#include "gusuku_bake/alpha_mask_footprint.h"

#include "lightmap_raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace gusuku::bake {
namespace {

// The shader's alpha is factor * mix(texel / 255, ...); rounding of the mix and the product can take a value that
// is exactly at the cutoff a few ulps below it. A texel counts as a possible hole unless it clears the cutoff by
// this much, far above float rounding (1e-7 relative) and far below an 8-bit step (4e-3).
constexpr float kCutoffMargin = 1e-5f;
// Corners' uv, in texels, are widened by this before the footprint is taken: the shader interpolates uv from
// barycentrics that may stray 1e-7 outside the triangle (bvh_traverse.glsl's slack), in float.
constexpr double kFootprintSlackTexels = 1e-3;

// Counts of possible-hole texels over [0, x) x [0, y) of one texture, for one material's threshold.
struct HoleTable {
    int width = 0;
    int height = 0;
    std::vector<uint32_t> prefix;  // (width + 1) * (height + 1)

    uint32_t at(int x, int y) const { return prefix[size_t(y) * size_t(width + 1) + size_t(x)]; }
    // Holes in columns [x0, x1) and rows [y0, y1), all within the texture.
    uint32_t count(int x0, int y0, int x1, int y1) const { return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0); }
};

HoleTable holeTable(const PackedSceneShading& shading, const MaterialGpu& material) {
    HoleTable table;
    table.width = int(material.texture_width);
    table.height = int(material.texture_height);
    table.prefix.assign(size_t(table.width + 1) * size_t(table.height + 1), 0u);
    const float factor = material.base_color_factor.a, cutoff = material.emission.w;
    for (int y = 0; y < table.height; ++y) {
        uint32_t row = 0;
        for (int x = 0; x < table.width; ++x) {
            const uint32_t word = shading.texture_words[material.texture_first_word + uint32_t(y) * material.texture_width + uint32_t(x)];
            const float alpha = float(word >> 24u) / 255.0f;
            row += factor * alpha < cutoff + kCutoffMargin ? 1u : 0u;
            table.prefix[size_t(y + 1) * size_t(table.width + 1) + size_t(x + 1)] =
                table.prefix[size_t(y) * size_t(table.width + 1) + size_t(x + 1)] + row;
        }
    }
    return table;
}

// The texel indices first .. first + count - 1 (before wrapping) that the bilinear lookups at uv in [low, high]
// read along one axis: floor(uv * size - 0.5) and the next, as sampleBaseColorAlpha takes them.
struct AxisSpan {
    int64_t first = 0;
    int64_t count = 0;
};

// float's rounding of uv * size grows with the coordinate (uv of a texture repeated a thousand times).
double slackTexels(double low_uv, double high_uv, int size) {
    return kFootprintSlackTexels + 1e-6 * std::max(std::abs(low_uv), std::abs(high_uv)) * size;
}

AxisSpan readSpan(double low_uv, double high_uv, int size) {
    const double slack = slackTexels(low_uv, high_uv, size);
    const double first = std::floor(low_uv * size - 0.5 - slack);
    const double last = std::floor(high_uv * size - 0.5 + slack) + 1.0;
    return {int64_t(first), int64_t(last - first) + 1};
}

int64_t wrapped(int64_t index, int size) { return ((index % size) + size) % size; }

// Holes among the span's texels (wrapped): the table's rectangles, a span split where it passes the edge, or the
// whole axis once it reaches all of it.
uint32_t holesIn(const HoleTable& table, const AxisSpan& x_span, const AxisSpan& y_span) {
    const auto pieces = [](const AxisSpan& span, int size) {
        std::vector<std::pair<int, int>> parts;
        if (span.count >= size) return std::vector<std::pair<int, int>>{{0, size}};
        const int first = int(wrapped(span.first, size)), end = first + int(span.count);
        parts.push_back({first, std::min(end, size)});
        if (end > size) parts.push_back({0, end - size});
        return parts;
    };
    uint32_t holes = 0;
    for (const auto& [x0, x1] : pieces(x_span, table.width))
        for (const auto& [y0, y1] : pieces(y_span, table.height)) holes += table.count(x0, y0, x1, y1);
    return holes;
}

bool isHole(const HoleTable& table, int64_t x, int64_t y) {
    const int64_t wx = wrapped(x, table.width), wy = wrapped(y, table.height);
    return table.count(int(wx), int(wy), int(wx) + 1, int(wy) + 1) > 0;
}

// Past this many texels in a triangle's span, a hole in its bounds keeps the test without the exact check.
constexpr int64_t kMaxExactTexels = 1 << 16;

// The exact footprint: lookups at a point p (texels, uv * size) read texel x when |p - (x + 0.5)| < 1 on both
// axes, so a hole texel is read only when the triangle meets the open 2 x 2 square about its centre (widened by
// the slack). Large triangles' bounds hold holes they never reach (an atlas' transparent corners).
bool triangleReadsAHole(const HoleTable& table, const detail::UvTriangle& texels, const AxisSpan& x_span,
                        const AxisSpan& y_span, double slack) {
    if (x_span.count * y_span.count > kMaxExactTexels) return true;
    for (int64_t y = y_span.first; y < y_span.first + y_span.count; ++y)
        for (int64_t x = x_span.first; x < x_span.first + x_span.count; ++x)
            if (isHole(table, x, y) &&
                detail::triangleMeetsSquare(texels, double(x) - 0.5 - slack, double(y) - 0.5 - slack, 2.0 + 2.0 * slack))
                return true;
    return false;
}

}  // namespace

std::vector<uint32_t> narrowAlphaMaskFlags(const PackedSceneShading& shading,
                                           const std::vector<uint32_t>& triangle_flags) {
    std::vector<uint32_t> narrowed = triangle_flags;
    std::map<uint32_t, HoleTable> tables;  // by material, built on first use
    for (size_t t = 0; t < narrowed.size() && t < shading.triangles.size(); ++t) {
        if ((narrowed[t] & kTriangleFlagAlphaMasked) == 0) continue;
        const TriangleShadingGpu& triangle = shading.triangles[t];
        uint32_t material_index;
        std::memcpy(&material_index, &triangle.normal2_material.w, sizeof material_index);
        if (material_index >= shading.materials.size()) continue;
        const MaterialGpu& material = shading.materials[material_index];
        const float cutoff = material.emission.w;
        if (material.texture_height == 0) {
            // No texture: the factor alone decides, the same at every point.
            if (material.base_color_factor.a >= cutoff + kCutoffMargin) narrowed[t] &= ~kTriangleFlagAlphaMasked;
            continue;
        }
        const double us[3] = {triangle.normal0_u0.w, triangle.uv0_vertex1_vertex2.x, triangle.uv0_vertex1_vertex2.z};
        const double vs[3] = {triangle.normal1_v0.w, triangle.uv0_vertex1_vertex2.y, triangle.uv0_vertex1_vertex2.w};
        bool finite = true;
        for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(us[i]) && std::isfinite(vs[i]);
        if (!finite) continue;
        auto found = tables.find(material_index);
        if (found == tables.end()) found = tables.emplace(material_index, holeTable(shading, material)).first;
        const HoleTable& table = found->second;
        const double low_u = *std::min_element(us, us + 3), high_u = *std::max_element(us, us + 3);
        const double low_v = *std::min_element(vs, vs + 3), high_v = *std::max_element(vs, vs + 3);
        const AxisSpan x_span = readSpan(low_u, high_u, table.width);
        const AxisSpan y_span = readSpan(low_v, high_v, table.height);
        if (holesIn(table, x_span, y_span) > 0) {
            const double slack = std::max(slackTexels(low_u, high_u, table.width), slackTexels(low_v, high_v, table.height));
            detail::UvTriangle texels;
            for (int i = 0; i < 3; ++i) texels[size_t(i)] = {us[i] * table.width, vs[i] * table.height};
            if (triangleReadsAHole(table, texels, x_span, y_span, slack)) continue;
        }
        narrowed[t] &= ~kTriangleFlagAlphaMasked;
    }
    return narrowed;
}

}  // namespace gusuku::bake
