#include "gusuku_bake/closed_parts.h"

#include <cmath>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace gusuku::bake {

namespace {

// Welded vertex ids: positions on a kClosedPartWeldM grid share an id.
std::vector<uint32_t> weldedVertexIds(const TriangleMesh& mesh) {
    struct Key {
        int64_t x, y, z;
        bool operator==(const Key& other) const { return x == other.x && y == other.y && z == other.z; }
    };
    struct KeyHash {
        size_t operator()(const Key& key) const {
            return size_t(key.x * 73856093) ^ size_t(key.y * 19349663) ^ size_t(key.z * 83492791);
        }
    };
    std::unordered_map<Key, uint32_t, KeyHash> ids;
    std::vector<uint32_t> welded(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        const Key key{std::llround(double(p.x) / kClosedPartWeldM), std::llround(double(p.y) / kClosedPartWeldM),
                      std::llround(double(p.z) / kClosedPartWeldM)};
        welded[i] = ids.emplace(key, uint32_t(ids.size())).first->second;
    }
    return welded;
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

uint64_t edgeKey(uint32_t from, uint32_t to) { return uint64_t(from) << 32 | to; }

}  // namespace

std::vector<bool> closedOutwardTriangles(const TriangleMesh& mesh) {
    const size_t triangle_count = mesh.triangleCount();
    const std::vector<uint32_t> welded = weldedVertexIds(mesh);
    auto corner = [&](size_t triangle, int k) { return welded[mesh.indices[3 * triangle + size_t(k)]]; };
    auto degenerate = [&](size_t t) {
        return corner(t, 0) == corner(t, 1) || corner(t, 1) == corner(t, 2) || corner(t, 2) == corner(t, 0);
    };
    // Each directed edge with the triangles that run it (a count, and the first for joining parts).
    struct EdgeUse {
        uint32_t count = 0;
        uint32_t triangle = 0;
    };
    std::unordered_map<uint64_t, EdgeUse> directed;
    directed.reserve(triangle_count * 3);
    for (size_t t = 0; t < triangle_count; ++t) {
        if (degenerate(t)) continue;
        for (int k = 0; k < 3; ++k) {
            EdgeUse& use = directed[edgeKey(corner(t, k), corner(t, (k + 1) % 3))];
            if (use.count++ == 0) use.triangle = uint32_t(t);
        }
    }
    // Parts: triangles joined through edges run either way. A part is open when any of its edges is not run
    // exactly once each way (a boundary, a fold of three or more faces, or a flipped neighbour).
    std::vector<uint32_t> parent(triangle_count);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<bool> edge_is_open(triangle_count, false);
    for (size_t t = 0; t < triangle_count; ++t) {
        if (degenerate(t)) continue;
        for (int k = 0; k < 3; ++k) {
            const uint32_t from = corner(t, k), to = corner(t, (k + 1) % 3);
            const EdgeUse& forward = directed[edgeKey(from, to)];
            const auto reverse = directed.find(edgeKey(to, from));
            // Joined to every triangle on the edge either way (a flipped neighbour runs it the same way).
            parent[findRoot(parent, uint32_t(t))] = findRoot(parent, forward.triangle);
            if (reverse != directed.end())
                parent[findRoot(parent, uint32_t(t))] = findRoot(parent, reverse->second.triangle);
            if (forward.count != 1 || reverse == directed.end() || reverse->second.count != 1) edge_is_open[t] = true;
        }
    }
    // Per part: open or not, and six times its signed volume (sum of p0 . (p1 x p2)).
    std::vector<bool> part_open(triangle_count, false);
    std::vector<double> part_volume(triangle_count, 0.0);
    for (size_t t = 0; t < triangle_count; ++t) {
        if (degenerate(t)) continue;
        const uint32_t root = findRoot(parent, uint32_t(t));
        if (edge_is_open[t]) part_open[root] = true;
        const glm::dvec3 p0(mesh.positions[mesh.indices[3 * t]]), p1(mesh.positions[mesh.indices[3 * t + 1]]),
            p2(mesh.positions[mesh.indices[3 * t + 2]]);
        part_volume[root] += glm::dot(p0, glm::cross(p1, p2));
    }
    std::vector<bool> closed(triangle_count, false);
    for (size_t t = 0; t < triangle_count; ++t) {
        if (degenerate(t)) continue;
        const uint32_t root = findRoot(parent, uint32_t(t));
        closed[t] = !part_open[root] && part_volume[root] > 0.0;
    }
    return closed;
}

}  // namespace gusuku::bake
