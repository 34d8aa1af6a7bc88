// Binned-SAH BVH construction (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies"):
// per node, triangle centroids are sorted into 16 bins along each axis and the plane between bins with the
// lowest surface-area cost is chosen. The tree is built with float boxes, then written in the GPU layout of
// bvh.h: each inner node holding its two children's boxes quantised to 16 bits on its own grid.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
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
Box paddedBox(const Box& box) {
    float largest = 0.0f;
    for (int axis = 0; axis < 3; ++axis)
        largest = std::max({largest, std::fabs(box.min[axis]), std::fabs(box.max[axis])});
    const float pad = largest * (1.0f / 1048576.0f) + 1e-30f;
    Box padded;
    padded.min = box.min - glm::vec3(pad);
    padded.max = box.max + glm::vec3(pad);
    return padded;
}

// The tree as built, before quantisation: a leaf has triangle_count > 0 (or is the empty placeholder child).
struct FloatNode {
    Box bounds;  // padded
    uint32_t left_or_first = 0;
    uint32_t triangle_count = 0;
    bool leaf = false;
};

float gridValue(float origin, uint32_t step, float scale) { return origin + static_cast<float>(step) * scale; }

float scaleOfExponent(uint32_t biased_exponent) {
    const uint32_t bits = biased_exponent << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return scale;
}

constexpr uint32_t kGridSteps = 65535;  // 16-bit grid

// Quantises both children's boxes on one axis: the grid starts at origin (the parent's min) with the smallest
// power-of-two step whose kGridSteps steps reach past both maxima; each min rounds down and each max up, then
// moves a step further while float rounding of origin + q * scale would still cut into the box.
void quantiseAxis(float origin, const Box (&children)[2], int axis, uint32_t& exponent_byte, uint32_t& min_word,
                  uint32_t& max_word) {
    float extent = std::max(children[0].max[axis], children[1].max[axis]) - origin;
    extent = std::max(extent, 0.0f);
    int exponent = 0;
    std::frexp(extent / static_cast<float>(kGridSteps), &exponent);  // extent / steps < 2^exponent
    uint32_t biased = static_cast<uint32_t>(std::clamp(exponent + 126, 1, 254));
    for (;; ++biased) {
        if (biased > 254) throw std::logic_error("bvh: a box too large to quantise");
        const float scale = scaleOfExponent(biased);
        uint32_t quantised[4] = {};
        bool fits = true;
        for (int c = 0; c < 2 && fits; ++c) {
            const float lo = children[c].min[axis], hi = children[c].max[axis];
            const double q_lo = std::floor((static_cast<double>(lo) - origin) / scale);
            const double q_hi = std::ceil((static_cast<double>(hi) - origin) / scale);
            uint32_t step_lo = static_cast<uint32_t>(std::clamp(q_lo, 0.0, double(kGridSteps)));
            uint32_t step_hi = static_cast<uint32_t>(std::clamp(q_hi, 0.0, double(kGridSteps)));
            while (step_lo > 0 && gridValue(origin, step_lo, scale) > lo) --step_lo;
            while (step_hi < kGridSteps && gridValue(origin, step_hi, scale) < hi) ++step_hi;
            if (gridValue(origin, step_lo, scale) > lo || gridValue(origin, step_hi, scale) < hi) fits = false;
            quantised[c] = step_lo;
            quantised[2 + c] = step_hi;
        }
        if (!fits) continue;
        exponent_byte = biased;
        min_word = quantised[0] | quantised[1] << 16;
        max_word = quantised[2] | quantised[3] << 16;
        return;
    }
}

