// Binned-SAH BVH construction with spatial splits. Object splits (Wald 2007, "On fast Construction of SAH-based
// Bounding Volume Hierarchies"): per node, reference centroids are sorted into 32 bins along each axis and the
// plane between bins with the lowest surface-area cost is chosen. Spatial splits (Stich, Friedrich and Dietrich
// 2009, "Spatial Splits in Bounding Volume Hierarchies"): where the best object split leaves two boxes that
// overlap, planes through the node's box are tried too, a triangle crossing the plane going to both sides with
// the box of its piece on each. Why: a timber building's beams, rafters and roof planes are long thin triangles
// whose boxes are mostly empty and overlap everything near them; spatial splits cut the inner nodes and
// triangles a bake ray visits there. The tree is built with float boxes, then written in the GPU layout of bvh.h: each inner node holding its two children's boxes quantised to 16
// bits on its own grid.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "gusuku/formats/input_error.h"
#include "gusuku_bake/bvh.h"

namespace gusuku::bake {
namespace {

constexpr int kBinCount = 32;         // object split bins (centroids)
constexpr int kSpatialBinCount = 16;  // spatial split bins (the node's box)
// Spatial splits are tried only where the best object split's two boxes overlap by more than this fraction of
// the root's area (SBVH's alpha: below it the overlap costs little, and the search would only add references).
constexpr float kSpatialSplitOverlap = 1e-5f;
// Spatial splits stop adding references once there are this many per triangle (the cap bounds memory and the
// depth argument below).
constexpr double kMaxReferencesPerTriangle = 2.0;
// SAH costs in units of one ray/triangle test. A node visit on lavapipe (two child boxes fetched and tested)
// costs about as much as one triangle test.
constexpr float kTraversalCost = 1.0f;
constexpr float kTriangleCost = 1.0f;
// Below this depth the builder stops trusting SAH (and makes no more spatial splits) and halves at the centroid
// median, so that even pathological input (thousands of triangles in a spiral) stays within kBvhMaxDepth: at
// most 2 x 2^24 references, so 40 + log2(2^25 / 4) = 63 levels.
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

// One triangle as the builder sees it: its corners (for clipping) and the padding its boxes get.
struct Primitive {
    glm::vec3 corner[3];
    float pad;  // ~1e-6 of the triangle's largest coordinate, see paddedBox
};

// A reference to a triangle, or to the part of it inside `bounds` after spatial splits: one triangle may be
// referenced from several leaves, each reference boxing only its piece.
struct Reference {
    Box bounds;
    uint32_t primitive;
    float centroid(int axis) const { return 0.5f * (bounds.min[axis] + bounds.max[axis]); }
};

struct BuildTask {
    uint32_t node;
    std::vector<Reference> references;
    uint32_t depth;
};

struct ObjectSplit {
    int axis = -1;
    int bin = 0;  // references whose centroid falls in bins [0, bin] go left
    float cost = std::numeric_limits<float>::infinity();
    Box left, right;
};

struct SpatialSplit {
    int axis = -1;
    int bin = 0;  // the plane is the upper face of bin `bin`
    float cost = std::numeric_limits<float>::infinity();
};

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

int binOf(float centroid, float axis_min, float bin_scale) {
    const int bin = static_cast<int>((centroid - axis_min) * bin_scale);
    return std::clamp(bin, 0, kBinCount - 1);
}

ObjectSplit findObjectSplit(const std::vector<Reference>& references, const Box& centroid_bounds) {
    ObjectSplit best;
    const uint32_t count = static_cast<uint32_t>(references.size());
    for (int axis = 0; axis < 3; ++axis) {
        const float extent = centroid_bounds.max[axis] - centroid_bounds.min[axis];
        if (!(extent > 0.0f)) continue;
        const float bin_scale = kBinCount / extent;
        std::array<Box, kBinCount> bin_bounds;
        std::array<uint32_t, kBinCount> bin_counts{};
        for (const Reference& reference : references) {
            const int bin = binOf(reference.centroid(axis), centroid_bounds.min[axis], bin_scale);
            bin_bounds[bin].extend(reference.bounds);
            ++bin_counts[bin];
        }
        // Sweep from the right to get the cost of every right side, then from the left.
        std::array<float, kBinCount> right_area_times_count{};
        std::array<Box, kBinCount> right_boxes;
        Box right_box;
        uint32_t right_count = 0;
        for (int bin = kBinCount - 1; bin > 0; --bin) {
            right_box.extend(bin_bounds[bin]);
            right_count += bin_counts[bin];
            right_area_times_count[bin - 1] = right_box.halfArea() * static_cast<float>(right_count);
            right_boxes[bin - 1] = right_box;
        }
        Box left_box;
        uint32_t left_count = 0;
        for (int bin = 0; bin < kBinCount - 1; ++bin) {
            left_box.extend(bin_bounds[bin]);
            left_count += bin_counts[bin];
            if (left_count == 0 || left_count == count) continue;
            const float cost = left_box.halfArea() * static_cast<float>(left_count) + right_area_times_count[bin];
            if (cost < best.cost) {
                best.axis = axis;
                best.bin = bin;
                best.cost = cost;
                best.left = left_box;
                best.right = right_boxes[bin];
            }
        }
    }
    return best;
}

// Splits the part of `primitive` inside `within` (a reference's box, which holds that part with its padding)
// at the plane x[axis] = plane: the boxes of the pieces on either side, each padded by primitive.pad and cut to
// `within`; a side the triangle does not reach there comes out empty. Corners and edge crossings are computed
// in double; rounding them to float errs by at most half an ulp of the triangle's largest coordinate, far
// less than the pad (2^-20 of it), so the pieces' boxes together hold every point of the triangle in `within`.
void splitPrimitive(const Primitive& primitive, const Box& within, int axis, float plane, Box& left, Box& right) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    glm::dvec3 left_low(inf), left_high(-inf), right_low(inf), right_high(-inf);
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 a(primitive.corner[k]), b(primitive.corner[(k + 1) % 3]);
        if (a[axis] <= plane) {
            left_low = glm::min(left_low, a);
            left_high = glm::max(left_high, a);
        }
        if (a[axis] >= plane) {
            right_low = glm::min(right_low, a);
            right_high = glm::max(right_high, a);
        }
        if ((a[axis] < plane && b[axis] > plane) || (a[axis] > plane && b[axis] < plane)) {
            glm::dvec3 crossing = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
            crossing[axis] = plane;
            left_low = glm::min(left_low, crossing);
            left_high = glm::max(left_high, crossing);
            right_low = glm::min(right_low, crossing);
            right_high = glm::max(right_high, crossing);
        }
    }
    auto piece = [&](const glm::dvec3& low, const glm::dvec3& high) {
        Box box;
        if (!(low.x <= high.x)) return box;
        for (int a = 0; a < 3; ++a) {
            box.min[a] = std::max(static_cast<float>(low[a] - primitive.pad), within.min[a]);
            box.max[a] = std::min(static_cast<float>(high[a] + primitive.pad), within.max[a]);
            if (!(box.min[a] <= box.max[a])) return Box{};
        }
        return box;
    };
    left = piece(left_low, left_high);
    right = piece(right_low, right_high);
}

