// Binned-SAH BVH construction (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"):
// per node, triangle centroids are sorted into 16 bins along each axis and the plane between bins with the
// lowest surface-area cost is chosen. The tree is written straight into the GPU layout of bvh.h.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/input_error.h"
#include "gusuku_bake/bvh.h"

namespace gusuku::bake {
namespace {

constexpr int kBinCount = 16;
// SAH costs in units of one ray/triangle test. A node visit on lavapipe (two child boxes fetched and tested)
// costs about as much as one triangle test.
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;
// Below this depth the builder stops trusting SAH and halves at the centroid median, so that even
// pathological input (thousands of triangles in a spiral) stays within kBvhMaxDepth: 40 + log2(2^24 / 4).
constexpr uint32_t kMedianSplitDepth = 40;

struct Box {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};
    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const Box& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    bool empty() const { return !(min.x <= max.x); }
    // Half the surface area: the SAH only compares ratios.
    float halfArea() const {
        if (empty()) return 0.0f;
        const glm::vec3 e = max - min;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

struct PrimitiveInfo {
    Box bounds;
    glm::vec3 centroid;
};

struct BuildTask {
    uint32_t node;
    uint32_t begin;
    uint32_t end;
    uint32_t depth;
};

struct SplitChoice {
    int axis = -1;
    int bin = 0;  // triangles in bins [0, bin] go left
    float cost = std::numeric_limits<float>::infinity();
};

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

int binOf(float centroid, float axis_min, float bin_scale) {
    const int bin = static_cast<int>((centroid - axis_min) * bin_scale);
    return std::clamp(bin, 0, kBinCount - 1);
}

SplitChoice findSahSplit(const std::vector<PrimitiveInfo>& primitives, const std::vector<uint32_t>& order,
                         uint32_t begin, uint32_t end, const Box& centroid_bounds) {
    SplitChoice best;
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = centroid_bounds.max[axis] - centroid_bounds.min[axis];
        if (!(extent > 0.0f)) continue;
        const float bin_scale = kBinCount / extent;
        std::array<Box, kBinCount> bin_bounds;
        std::array<uint32_t, kBinCount> bin_counts{};
        for (uint32_t i = begin; i < end; ++i) {
            const PrimitiveInfo& primitive = primitives[order[i]];
            const int bin = binOf(primitive.centroid[axis], centroid_bounds.min[axis], bin_scale);
            bin_bounds[bin].extend(primitive.bounds);
            ++bin_counts[bin];
        }
        // Sweep from the right to get the cost of every right side, then from the left.
        std::array<float, kBinCount> right_area_times_count{};
        Box right_box;
        uint32_t right_count = 0;
        for (int bin = kBinCount - 1; bin > 0; --bin) {
            right_box.extend(bin_bounds[bin]);
            right_count += bin_counts[bin];
            right_area_times_count[bin - 1] = right_box.halfArea() * static_cast<float>(right_count);
        }
        Box left_box;
        uint32_t left_count = 0;
        for (int bin = 0; bin < kBinCount - 1; ++bin) {
            left_box.extend(bin_bounds[bin]);
            left_count += bin_counts[bin];
            if (left_count == 0 || left_count == end - begin) continue;
            const float cost = left_box.halfArea() * static_cast<float>(left_count) + right_area_times_count[bin];
            if (cost < best.cost) {
                best.axis = axis;
                best.bin = bin;
                best.cost = cost;
            }
        }
    }
    return best;
}

// Node bounds grow by ~1e-6 relative: Moller-Trumbore works on v0 + edges rounded to float, and its t is
// rounded too, so a hit can land a few ulps outside the exact box. Padding by a quantity that grows with
// the coordinates keeps parents enclosing children (a parent's largest coordinate is at least its child's).
void writePaddedBounds(BvhNodeGpu& node, const Box& box) {
    float largest = 0.0f;
    for (int axis = 0; axis < 3; ++axis)
        largest = std::max({largest, std::fabs(box.min[axis]), std::fabs(box.max[axis])});
    const float pad = largest * (1.0f / 1048576.0f) + 1e-30f;
    for (int axis = 0; axis < 3; ++axis) {
        node.bounds_min[axis] = box.min[axis] - pad;
        node.bounds_max[axis] = box.max[axis] + pad;
    }
}

}  // namespace

Bvh buildBvh(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_flags) {
    const size_t triangle_count = mesh.triangleCount();
    if (mesh.indices.size() % 3 != 0)
        throw InputError("mesh", "indices", "index count " + std::to_string(mesh.indices.size()) +
                                                " is not a multiple of 3");
    if (!triangle_flags.empty() && triangle_flags.size() != triangle_count)
        throw InputError("mesh", "triangle flags",
                         std::to_string(triangle_flags.size()) + " flags for " + std::to_string(triangle_count) +
                             " triangles");

    Bvh bvh;
    std::vector<BvhTriangleGpu> usable_triangles;
    std::vector<PrimitiveInfo> primitives;
    usable_triangles.reserve(triangle_count);
    primitives.reserve(triangle_count);
    for (size_t triangle = 0; triangle < triangle_count; ++triangle) {
        glm::vec3 corner[3];
        for (int k = 0; k < 3; ++k) {
            const uint32_t vertex = mesh.indices[3 * triangle + k];
            if (vertex >= mesh.positions.size())
                throw InputError("mesh", "triangle " + std::to_string(triangle),
                                 "vertex index " + std::to_string(vertex) + " out of range (" +
                                     std::to_string(mesh.positions.size()) + " vertices)");
            corner[k] = mesh.positions[vertex];
        }
        const glm::vec3 edge1 = corner[1] - corner[0];
        const glm::vec3 edge2 = corner[2] - corner[0];
        const glm::vec3 normal = glm::cross(edge1, edge2);
        const bool usable = finite(corner[0]) && finite(corner[1]) && finite(corner[2]) && finite(normal) &&
                            (normal.x != 0.0f || normal.y != 0.0f || normal.z != 0.0f);
        if (!usable) {
            ++bvh.dropped_triangle_count;
            continue;
        }
        BvhTriangleGpu gpu{};
        for (int axis = 0; axis < 3; ++axis) {
            gpu.v0[axis] = corner[0][axis];
            gpu.edge1[axis] = edge1[axis];
            gpu.edge2[axis] = edge2[axis];
        }
        gpu.triangle_index = static_cast<uint32_t>(triangle);
        gpu.flags = triangle_flags.empty() ? 0u : triangle_flags[triangle];
        usable_triangles.push_back(gpu);
        PrimitiveInfo primitive;
        for (const glm::vec3& p : corner) primitive.bounds.extend(p);
        primitive.centroid = (primitive.bounds.min + primitive.bounds.max) * 0.5f;
        primitives.push_back(primitive);
    }

    if (usable_triangles.empty()) {
        // The slab test is symmetric in min and max, so "inverted" bounds would still be hit; instead the
        // root is a leaf holding one placeholder whose zero edges make Moller-Trumbore's determinant zero.
        BvhTriangleGpu placeholder{};
        placeholder.triangle_index = kBvhNoTriangle;
        bvh.triangles.push_back(placeholder);
        BvhNodeGpu root{};
        root.left_or_first = 0;
        root.triangle_count = 1;
        bvh.nodes.push_back(root);
        bvh.depth = 1;
        return bvh;
    }

    const uint32_t primitive_count = static_cast<uint32_t>(primitives.size());
    std::vector<uint32_t> order(primitive_count);
    for (uint32_t i = 0; i < primitive_count; ++i) order[i] = i;

    bvh.nodes.reserve(2 * primitive_count);
    bvh.nodes.emplace_back();
    std::vector<BuildTask> tasks{{0, 0, primitive_count, 1}};
    while (!tasks.empty()) {
        const BuildTask task = tasks.back();
        tasks.pop_back();
        bvh.depth = std::max(bvh.depth, task.depth);

        Box bounds, centroid_bounds;
        for (uint32_t i = task.begin; i < task.end; ++i) {
            bounds.extend(primitives[order[i]].bounds);
            centroid_bounds.extend(primitives[order[i]].centroid);
        }
        writePaddedBounds(bvh.nodes[task.node], bounds);
        const uint32_t count = task.end - task.begin;

        auto makeLeaf = [&] {
            bvh.nodes[task.node].left_or_first = task.begin;
            bvh.nodes[task.node].triangle_count = count;
        };
        if (count == 1) {
            makeLeaf();
            continue;
        }

        uint32_t middle = task.begin;
        const SplitChoice split = task.depth < kMedianSplitDepth
                                      ? findSahSplit(primitives, order, task.begin, task.end, centroid_bounds)
                                      : SplitChoice{};
        const float leaf_cost = kTriangleCost * static_cast<float>(count);
        const float split_cost =
            kTraversalCost + kTriangleCost * split.cost / std::max(bounds.halfArea(), 1e-30f);
        if (count <= kBvhMaxLeafTriangles && (split.axis < 0 || leaf_cost <= split_cost)) {
            makeLeaf();
            continue;
        }
        if (split.axis >= 0) {
            const int axis = split.axis;
            const float axis_min = centroid_bounds.min[axis];
            const float bin_scale = kBinCount / (centroid_bounds.max[axis] - axis_min);
            auto goes_left = [&](uint32_t primitive) {
                return binOf(primitives[primitive].centroid[axis], axis_min, bin_scale) <= split.bin;
            };
            middle = static_cast<uint32_t>(
                std::partition(order.begin() + task.begin, order.begin() + task.end, goes_left) - order.begin());
        }
        if (middle == task.begin || middle == task.end) {
            // No SAH split (too deep, or all centroids coincide): halve at the median of the widest axis,
            // which bounds the depth and still makes progress when every centroid is the same point.
            const glm::vec3 extent = centroid_bounds.max - centroid_bounds.min;
            const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
            middle = task.begin + count / 2;
            std::nth_element(order.begin() + task.begin, order.begin() + middle, order.begin() + task.end,
                             [&](uint32_t a, uint32_t b) {
                                 return primitives[a].centroid[axis] < primitives[b].centroid[axis];
                             });
        }

        const uint32_t left_child = static_cast<uint32_t>(bvh.nodes.size());
        bvh.nodes.emplace_back();
        bvh.nodes.emplace_back();
        bvh.nodes[task.node].left_or_first = left_child;
        bvh.nodes[task.node].triangle_count = 0;
        tasks.push_back({left_child + 1, middle, task.end, task.depth + 1});
        tasks.push_back({left_child, task.begin, middle, task.depth + 1});
    }

    bvh.triangles.resize(primitive_count);
    for (uint32_t i = 0; i < primitive_count; ++i) bvh.triangles[i] = usable_triangles[order[i]];
    if (bvh.dropped_triangle_count > 0)
        std::fprintf(stderr, "bvh: dropped %zu zero-area or non-finite triangles of %zu\n",
                     bvh.dropped_triangle_count, triangle_count);
    return bvh;
}

}  // namespace gusuku::bake