// Writes the float tree in the GPU layout, inner nodes in depth-first order (a node's first child right
// after it, so a descent reads neighbouring memory). Returns the levels of the tree, leaves included.
uint32_t writeQuantisedTree(const std::vector<FloatNode>& tree, std::vector<BvhNodeGpu>& nodes) {
    constexpr uint32_t kNoParent = 0xffffffffu;
    struct Pending {
        uint32_t tree_node;
        uint32_t parent_gpu_node;  // kNoParent for the root
        uint32_t child_slot;
        uint32_t depth;
    };
    // A lone leaf at the root becomes the first child of a root whose second child is an empty leaf.
    FloatNode lone_root_children[2];
    if (tree[0].leaf) {
        lone_root_children[0] = tree[0];
        lone_root_children[1].leaf = true;
        lone_root_children[1].bounds = tree[0].bounds;
    }
    uint32_t deepest = 0;
    nodes.clear();
    std::vector<Pending> todo{{0, kNoParent, 0, 1}};
    while (!todo.empty()) {
        const Pending pending = todo.back();
        todo.pop_back();
        const uint32_t gpu_index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        if (pending.parent_gpu_node != kNoParent) nodes[pending.parent_gpu_node].child[pending.child_slot] = gpu_index;
        deepest = std::max(deepest, pending.depth);

        const FloatNode& parent = tree[pending.tree_node];
        const FloatNode* children[2] = {&lone_root_children[0], &lone_root_children[1]};
        if (!parent.leaf) {
            children[0] = &tree[parent.left_or_first];
            children[1] = &tree[parent.left_or_first + 1];
        }
        const Box child_boxes[2] = {children[0]->bounds, children[1]->bounds};
        Box grid_box = child_boxes[0];
        grid_box.extend(child_boxes[1]);
        BvhNodeGpu gpu{};
        for (int axis = 0; axis < 3; ++axis) {
            gpu.origin[axis] = grid_box.min[axis];
            uint32_t exponent_byte = 0;
            quantiseAxis(grid_box.min[axis], child_boxes, axis, exponent_byte, gpu.quantised[2 * axis],
                         gpu.quantised[2 * axis + 1]);
            gpu.exponents |= exponent_byte << (8 * axis);
        }
        // The second child is pushed first, so the first child's subtree is numbered right after this node.
        for (int c = 1; c >= 0; --c) {
            const FloatNode& child = *children[c];
            if (child.leaf) {
                gpu.child[c] = kBvhChildLeaf | child.triangle_count << kBvhLeafCountShift | child.left_or_first;
                deepest = std::max(deepest, pending.depth + 1);
            } else {
                todo.push_back({parent.left_or_first + static_cast<uint32_t>(c), gpu_index,
                                static_cast<uint32_t>(c), pending.depth + 1});
            }
        }
        nodes[gpu_index] = gpu;  // inner children's indices are filled in as they are numbered, after this
    }
    return deepest;
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
        FloatNode leaf;
        leaf.bounds.extend(glm::vec3(0.0f));
        leaf.bounds = paddedBox(leaf.bounds);
        leaf.triangle_count = 1;
        leaf.leaf = true;
        bvh.depth = writeQuantisedTree({leaf}, bvh.nodes);
        return bvh;
    }

    if (primitives.size() > kBvhMaxTriangles)
        throw InputError("mesh", "triangles",
                         std::to_string(primitives.size()) + " triangles, above the BVH's limit of " +
                             std::to_string(kBvhMaxTriangles));
    const uint32_t primitive_count = static_cast<uint32_t>(primitives.size());
    std::vector<uint32_t> order(primitive_count);
    for (uint32_t i = 0; i < primitive_count; ++i) order[i] = i;

    std::vector<FloatNode> tree;
    tree.reserve(2 * primitive_count);
    tree.emplace_back();
    std::vector<BuildTask> tasks{{0, 0, primitive_count, 1}};
    while (!tasks.empty()) {
        const BuildTask task = tasks.back();
        tasks.pop_back();

        Box bounds, centroid_bounds;
        for (uint32_t i = task.begin; i < task.end; ++i) {
            bounds.extend(primitives[order[i]].bounds);
            centroid_bounds.extend(primitives[order[i]].centroid);
        }
        tree[task.node].bounds = paddedBox(bounds);
        const uint32_t count = task.end - task.begin;

        auto makeLeaf = [&] {
            tree[task.node].left_or_first = task.begin;
            tree[task.node].triangle_count = count;
            tree[task.node].leaf = true;
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

        const uint32_t left_child = static_cast<uint32_t>(tree.size());
        tree.emplace_back();
        tree.emplace_back();
        tree[task.node].left_or_first = left_child;
        tree[task.node].triangle_count = 0;
        tasks.push_back({left_child + 1, middle, task.end, task.depth + 1});
        tasks.push_back({left_child, task.begin, middle, task.depth + 1});
    }

    bvh.depth = writeQuantisedTree(tree, bvh.nodes);
    bvh.triangles.resize(primitive_count);
    for (uint32_t i = 0; i < primitive_count; ++i) bvh.triangles[i] = usable_triangles[order[i]];
    if (bvh.dropped_triangle_count > 0)
        std::fprintf(stderr, "bvh: dropped %zu zero-area or non-finite triangles of %zu\n",
                     bvh.dropped_triangle_count, triangle_count);
    return bvh;
}

}  // namespace gusuku::bake