// Spatial split bins cover the node's box; bin b spans [plane(b), plane(b + 1)].
struct SpatialBins {
    float axis_min, axis_max, bin_size;
    float plane(int b) const { return b >= kSpatialBinCount ? axis_max : axis_min + bin_size * static_cast<float>(b); }
    // The bin holding a reference's lower (upper) face: a face exactly on a plane belongs to the side
    // the reference extends into, so a reference touching a plane is not counted on both sides.
    int binOfMin(float x) const {
        int b = std::clamp(static_cast<int>((x - axis_min) / bin_size), 0, kSpatialBinCount - 1);
        while (b > 0 && x < plane(b)) --b;
        while (b < kSpatialBinCount - 1 && x >= plane(b + 1)) ++b;
        return b;
    }
    int binOfMax(float x) const {
        int b = std::clamp(static_cast<int>((x - axis_min) / bin_size), 0, kSpatialBinCount - 1);
        while (b > 0 && x <= plane(b)) --b;
        while (b < kSpatialBinCount - 1 && x > plane(b + 1)) ++b;
        return b;
    }
};

SpatialBins spatialBins(const Box& bounds, int axis) {
    return {bounds.min[axis], bounds.max[axis], (bounds.max[axis] - bounds.min[axis]) / kSpatialBinCount};
}

// Extends bins first..last by the boxes of the pieces of `primitive` in each (the first and last bins reaching
// out to infinity, as the reference's box already bounds it there), cut to `within` and padded as in
// splitPrimitive. One pass over the edges: each crossing of a plane is computed once and shared by the two bins
// it separates, where chopping the triangle plane by plane would redo all three edges per plane.
void addPiecesToBins(const Primitive& primitive, const Box& within, const SpatialBins& bins, int axis, int first,
                     int last, std::array<Box, kSpatialBinCount>& bin_bounds) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<glm::dvec3, kSpatialBinCount> low, high;
    for (int b = first; b <= last; ++b) {
        low[b] = glm::dvec3(inf);
        high[b] = glm::dvec3(-inf);
    }
    auto add = [&](int b, const glm::dvec3& p) {
        low[b] = glm::min(low[b], p);
        high[b] = glm::max(high[b], p);
    };
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 a(primitive.corner[k]), b(primitive.corner[(k + 1) % 3]);
        // The corner's bin, clamped to the reference's; a corner exactly on a plane belongs to both sides.
        const int bin = std::clamp(bins.binOfMin(primitive.corner[k][axis]), first, last);
        add(bin, a);
        if (bin > first && primitive.corner[k][axis] == bins.plane(bin)) add(bin - 1, a);
        // Crossings of the planes strictly between the edge's ends, inside the reference's bin range.
        const float lo = std::min(primitive.corner[k][axis], primitive.corner[(k + 1) % 3][axis]);
        const float hi = std::max(primitive.corner[k][axis], primitive.corner[(k + 1) % 3][axis]);
        const int plane_end = std::min(last, bins.binOfMax(hi));
        for (int plane_index = std::max(first, bins.binOfMin(lo)) + 1; plane_index <= plane_end; ++plane_index) {
            const double plane = bins.plane(plane_index);
            if (!(plane > lo && plane < hi)) continue;
            glm::dvec3 crossing = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
            crossing[axis] = plane;
            add(plane_index - 1, crossing);
            add(plane_index, crossing);
        }
    }
    for (int b = first; b <= last; ++b) {
        if (!(low[b].x <= high[b].x)) continue;
        Box piece;
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
            piece.min[a] = std::max(static_cast<float>(low[b][a] - primitive.pad), within.min[a]);
            piece.max[a] = std::min(static_cast<float>(high[b][a] + primitive.pad), within.max[a]);
            empty = empty || !(piece.min[a] <= piece.max[a]);
        }
        if (!empty) bin_bounds[b].extend(piece);
    }
}

// SBVH's spatial split (Stich, Friedrich and Dietrich 2009, "Spatial Splits in Bounding Volume Hierarchies"):
// planes through the node's box, references straddling the plane go to both sides, each with the box of its
// piece on that side. Binned the same way as the object split; the cost counts each reference on every side
// it reaches.
SpatialSplit findSpatialSplit(const std::vector<Reference>& references, const std::vector<Primitive>& primitives,
                              const Box& bounds) {
    SpatialSplit best;
    for (int axis = 0; axis < 3; ++axis) {
        if (!(bounds.max[axis] - bounds.min[axis] > 0.0f)) continue;
        const SpatialBins bins = spatialBins(bounds, axis);
        if (!(bins.bin_size > 0.0f)) continue;
        std::array<Box, kSpatialBinCount> bin_bounds;
        std::array<uint32_t, kSpatialBinCount> entering{}, leaving{};
        for (const Reference& reference : references) {
            const int first = bins.binOfMin(reference.bounds.min[axis]);
            const int last = std::max(first, bins.binOfMax(reference.bounds.max[axis]));
            ++entering[first];
            ++leaving[last];
            if (first == last) {
                bin_bounds[first].extend(reference.bounds);
                continue;
            }
            addPiecesToBins(primitives[reference.primitive], reference.bounds, bins, axis, first, last, bin_bounds);
        }
        std::array<float, kSpatialBinCount> right_area_times_count{};
        Box right_box;
        uint32_t right_count = 0;
        for (int bin = kSpatialBinCount - 1; bin > 0; --bin) {
            right_box.extend(bin_bounds[bin]);
            right_count += leaving[bin];
            right_area_times_count[bin - 1] =
                right_count == 0 ? -1.0f : right_box.halfArea() * static_cast<float>(right_count);
        }
        Box left_box;
        uint32_t left_count = 0;
        for (int bin = 0; bin < kSpatialBinCount - 1; ++bin) {
            left_box.extend(bin_bounds[bin]);
            left_count += entering[bin];
            if (left_count == 0 || right_area_times_count[bin] < 0.0f) continue;
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

// Splits the references at the spatial split's plane; false (references untouched) if a side came out empty.
bool applySpatialSplit(const SpatialSplit& split, const std::vector<Primitive>& primitives, const Box& bounds,
                       std::vector<Reference>& references, std::vector<Reference>& left,
                       std::vector<Reference>& right) {
    const int axis = split.axis;
    const SpatialBins bins = spatialBins(bounds, axis);
    const float plane = bins.plane(split.bin + 1);
    left.clear();
    right.clear();
    for (const Reference& reference : references) {
        const int first = bins.binOfMin(reference.bounds.min[axis]);
        const int last = std::max(first, bins.binOfMax(reference.bounds.max[axis]));
        if (last <= split.bin) {
            left.push_back(reference);
        } else if (first > split.bin) {
            right.push_back(reference);
        } else {
            Box left_piece, right_piece;
            splitPrimitive(primitives[reference.primitive], reference.bounds, axis, plane, left_piece, right_piece);
            // A piece can come out empty when the reference's box reaches past the plane but the triangle
            // inside it does not: then the whole reference goes to the other side.
            if (!left_piece.empty()) left.push_back({left_piece, reference.primitive});
            if (!right_piece.empty()) right.push_back({right_piece, reference.primitive});
            if (left_piece.empty() && right_piece.empty()) left.push_back(reference);  // cannot happen; be safe
        }
    }
    if (!left.empty() && !right.empty()) return true;
    left.clear();
    right.clear();
    return false;
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

// The mesh's triangles a BVH can hold (finite, with a non-zero normal), in mesh order: their GPU records and
// the builder's view of each.
struct UsableTriangles {
    std::vector<BvhTriangleGpu> gpu;
    std::vector<Primitive> primitives;
    size_t dropped = 0;  ///< zero-area or non-finite triangles left out
};

void requireBvhInput(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_flags) {
    const size_t triangle_count = mesh.triangleCount();
    if (mesh.indices.size() % 3 != 0)
        throw InputError("mesh", "indices", "index count " + std::to_string(mesh.indices.size()) +
                                                " is not a multiple of 3");
    if (!triangle_flags.empty() && triangle_flags.size() != triangle_count)
        throw InputError("mesh", "triangle flags",
                         std::to_string(triangle_flags.size()) + " flags for " + std::to_string(triangle_count) +
                             " triangles");
}

// Throws InputError on a vertex index out of range.
UsableTriangles usableTriangles(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_flags) {
    const size_t triangle_count = mesh.triangleCount();
    UsableTriangles usable;
    usable.gpu.reserve(triangle_count);
    usable.primitives.reserve(triangle_count);
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
        const bool usable_triangle = finite(corner[0]) && finite(corner[1]) && finite(corner[2]) && finite(normal) &&
                                     (normal.x != 0.0f || normal.y != 0.0f || normal.z != 0.0f);
        if (!usable_triangle) {
            ++usable.dropped;
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
        usable.gpu.push_back(gpu);
        Primitive primitive;
        float largest = 0.0f;
        for (int k = 0; k < 3; ++k) {
            primitive.corner[k] = corner[k];
            largest = std::max({largest, std::fabs(corner[k].x), std::fabs(corner[k].y), std::fabs(corner[k].z)});
        }
        primitive.pad = largest * (1.0f / 1048576.0f) + 1e-30f;  // as paddedBox, but from the whole triangle
        usable.primitives.push_back(primitive);
    }
    return usable;
}

// A BVH of no usable triangle. The slab test is symmetric in min and max, so "inverted" bounds would still be
// hit; instead the root is a leaf holding one placeholder whose zero edges make Moller-Trumbore's determinant
// zero.
void writePlaceholderTree(Bvh& bvh) {
    BvhTriangleGpu placeholder{};
    placeholder.triangle_index = kBvhNoTriangle;
    bvh.triangles.push_back(placeholder);
    FloatNode leaf;
    leaf.bounds.extend(glm::vec3(0.0f));
    leaf.bounds = paddedBox(leaf.bounds);
    leaf.triangle_count = 1;
    leaf.leaf = true;
    bvh.depth = writeQuantisedTree({leaf}, bvh.nodes);
}

// The tree as built in float boxes, and the primitive of every leaf slot in leaf order.
struct FloatTree {
    std::vector<FloatNode> nodes;
    std::vector<uint32_t> leaf_primitives;
};

// Top-down build: each task's references become a leaf, or are split (spatially, by object bins, or at the
// centroid median) into two child tasks. Tasks are a stack whose left child is popped first, so leaves come out
// in left-to-right order.
class FloatTreeBuilder {
public:
    explicit FloatTreeBuilder(const std::vector<Primitive>& primitives) : primitives_(primitives) {}

    FloatTree build() {
        const uint32_t primitive_count = static_cast<uint32_t>(primitives_.size());
        Box root_bounds;
        std::vector<Reference> root_references = rootReferences(root_bounds);
        overlap_threshold_ = kSpatialSplitOverlap * root_bounds.halfArea();
        reference_budget_ = static_cast<size_t>(kMaxReferencesPerTriangle * primitive_count);
        reference_count_ = primitive_count;
        tree_.nodes.reserve(2 * primitive_count);
        tree_.nodes.emplace_back();
        tree_.leaf_primitives.reserve(primitive_count);
        tasks_.push_back({0, std::move(root_references), 1});
        while (!tasks_.empty()) {
            BuildTask task = std::move(tasks_.back());
            tasks_.pop_back();
            buildNode(task);
        }
        return std::move(tree_);
    }

private:
    // One reference per primitive, boxing the whole triangle with its padding; root_bounds encloses them all.
    std::vector<Reference> rootReferences(Box& root_bounds) const {
        const uint32_t primitive_count = static_cast<uint32_t>(primitives_.size());
        std::vector<Reference> references(primitive_count);
        for (uint32_t i = 0; i < primitive_count; ++i) {
            Box box;
            for (const glm::vec3& p : primitives_[i].corner) box.extend(p);
            box.min -= glm::vec3(primitives_[i].pad);
            box.max += glm::vec3(primitives_[i].pad);
            references[i] = {box, i};
            root_bounds.extend(box);
        }
        return references;
    }

    void buildNode(BuildTask& task) {
        std::vector<Reference>& references = task.references;
        Box bounds, centroid_bounds;
        for (const Reference& reference : references) {
            bounds.extend(reference.bounds);
            centroid_bounds.extend(0.5f * (reference.bounds.min + reference.bounds.max));
        }
        tree_.nodes[task.node].bounds = paddedBox(bounds);
        const uint32_t count = static_cast<uint32_t>(references.size());
        if (count == 1) {
            makeLeaf(task.node, references);
            return;
        }
        const bool sah = task.depth < kMedianSplitDepth;
        const ObjectSplit object = sah ? findObjectSplit(references, centroid_bounds) : ObjectSplit{};
        const SpatialSplit spatial = sah ? spatialSplitWherePays(references, object, bounds) : SpatialSplit{};
        const float best_cost = std::min(object.cost, spatial.cost);
        const float leaf_cost = kTriangleCost * static_cast<float>(count);
        const float split_cost = kTraversalCost + kTriangleCost * best_cost / std::max(bounds.halfArea(), 1e-30f);
        if (count <= kBvhMaxLeafTriangles && (!(best_cost < std::numeric_limits<float>::infinity()) ||
                                              leaf_cost <= split_cost)) {
            makeLeaf(task.node, references);
            return;
        }
        std::vector<Reference> left, right;
        bool split_done = false;
        if (spatial.cost < object.cost) {
            split_done = applySpatialSplit(spatial, primitives_, bounds, references, left, right);
            if (split_done) reference_count_ += left.size() + right.size() - count;
        }
        // The object split partitions `references` in place even when a side comes out empty; the median split
        // then works on that order.
        if (!split_done && object.axis >= 0) split_done = applyObjectSplit(object, centroid_bounds, references, left, right);
        if (!split_done) applyMedianSplit(centroid_bounds, references, left, right);
        pushChildren(task, std::move(left), std::move(right));
    }

    void makeLeaf(uint32_t node, const std::vector<Reference>& references) {
        tree_.nodes[node].left_or_first = static_cast<uint32_t>(tree_.leaf_primitives.size());
        tree_.nodes[node].triangle_count = static_cast<uint32_t>(references.size());
        tree_.nodes[node].leaf = true;
        for (const Reference& reference : references) tree_.leaf_primitives.push_back(reference.primitive);
    }

    // A spatial split can add up to `count` references: it is searched only within the budget, only where the
    // object split's children overlap enough for it to pay, and not in nodes small enough to be a leaf (there
    // the search costs build time without fewer nodes or triangles visited per ray). No split (infinite cost)
    // otherwise.
    SpatialSplit spatialSplitWherePays(const std::vector<Reference>& references, const ObjectSplit& object,
                                       const Box& bounds) const {
        const size_t count = references.size();
        if (!(count > kBvhMaxLeafTriangles && reference_count_ + count <= reference_budget_)) return {};
        Box overlap;
        overlap.min = glm::max(object.left.min, object.right.min);
        overlap.max = glm::min(object.left.max, object.right.max);
        const bool overlapping = object.axis < 0 || (overlap.min.x <= overlap.max.x &&
                                                     overlap.min.y <= overlap.max.y &&
                                                     overlap.min.z <= overlap.max.z);
        if (overlapping && (object.axis < 0 || overlap.halfArea() > overlap_threshold_))
            return findSpatialSplit(references, primitives_, bounds);
        return {};
    }

    // Partitions the references by the object split's bin; false when a side came out empty.
    static bool applyObjectSplit(const ObjectSplit& object, const Box& centroid_bounds,
                                 std::vector<Reference>& references, std::vector<Reference>& left,
                                 std::vector<Reference>& right) {
        const int axis = object.axis;
        const float axis_min = centroid_bounds.min[axis];
        const float bin_scale = kBinCount / (centroid_bounds.max[axis] - axis_min);
        const auto middle = std::partition(references.begin(), references.end(), [&](const Reference& r) {
            return binOf(r.centroid(axis), axis_min, bin_scale) <= object.bin;
        });
        if (middle == references.begin() || middle == references.end()) return false;
        left.assign(references.begin(), middle);
        right.assign(middle, references.end());
        return true;
    }

    // No SAH split (too deep, or all centroids coincide): halve at the median of the widest axis, which bounds
    // the depth and still makes progress when every centroid is the same point.
    static void applyMedianSplit(const Box& centroid_bounds, std::vector<Reference>& references,
                                 std::vector<Reference>& left, std::vector<Reference>& right) {
        const glm::vec3 extent = centroid_bounds.max - centroid_bounds.min;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const auto middle = references.begin() + references.size() / 2;
        std::nth_element(references.begin(), middle, references.end(),
                         [&](const Reference& a, const Reference& b) { return a.centroid(axis) < b.centroid(axis); });
        left.assign(references.begin(), middle);
        right.assign(middle, references.end());
    }

    void pushChildren(const BuildTask& task, std::vector<Reference> left, std::vector<Reference> right) {
        const uint32_t left_child = static_cast<uint32_t>(tree_.nodes.size());
        tree_.nodes.emplace_back();
        tree_.nodes.emplace_back();
        tree_.nodes[task.node].left_or_first = left_child;
        tree_.nodes[task.node].triangle_count = 0;
        // The left child is popped first, so leaves come out in left-to-right order.
        tasks_.push_back({left_child + 1, std::move(right), task.depth + 1});
        tasks_.push_back({left_child, std::move(left), task.depth + 1});
    }

    const std::vector<Primitive>& primitives_;
    float overlap_threshold_ = 0.0f;  // spatial splits only where the object split's overlap is above this
    size_t reference_budget_ = 0;     // kMaxReferencesPerTriangle per primitive
    size_t reference_count_ = 0;      // references in the tree so far (spatial splits add some)
    FloatTree tree_;
    std::vector<BuildTask> tasks_;
};

}  // namespace

Bvh buildBvh(const TriangleMesh& mesh, const std::vector<uint32_t>& triangle_flags) {
    requireBvhInput(mesh, triangle_flags);
    const UsableTriangles usable = usableTriangles(mesh, triangle_flags);
    Bvh bvh;
    bvh.dropped_triangle_count = usable.dropped;
    if (usable.primitives.empty()) {
        writePlaceholderTree(bvh);
        return bvh;
    }
    if (usable.primitives.size() > kBvhMaxTriangles)
        throw InputError("mesh", "triangles",
                         std::to_string(usable.primitives.size()) + " triangles, above the BVH's limit of " +
                             std::to_string(kBvhMaxTriangles));
    const FloatTree tree = FloatTreeBuilder(usable.primitives).build();
    bvh.depth = writeQuantisedTree(tree.nodes, bvh.nodes);
    bvh.triangles.resize(tree.leaf_primitives.size());
    for (size_t i = 0; i < tree.leaf_primitives.size(); ++i) bvh.triangles[i] = usable.gpu[tree.leaf_primitives[i]];
    // Dropped triangles are the caller's to report (the bake adds a warning to the manifest); printing here put
    // a stray line before the one-line error of a bake that is then refused.
    return bvh;
}

}  // namespace gusuku::bake
