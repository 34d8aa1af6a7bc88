// The software BVH: the CPU traversal against an independent double-precision brute force over every
// triangle, the tree's structural invariants, bad triangles, and the GLSL traversal (bvh_probe.comp) against
// the CPU traversal on the real device.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <gtest/gtest.h>

#include "bvh_probe_comp_spv.h"
#include "gpu_test_support.h"
#include "gusuku/gpu/gpu_compute.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/bvh.h"

namespace gusuku::bake {
namespace {

using glm::dvec3;
using glm::vec3;


struct Ray {
    vec3 origin;
    vec3 direction;
    float t_max;
    uint32_t skip_flags;
};

// ---- meshes ---------------------------------------------------------------------------------------------

void addTriangle(TriangleMesh& mesh, vec3 a, vec3 b, vec3 c) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
}

vec3 randomInBox(std::mt19937& rng, vec3 lo, vec3 hi) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    return lo + (hi - lo) * vec3(unit(rng), unit(rng), unit(rng));
}

vec3 randomUnitVector(std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float z = 2.0f * unit(rng) - 1.0f;
    const float phi = 2.0f * std::numbers::pi_v<float> * unit(rng);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Triangles of mixed sizes (a few metres down to centimetres) scattered in a 10 m cube, randomly oriented.
TriangleMesh randomSoup(uint32_t triangle_count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> log_size(std::log(0.02f), std::log(3.0f));
    TriangleMesh mesh;
    for (uint32_t i = 0; i < triangle_count; ++i) {
        const vec3 centre = randomInBox(rng, vec3(-5.0f), vec3(5.0f));
        const float size = std::exp(log_size(rng));
        addTriangle(mesh, centre + size * randomUnitVector(rng), centre + size * randomUnitVector(rng),
                    centre + size * randomUnitVector(rng));
    }
    return mesh;
}

// Indexed heightfield of (cells x cells) quads over [-extent, extent]^2, sharing vertices: a watertight surface.
void addHeightfield(TriangleMesh& mesh, uint32_t cells, float extent) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (uint32_t j = 0; j <= cells; ++j)
        for (uint32_t i = 0; i <= cells; ++i) {
            const float x = -extent + 2.0f * extent * i / cells;
            const float y = -extent + 2.0f * extent * j / cells;
            mesh.positions.push_back({x, y, 0.3f * std::sin(0.7f * x) * std::cos(0.5f * y)});
        }
    for (uint32_t j = 0; j < cells; ++j)
        for (uint32_t i = 0; i < cells; ++i) {
            const uint32_t v00 = base + j * (cells + 1) + i, v10 = v00 + 1, v01 = v00 + cells + 1, v11 = v01 + 1;
            mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
        }
}

// Axis-aligned closed box, counter-clockwise seen from outside.
void addBox(TriangleMesh& mesh, vec3 lo, vec3 hi) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (int k = 0; k < 8; ++k)
        mesh.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads)
        mesh.indices.insert(mesh.indices.end(),
                            {base + q[0], base + q[1], base + q[2], base + q[0], base + q[2], base + q[3]});
}

// A "site": a heightfield ground with box "buildings" standing on it.
TriangleMesh structuredScene(uint32_t ground_cells, uint32_t box_count, uint32_t seed) {
    std::mt19937 rng(seed);
    TriangleMesh mesh;
    addHeightfield(mesh, ground_cells, 20.0f);
    for (uint32_t i = 0; i < box_count; ++i) {
        const vec3 lo = randomInBox(rng, vec3(-18.0f, -18.0f, -0.5f), vec3(16.0f, 16.0f, 1.0f));
        const vec3 size = randomInBox(rng, vec3(0.2f, 0.2f, 0.5f), vec3(2.0f, 2.0f, 6.0f));
        addBox(mesh, lo, lo + size);
    }
    return mesh;
}

// Long thin triangles, as in a timber building's beams and rafters: boxes 4-16 m long and 5-30 cm thick along
// random (mostly not axis-aligned) directions, long slivers, and a heightfield ground. Their bounding boxes
// are mostly empty space and overlap one another: the case spatial splits are for.
TriangleMesh beamScene(uint32_t beam_count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    TriangleMesh mesh;
    addHeightfield(mesh, 16, 20.0f);
    for (uint32_t i = 0; i < beam_count; ++i) {
        const vec3 centre = randomInBox(rng, vec3(-12.0f, -12.0f, 0.5f), vec3(12.0f, 12.0f, 8.0f));
        vec3 along = randomUnitVector(rng);
        if (i % 5 == 0) along = vec3(1.0f, 0.0f, 0.0f);  // some axis-aligned, as most beams are
        along.z *= 0.4f;  // mostly near-horizontal
        along = glm::normalize(along);
        const vec3 side = glm::normalize(glm::cross(along, std::fabs(along.z) < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0)));
        const vec3 up = glm::cross(side, along);
        const float length = 4.0f + 12.0f * unit(rng);
        const float thickness = 0.05f + 0.25f * unit(rng);
        if (i % 4 == 3) {  // a sliver: one long thin triangle
            addTriangle(mesh, centre - 0.5f * length * along, centre + 0.5f * length * along,
                        centre + thickness * side);
            continue;
        }
        vec3 corner[8];
        for (int k = 0; k < 8; ++k)
            corner[k] = centre + (k & 1 ? 0.5f : -0.5f) * length * along + (k & 2 ? 0.5f : -0.5f) * thickness * side +
                        (k & 4 ? 0.5f : -0.5f) * thickness * up;
        const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), corner, corner + 8);
        const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads)
            mesh.indices.insert(mesh.indices.end(),
                                {base + q[0], base + q[1], base + q[2], base + q[0], base + q[2], base + q[3]});
    }
    return mesh;
}

std::vector<Ray> randomRays(uint32_t count, vec3 lo, vec3 hi, uint32_t seed, float t_max = 1e30f) {
    std::mt19937 rng(seed);
    std::vector<Ray> rays(count);
    for (Ray& ray : rays) {
        ray.origin = randomInBox(rng, lo, hi);
        // Mostly unit directions, some scaled (t is in units of |direction|), some with zero components.
        ray.direction = randomUnitVector(rng);
        const uint32_t kind = rng() % 8;
        if (kind == 0) ray.direction *= 3.5f;
        if (kind == 1) ray.direction.x = 0.0f;
        if (kind == 2) ray.direction = vec3(0.0f, 0.0f, ray.direction.z < 0 ? -1.0f : 1.0f);
        ray.t_max = t_max;
        ray.skip_flags = 0;
    }
    return rays;
}

// ---- independent reference: double-precision Moller-Trumbore over every source triangle ---------------

struct BruteForceResult {
    bool hit = false;
    double t = 0.0;
    std::set<uint32_t> closest_triangles;  // every triangle whose hit ties the closest within 1e-5 relative
    // The float BVH may legitimately differ: some triangle is hit (or missed) within 1e-5 of its edge, or
    // nearly edge-on, or within 1e-5 relative of t_max.
    bool ambiguous = false;
};

BruteForceResult bruteForce(const TriangleMesh& mesh, const std::vector<uint32_t>& flags, const Ray& ray) {
    struct Candidate {
        uint32_t triangle;
        double t;
    };
    std::vector<Candidate> hits;
    BruteForceResult result;
    const dvec3 origin(ray.origin), direction(ray.direction);
    const double tolerance = 1e-5;
    for (uint32_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        if (!flags.empty() && (flags[triangle] & ray.skip_flags) != 0) continue;
        const dvec3 p0(mesh.positions[mesh.indices[3 * triangle]]);
        const dvec3 p1(mesh.positions[mesh.indices[3 * triangle + 1]]);
        const dvec3 p2(mesh.positions[mesh.indices[3 * triangle + 2]]);
        if (!std::isfinite(p0.x + p0.y + p0.z + p1.x + p1.y + p1.z + p2.x + p2.y + p2.z)) continue;
        const dvec3 e1 = p1 - p0, e2 = p2 - p0;
        const dvec3 normal = glm::cross(e1, e2);
        if (glm::length(normal) == 0.0) continue;
        const dvec3 p = glm::cross(direction, e2);
        const double det = glm::dot(e1, p);
        if (det == 0.0) continue;
        const dvec3 s = origin - p0;
        const double u = glm::dot(s, p) / det;
        const dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(direction, q) / det;
        const double t = glm::dot(e2, q) / det;
        const double grazing = std::fabs(glm::dot(normal, direction)) / (glm::length(normal) * glm::length(direction));
        const double edge_distance = std::min({u, v, 1.0 - u - v});
        const bool inside = edge_distance >= 0.0;
        const bool near_edge = std::fabs(edge_distance) < tolerance;
        if (t > 0.0 && t < ray.t_max && inside) hits.push_back({triangle, t});
        if (t > -tolerance * std::max(1.0, t) && t < ray.t_max * (1.0 + tolerance) && (inside || near_edge) &&
            (near_edge || grazing < tolerance || std::fabs(t - ray.t_max) < tolerance * ray.t_max ||
             std::fabs(t) < tolerance))
            result.ambiguous = true;
    }
    if (hits.empty()) return result;
    result.hit = true;
    result.t = std::min_element(hits.begin(), hits.end(), [](auto& a, auto& b) { return a.t < b.t; })->t;
    for (const Candidate& c : hits)
        if (c.t <= result.t * (1.0 + tolerance)) result.closest_triangles.insert(c.triangle);
    return result;
}

// Checks traceClosestCpu and occludedCpu on every ray (skipping the few too ambiguous to judge).
void expectMatchesBruteForce(const TriangleMesh& mesh, const std::vector<uint32_t>& flags, const Bvh& bvh,
                               const std::vector<Ray>& rays) {
    size_t ambiguous = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& ray = rays[i];
        const BruteForceResult expected = bruteForce(mesh, flags, ray);
        if (expected.ambiguous) {
            ++ambiguous;
            continue;
        }
        const std::optional<BvhHit> hit = traceClosestCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
        const bool occluded = occludedCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
        EXPECT_EQ(occluded, expected.hit) << "ray " << i;
        if (hit.has_value() != expected.hit) {
            ADD_FAILURE() << "ray " << i << ": BVH " << (hit ? "hit" : "missed") << ", brute force did not";
            continue;
        }
        if (!expected.hit) continue;
        ++hits;
        // 1e-5 relative; for hits close to the origin float rounding is relative to the coordinates, not t.
        const double t_tolerance =
            1e-5 * (expected.t + (glm::length(ray.origin) + 1.0) / glm::length(ray.direction));
        EXPECT_NEAR(hit->t, expected.t, t_tolerance) << "ray " << i;
        EXPECT_TRUE(expected.closest_triangles.count(hit->triangle_index)) << "ray " << i << " hit "
                                                                           << hit->triangle_index;
        // Barycentrics in the source vertex order reproduce the hit point; front_face follows the winding.
        const uint32_t tri = hit->triangle_index;
        const vec3 p0 = mesh.positions[mesh.indices[3 * tri]], p1 = mesh.positions[mesh.indices[3 * tri + 1]],
                   p2 = mesh.positions[mesh.indices[3 * tri + 2]];
        const float u = hit->barycentric_u, v = hit->barycentric_v;
        const vec3 interpolated = (1.0f - u - v) * p0 + u * p1 + v * p2;
        const vec3 along_ray = ray.origin + hit->t * ray.direction;
        EXPECT_LT(glm::length(interpolated - along_ray), 1e-4f * (1.0f + glm::length(along_ray))) << "ray " << i;
        const dvec3 normal = glm::cross(dvec3(p1) - dvec3(p0), dvec3(p2) - dvec3(p0));
        const bool front = glm::dot(normal, dvec3(ray.direction)) < 0.0;
        EXPECT_EQ(hit->front_face, front) << "ray " << i;
    }
    EXPECT_LT(ambiguous, rays.size() / 100 + 1) << "too many rays near edges to be a fair test";
    EXPECT_GT(hits, rays.size() / 10) << "the rays should hit something";
}

// ---- structure ------------------------------------------------------------------------------------------

// Every inner node reached once, every leaf slot reached once, leaves of <= kBvhMaxLeafTriangles holding a
// triangle at most once, every usable triangle in at least one leaf (spatial splits reference a triangle from
// several leaves, each boxing only its piece) and at most 2x as many slots as triangles, and the depth bound.
// Coverage: points all over each triangle (corners, edge midpoints, random interior points, computed from the
// stored v0 and edges as the traversal sees them) each lie inside every decoded box on the way down to at least
// one of the triangle's leaves; otherwise a ray could pass through the triangle there unseen. (A child's box
// may overhang its parent's by a quantisation step: only the triangles must be inside.)
void expectWellFormed(const Bvh& bvh, size_t usable_triangle_count) {
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_GE(bvh.triangles.size(), usable_triangle_count);
    EXPECT_LE(bvh.triangles.size(), std::max<size_t>(2 * usable_triangle_count, 1));
    std::vector<int> triangle_seen(bvh.triangles.size(), 0);
    std::vector<BvhBox> slot_box(bvh.triangles.size());  // the boxes on the way down to the slot, intersected
    std::vector<int> node_seen(bvh.nodes.size(), 0);
    struct Visit {
        uint32_t node;
        uint32_t depth;
        BvhBox box;  // the intersection of the boxes on the way down (the root: everything)
    };
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<Visit> todo{{0, 1, BvhBox{vec3(-inf), vec3(inf)}}};
    uint32_t deepest = 0;
    while (!todo.empty()) {
        const Visit visit = todo.back();
        todo.pop_back();
        ASSERT_LT(visit.node, bvh.nodes.size());
        ++node_seen[visit.node];
        deepest = std::max(deepest, visit.depth);
        const BvhNodeGpu& node = bvh.nodes[visit.node];
        for (int c = 0; c < 2; ++c) {
            const BvhBox decoded = decodeBvhChildBox(node, c);
            const BvhBox box{glm::max(decoded.min, visit.box.min), glm::min(decoded.max, visit.box.max)};
            const uint32_t ref = node.child[c];
            if ((ref & kBvhChildLeaf) == 0) {
                todo.push_back({ref, visit.depth + 1, box});
                continue;
            }
            deepest = std::max(deepest, visit.depth + 1);
            EXPECT_LE(bvhLeafCount(ref), kBvhMaxLeafTriangles);
            ASSERT_LE(bvhLeafFirst(ref) + bvhLeafCount(ref), bvh.triangles.size());
            std::set<uint32_t> in_leaf;
            for (uint32_t i = bvhLeafFirst(ref); i < bvhLeafFirst(ref) + bvhLeafCount(ref); ++i) {
                ++triangle_seen[i];
                slot_box[i] = box;
                EXPECT_TRUE(in_leaf.insert(bvh.triangles[i].triangle_index).second) << "a leaf holds a triangle twice";
            }
        }
    }
    for (size_t i = 0; i < triangle_seen.size(); ++i) ASSERT_EQ(triangle_seen[i], 1) << "triangle slot " << i;
    for (size_t i = 0; i < node_seen.size(); ++i) ASSERT_EQ(node_seen[i], 1) << "node " << i;
    EXPECT_EQ(deepest, bvh.depth);
    EXPECT_LE(bvh.depth, kBvhMaxDepth);

    std::map<uint32_t, std::vector<uint32_t>> slots_of;  // source triangle -> its slots
    for (uint32_t i = 0; i < bvh.triangles.size(); ++i) slots_of[bvh.triangles[i].triangle_index].push_back(i);
    EXPECT_EQ(slots_of.size(), usable_triangle_count) << "every usable triangle is in some leaf";
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    size_t uncovered = 0;
    for (const auto& [source, slots] : slots_of) {
        const BvhTriangleGpu& t = bvh.triangles[slots[0]];
        const vec3 v0(t.v0[0], t.v0[1], t.v0[2]), e1(t.edge1[0], t.edge1[1], t.edge1[2]),
            e2(t.edge2[0], t.edge2[1], t.edge2[2]);
        std::vector<std::pair<float, float>> uvs = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0, 0.5f}, {0.5f, 0.5f}};
        for (int k = 0; k < 24; ++k) {
            float u = unit(rng), v = unit(rng);
            if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
            uvs.push_back({u, v});
        }
        for (const auto& [u, v] : uvs) {
            const vec3 p = u == 0.0f && v == 0.0f ? v0 : v0 + u * e1 + v * e2;
            bool inside = false;
            for (uint32_t slot : slots) {
                const BvhBox& box = slot_box[slot];
                inside = inside ||
                         (glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max)));
            }
            uncovered += !inside;
        }
    }
    EXPECT_EQ(uncovered, 0u) << "points of triangles outside all of their leaves' boxes";
}

// ---- CPU tests -----------------------------------------------------------------------------------------

TEST(BvhCpu, RandomSoupMatchesBruteForce) {
    const TriangleMesh mesh = randomSoup(3000, 7);
    const Bvh bvh = buildBvh(mesh, {});
    EXPECT_EQ(bvh.dropped_triangle_count, 0u);
    expectWellFormed(bvh, mesh.triangleCount());
    const std::vector<Ray> rays = randomRays(3000, vec3(-6.0f), vec3(6.0f), 11);
    expectMatchesBruteForce(mesh, {}, bvh, rays);
    // Short rays: t_max must cut hits off.
    expectMatchesBruteForce(mesh, {}, bvh, randomRays(2000, vec3(-6.0f), vec3(6.0f), 12, 1.5f));
}

TEST(BvhCpu, StructuredSceneMatchesBruteForce) {
    const TriangleMesh mesh = structuredScene(40, 60, 3);
    const Bvh bvh = buildBvh(mesh, {});
    EXPECT_EQ(bvh.dropped_triangle_count, 0u);
    expectWellFormed(bvh, mesh.triangleCount());
    expectMatchesBruteForce(mesh, {}, bvh, randomRays(3000, vec3(-20.0f, -20.0f, 0.5f), vec3(20.0f, 20.0f, 8.0f), 5));
}

// Spatial splits: triangles referenced from several leaves with clipped boxes must still give exactly the
// brute force's closest hit, and a any-hit answer, on rays from everywhere among the beams, short ones included.
TEST(BvhCpu, LongThinTrianglesMatchBruteForce) {
    const TriangleMesh mesh = beamScene(400, 21);
    const Bvh bvh = buildBvh(mesh, {});
    expectWellFormed(bvh, mesh.triangleCount());
    EXPECT_GT(bvh.triangles.size(), mesh.triangleCount() * 11 / 10) << "spatial splits should reference some "
                                                                        "long triangles more than once";
    const vec3 lo(-14.0f, -14.0f, 0.3f), hi(14.0f, 14.0f, 9.0f);
    expectMatchesBruteForce(mesh, {}, bvh, randomRays(3000, lo, hi, 23));
    expectMatchesBruteForce(mesh, {}, bvh, randomRays(2000, lo, hi, 24, 2.0f));
}

std::optional<BvhHit> exactClosest(const Bvh& bvh, const Ray& ray);  // below, with the bit-for-bit tests

// The worst case for spatial splits: long triangles all crossing one point, so no plane separates them. The
// reference budget and the depth bound must hold, and the traversal must still be exact.
TEST(BvhCpu, LongTrianglesThroughOnePointStayWithinBudgetAndDepth) {
    TriangleMesh mesh;
    std::mt19937 rng(9);
    for (int i = 0; i < 3000; ++i) {
        const vec3 along = randomUnitVector(rng) * 10.0f;
        const vec3 side = randomUnitVector(rng) * 0.01f;
        addTriangle(mesh, -along, along, side);
    }
    const Bvh bvh = buildBvh(mesh, {});
    expectWellFormed(bvh, mesh.triangleCount());
    const std::vector<Ray> rays = randomRays(1000, vec3(-3.0f), vec3(3.0f), 4);
    for (const Ray& ray : rays) {
        const auto expected = exactClosest(bvh, ray);
        const auto got = traceClosestCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
        ASSERT_EQ(got.has_value(), expected.has_value());
        if (got) {
            EXPECT_EQ(got->triangle_index, expected->triangle_index);
        }
    }
}

TEST(BvhCpu, WatertightAcrossSharedEdgesAndVertices) {
    // Rays straight down through grid vertices and edge midpoints of an indexed heightfield must all hit:
    // these are exactly the points where a non-watertight test lets rays through.
    TriangleMesh mesh;
    const uint32_t cells = 32;
    const float extent = 8.0f;
    addHeightfield(mesh, cells, extent);
    const Bvh bvh = buildBvh(mesh, {});
    size_t missed = 0, tested = 0;
    for (uint32_t j = 1; j < 2 * cells; ++j)
        for (uint32_t i = 1; i < 2 * cells; ++i) {
            const float x = -extent + extent * i / cells, y = -extent + extent * j / cells;
            for (const vec3 direction : {vec3(0, 0, -1), glm::normalize(vec3(0.3f, -0.2f, -1.0f))}) {
                // Passes over (x, y, 0) after rising 5 m: straight down, that is a vertex or an edge midpoint.
                const vec3 start = vec3(x, y, 0.0f) - 5.0f / -direction.z * direction;
                ++tested;
                if (!occludedCpu(bvh, start, direction, 1e30f, 0) ||
                    !traceClosestCpu(bvh, start, direction, 1e30f, 0))
                    ++missed;
            }
        }
    EXPECT_EQ(missed, 0u) << "of " << tested;
}

TEST(BvhCpu, SkipFlagsIgnoreFlaggedTriangles) {
    // A "building" (flag 1) floating above a ground quad (flag 2): rays straight down hit the building, or
    // the ground when the building is skipped, or nothing when both are.
    TriangleMesh mesh;
    addTriangle(mesh, {-10, -10, 0}, {10, -10, 0}, {10, 10, 0});
    addTriangle(mesh, {-10, -10, 0}, {10, 10, 0}, {-10, 10, 0});
    addBox(mesh, {-1, -1, 1}, {1, 1, 3});
    std::vector<uint32_t> flags(mesh.triangleCount(), 1u);
    flags[0] = flags[1] = 2u;
    const Bvh bvh = buildBvh(mesh, flags);
    const vec3 origin(0.25f, 0.3f, 10.0f), down(0, 0, -1);
    const auto building = traceClosestCpu(bvh, origin, down, 1e30f, 0);
    ASSERT_TRUE(building);
    EXPECT_NEAR(building->t, 7.0f, 1e-5f);
    EXPECT_GE(building->triangle_index, 2u);
    EXPECT_TRUE(building->front_face);  // the box's top, seen from above
    const auto ground = traceClosestCpu(bvh, origin, down, 1e30f, 1u);
    ASSERT_TRUE(ground);
    EXPECT_NEAR(ground->t, 10.0f, 1e-5f);
    EXPECT_LT(ground->triangle_index, 2u);
    EXPECT_TRUE(ground->front_face);
    EXPECT_FALSE(traceClosestCpu(bvh, origin, down, 1e30f, 3u));
    EXPECT_TRUE(occludedCpu(bvh, origin, down, 1e30f, 1u));
    EXPECT_FALSE(occludedCpu(bvh, origin, down, 1e30f, 3u));
    EXPECT_FALSE(occludedCpu(bvh, origin, down, 9.9f, 1u));  // ground beyond t_max
    // From inside the box, upwards: the lid is seen from behind.
    const auto lid = traceClosestCpu(bvh, vec3(0, 0, 2), vec3(0, 0, 1), 1e30f, 0);
    ASSERT_TRUE(lid);
    EXPECT_FALSE(lid->front_face);
    EXPECT_NEAR(lid->t, 1.0f, 1e-5f);

    // And against brute force with random flags on a soup.
    const TriangleMesh soup = randomSoup(1500, 21);
    std::vector<uint32_t> soup_flags(soup.triangleCount());
    std::mt19937 rng(4);
    for (uint32_t& f : soup_flags) f = 1u << (rng() % 3);
    const Bvh soup_bvh = buildBvh(soup, soup_flags);
    std::vector<Ray> rays = randomRays(1500, vec3(-6.0f), vec3(6.0f), 8);
    for (Ray& ray : rays) ray.skip_flags = rng() % 4;
    expectMatchesBruteForce(soup, soup_flags, soup_bvh, rays);
}

TEST(BvhCpu, DropsDegenerateAndNonFiniteTriangles) {
    TriangleMesh mesh = randomSoup(200, 9);
    const size_t good = mesh.triangleCount();
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    addTriangle(mesh, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});     // a point
    addTriangle(mesh, {0, 0, 0}, {1, 1, 1}, {2, 2, 2});     // collinear
    addTriangle(mesh, {0, 0, 0}, {nan, 1, 1}, {2, 0, 2});   // NaN vertex
    addTriangle(mesh, {0, 0, 0}, {1, inf, 1}, {2, 0, 2});   // infinite vertex
    addTriangle(mesh, {-1e30f, 0, 0}, {1e30f, 1e30f, 0}, {0, 1e30f, 1e30f});  // cross product overflows
    mesh.indices.insert(mesh.indices.end(), {0, 0, 1});     // repeated index
    const Bvh bvh = buildBvh(mesh, {});
    EXPECT_EQ(bvh.dropped_triangle_count, 6u);
    expectWellFormed(bvh, good);
    for (const BvhTriangleGpu& t : bvh.triangles) EXPECT_LT(t.triangle_index, good);
    expectMatchesBruteForce(randomSoup(200, 9), {}, bvh, randomRays(500, vec3(-6.0f), vec3(6.0f), 2));

    // Nothing usable at all: every ray misses, nothing crashes.
    TriangleMesh only_bad;
    addTriangle(only_bad, {0, 0, 0}, {nan, 0, 0}, {0, 1, 0});
    const Bvh empty = buildBvh(only_bad, {});
    EXPECT_EQ(empty.dropped_triangle_count, 1u);
    ASSERT_EQ(empty.triangles.size(), 1u);  // the never-hit placeholder
    EXPECT_EQ(empty.triangles[0].triangle_index, kBvhNoTriangle);
    EXPECT_FALSE(traceClosestCpu(empty, vec3(0.1f, 0.1f, 1), vec3(0, 0, -1), 1e30f));
    EXPECT_FALSE(occludedCpu(empty, vec3(0.1f, 0.1f, 1), vec3(0, 0, -1), 1e30f));
    EXPECT_FALSE(traceClosestCpu(buildBvh(TriangleMesh{}, {}), vec3(0), vec3(1, 0, 0), 1e30f));

    // A NaN ray misses instead of looping or crashing.
    EXPECT_FALSE(traceClosestCpu(bvh, vec3(nan), vec3(0, 0, 1), 1e30f));
    EXPECT_FALSE(occludedCpu(bvh, vec3(0), vec3(nan, 0, 1), 1e30f));
}

TEST(BvhCpu, RejectsBadIndicesAndFlagCounts) {
    TriangleMesh mesh = randomSoup(10, 1);
    EXPECT_THROW(buildBvh(mesh, std::vector<uint32_t>(3, 0u)), InputError);
    mesh.indices.back() = 1000;
    EXPECT_THROW(buildBvh(mesh, {}), InputError);
}

TEST(BvhCpu, CoincidentCentroidsStillMakeSmallLeavesAndBoundedDepth) {
    // 2000 copies of one triangle (same centroid: SAH cannot split) plus a thin fan around one point.
    TriangleMesh mesh;
    for (int i = 0; i < 2000; ++i) addTriangle(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    for (int i = 0; i < 2000; ++i) {
        const float angle = 2.0f * std::numbers::pi_v<float> * i / 2000.0f;
        addTriangle(mesh, {0, 0, 1}, {std::cos(angle), std::sin(angle), 1},
                    {std::cos(angle + 1e-3f), std::sin(angle + 1e-3f), 1});
    }
    const Bvh bvh = buildBvh(mesh, {});
    expectWellFormed(bvh, mesh.triangleCount());
    const auto hit = traceClosestCpu(bvh, vec3(0.2f, 0.2f, -1), vec3(0, 0, 1), 1e30f);
    ASSERT_TRUE(hit);
    EXPECT_LT(hit->triangle_index, 2000u);
    EXPECT_NEAR(hit->t, 1.0f, 1e-6f);
}

// This thread's CPU seconds: unlike wall time, not stretched when other processes share the cores.
double threadCpuSeconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

TEST(BvhCpu, Builds100kTrianglesQuickly) {
    const TriangleMesh mesh = structuredScene(200, 1000, 17);  // 80k ground + 12k box triangles
    ASSERT_GT(mesh.triangleCount(), 90000u);
    const double start = threadCpuSeconds();
    const Bvh bvh = buildBvh(mesh, {});
    const double seconds = threadCpuSeconds() - start;
    std::printf("buildBvh: %zu triangles in %.3f CPU s, %zu nodes, %zu leaf slots, depth %u\n", mesh.triangleCount(),
                seconds, bvh.nodes.size(), bvh.triangles.size(), bvh.depth);
    EXPECT_LT(seconds, 3.0) << "the contract is about half a second per 100k triangles";
    expectWellFormed(bvh, mesh.triangleCount());
    // SAH quality, loosely: a binary tree with leaves of 1-4 triangles has at most 2n-1 nodes and, if SAH
    // packs leaves, noticeably fewer.
    EXPECT_LT(bvh.nodes.size(), mesh.triangleCount());
}

// ---- exact reference: the closest hit by a linear scan of every leaf slot --------------------------------------

uint32_t bitsOf(float value) {
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

// The smallest t over every triangle, ties to the smallest source triangle index (the contract of bvh.h), with
// the very triangle test both traversals use: any correct traversal must return exactly this. A triangle
// referenced from several leaves gives the same answer from each copy.
std::optional<BvhHit> exactClosest(const Bvh& bvh, const Ray& ray) {
    std::optional<BvhHit> best;
    for (const BvhTriangleGpu& triangle : bvh.triangles) {
        if ((triangle.flags & ray.skip_flags) != 0) continue;
        float t, u, v;
        if (!intersectTriangleCpu(triangle, ray.origin, ray.direction, ray.t_max, t, u, v)) continue;
        if (best && !(t < best->t || (t == best->t && triangle.triangle_index < best->triangle_index))) continue;
        const vec3 edge1(triangle.edge1[0], triangle.edge1[1], triangle.edge1[2]);
        const vec3 edge2(triangle.edge2[0], triangle.edge2[1], triangle.edge2[2]);
        best = BvhHit{t, triangle.triangle_index, u, v, glm::dot(glm::cross(edge1, edge2), ray.direction) < 0.0f};
    }
    return best;
}

// A structured scene plus exact duplicates of every third triangle (coincident faces: every hit on them is a
// tie at exactly equal t), on a heightfield whose shared edges rays graze.
TriangleMesh withDuplicates(TriangleMesh mesh, size_t& original) {
    original = mesh.triangleCount();
    for (size_t triangle = 0; triangle < original; triangle += 3)
        mesh.indices.insert(mesh.indices.end(), {mesh.indices[3 * triangle], mesh.indices[3 * triangle + 1],
                                                 mesh.indices[3 * triangle + 2]});
    return mesh;
}

TriangleMesh sceneWithDuplicates(size_t& original) { return withDuplicates(structuredScene(30, 40, 13), original); }

// The beams with coincident copies: ties at exactly equal t between triangles that spatial splits reference
// from several leaves each, where a tie rule by leaf slot would depend on which references were reached.
TriangleMesh beamsWithDuplicates(size_t& original) { return withDuplicates(beamScene(300, 31), original); }

// Returns the hits on coincident triangles referenced from several leaves.
size_t expectTraversalEqualsLinearScan(const TriangleMesh& mesh, size_t original, const std::vector<Ray>& rays) {
    const Bvh bvh = buildBvh(mesh, {});
    expectWellFormed(bvh, mesh.triangleCount());
    std::map<uint32_t, int> references;
    for (const BvhTriangleGpu& slot : bvh.triangles) ++references[slot.triangle_index];
    size_t hits = 0, duplicate_hits = 0, split_duplicate_hits = 0;
    for (const Ray& ray : rays) {
        const auto expected = exactClosest(bvh, ray);
        const auto got = traceClosestCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
        EXPECT_EQ(got.has_value(), expected.has_value());
        EXPECT_EQ(occludedCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags), expected.has_value());
        if (!expected || !got) continue;
        ++hits;
        const bool duplicate = expected->triangle_index >= original || expected->triangle_index % 3 == 0;
        duplicate_hits += duplicate;
        split_duplicate_hits += duplicate && references[expected->triangle_index] > 1;
        EXPECT_EQ(got->triangle_index, expected->triangle_index);
        EXPECT_EQ(bitsOf(got->t), bitsOf(expected->t));
        EXPECT_EQ(bitsOf(got->barycentric_u), bitsOf(expected->barycentric_u));
        EXPECT_EQ(bitsOf(got->barycentric_v), bitsOf(expected->barycentric_v));
        EXPECT_EQ(got->front_face, expected->front_face);
    }
    std::printf("%zu rays, %zu hits, %zu on coincident triangles, %zu of them referenced from several leaves\n",
                rays.size(), hits, duplicate_hits, split_duplicate_hits);
    EXPECT_GT(hits, rays.size() / 5);
    EXPECT_GT(duplicate_hits, hits / 10) << "the ties should be exercised";
    return split_duplicate_hits;
}

TEST(BvhCpu, TraversalEqualsLinearScanBitForBitTiesIncluded) {
    size_t original = 0;
    const TriangleMesh scene = sceneWithDuplicates(original);
    expectTraversalEqualsLinearScan(scene, original,
                                    randomRays(3000, vec3(-20.0f, -20.0f, 0.5f), vec3(20.0f, 20.0f, 8.0f), 17));
    const TriangleMesh beams = beamsWithDuplicates(original);
    EXPECT_GT(expectTraversalEqualsLinearScan(beams, original, randomRays(3000, vec3(-14.0f, -14.0f, 0.3f),
                                                                          vec3(14.0f, 14.0f, 9.0f), 18)),
              50u)
        << "ties between triangles referenced from several leaves should be exercised";
}

// ---- GPU: the GLSL traversal against the CPU traversal ---------------------------------------------------

// Mirrors shaders/tests/bvh_probe.comp.
struct ProbeRay {
    float origin[3];
    float t_max;
    float direction[3];
    uint32_t skip_flags;
};
static_assert(sizeof(ProbeRay) == 32);
struct ProbeResult {
    float t;
    uint32_t triangle_index;
    float barycentric_u;
    float barycentric_v;
    uint32_t front_face;
    uint32_t occluded;
    uint32_t pad0;
    uint32_t pad1;
};
static_assert(sizeof(ProbeResult) == 32);
struct ProbeParams {
    uint32_t ray_count;
    uint32_t queries;
};
constexpr uint32_t kQueryClosest = 1, kQueryOccluded = 2;
constexpr uint32_t kProbeWorkgroupSize = 64;

class BvhGpuTest : public testing::GpuTest {
protected:
    // Runs the probe; returns the results and the seconds the dispatch took.
    std::vector<ProbeResult> probe(const Bvh& bvh, const std::vector<Ray>& rays, uint32_t queries,
                                   double* seconds = nullptr) {
        std::vector<ProbeRay> probe_rays(rays.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            for (int a = 0; a < 3; ++a) {
                probe_rays[i].origin[a] = rays[i].origin[a];
                probe_rays[i].direction[a] = rays[i].direction[a];
            }
            probe_rays[i].t_max = rays[i].t_max;
            probe_rays[i].skip_flags = rays[i].skip_flags;
        }
        GpuBuffer nodes(context(), bvh.nodes.size() * sizeof(BvhNodeGpu), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        GpuBuffer triangles(context(), bvh.triangles.size() * sizeof(BvhTriangleGpu),
                            VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
        GpuBuffer ray_buffer(context(), probe_rays.size() * sizeof(ProbeRay));
        GpuBuffer result_buffer(context(), rays.size() * sizeof(ProbeResult));
        nodes.uploadVector(bvh.nodes);
        triangles.uploadVector(bvh.triangles);
        ray_buffer.uploadVector(probe_rays);
        // bvh_layout.glsl reads nodes and triangles as RGBA32UI texel buffers at bindings 0 and 1.
        ComputePipeline pipeline(context(), kBvhProbeCompSpirv, sizeof(kBvhProbeCompSpirv), 4, sizeof(ProbeParams),
                                 {{0, VK_FORMAT_R32G32B32A32_UINT}, {1, VK_FORMAT_R32G32B32A32_UINT}});
        pipeline.bindBuffers({&nodes, &triangles, &ray_buffer, &result_buffer});
        const ProbeParams params{static_cast<uint32_t>(rays.size()), queries};
        const uint32_t groups = (params.ray_count + kProbeWorkgroupSize - 1) / kProbeWorkgroupSize;
        const auto start = std::chrono::steady_clock::now();
        pipeline.dispatchAndWait(&params, groups);
        if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result_buffer.downloadVector<ProbeResult>(rays.size());
    }

    // Hit for hit and bit for bit: the GLSL traversal, the CPU traversal and the linear scan
    // (exactClosest) agree on every ray, ties included, so the answer depends on neither the tree nor the
    // order its nodes are visited in.
    void expectMatchesCpu(const Bvh& bvh, const std::vector<Ray>& rays) {
        const std::vector<ProbeResult> results = probe(bvh, rays, kQueryClosest | kQueryOccluded);
        size_t hits = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const Ray& ray = rays[i];
            const std::optional<BvhHit> expected = exactClosest(bvh, ray);
            const auto cpu = traceClosestCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
            const bool cpu_occluded = occludedCpu(bvh, ray.origin, ray.direction, ray.t_max, ray.skip_flags);
            const ProbeResult& got = results[i];
            ASSERT_EQ(cpu.has_value(), expected.has_value()) << "ray " << i;
            EXPECT_EQ(cpu_occluded, expected.has_value()) << "ray " << i;
            EXPECT_EQ(got.occluded != 0, expected.has_value()) << "ray " << i;
            ASSERT_EQ(got.triangle_index != 0xffffffffu, expected.has_value()) << "ray " << i;
            if (!expected) continue;
            ++hits;
            for (const BvhHit& traversed : {*cpu, BvhHit{got.t, got.triangle_index, got.barycentric_u,
                                                         got.barycentric_v, got.front_face != 0}}) {
                EXPECT_EQ(traversed.triangle_index, expected->triangle_index) << "ray " << i;
                EXPECT_EQ(bitsOf(traversed.t), bitsOf(expected->t)) << "ray " << i;
                EXPECT_EQ(bitsOf(traversed.barycentric_u), bitsOf(expected->barycentric_u)) << "ray " << i;
                EXPECT_EQ(bitsOf(traversed.barycentric_v), bitsOf(expected->barycentric_v)) << "ray " << i;
                EXPECT_EQ(traversed.front_face, expected->front_face) << "ray " << i;
            }
        }
        std::printf("GPU, CPU traversal and linear scan compared on %zu rays, %zu hits\n", rays.size(), hits);
        EXPECT_GT(hits, rays.size() / 10);
    }
};

TEST_F(BvhGpuTest, ProbeMatchesCpuOnSoupAndScene) {
    const TriangleMesh soup = randomSoup(3000, 7);
    std::vector<uint32_t> soup_flags(soup.triangleCount());
    std::mt19937 rng(5);
    for (uint32_t& f : soup_flags) f = 1u << (rng() % 3);
    std::vector<Ray> soup_rays = randomRays(2000, vec3(-6.0f), vec3(6.0f), 11);
    for (size_t i = 0; i < soup_rays.size(); ++i) {
        soup_rays[i].skip_flags = rng() % 4;
        if (i % 4 == 0) soup_rays[i].t_max = 2.0f;
    }
    expectMatchesCpu(buildBvh(soup, soup_flags), soup_rays);

    const TriangleMesh scene = structuredScene(40, 60, 3);
    expectMatchesCpu(buildBvh(scene, {}),
                     randomRays(2000, vec3(-20.0f, -20.0f, 0.5f), vec3(20.0f, 20.0f, 8.0f), 5));

    size_t original = 0;
    expectMatchesCpu(buildBvh(sceneWithDuplicates(original), {}),
                     randomRays(2000, vec3(-20.0f, -20.0f, 0.5f), vec3(20.0f, 20.0f, 8.0f), 6));
}

TEST_F(BvhGpuTest, ProbeMatchesCpuOnLongThinTriangles) {
    const TriangleMesh mesh = beamScene(400, 21);
    std::vector<uint32_t> flags(mesh.triangleCount());
    std::mt19937 rng(8);
    for (uint32_t& f : flags) f = rng() % 8 == 0 ? 1u : 0u;
    std::vector<Ray> rays = randomRays(2000, vec3(-14.0f, -14.0f, 0.3f), vec3(14.0f, 14.0f, 9.0f), 25);
    for (size_t i = 0; i < rays.size(); ++i) {
        rays[i].skip_flags = i % 3 == 0 ? 1u : 0u;
        if (i % 5 == 0) rays[i].t_max = 2.0f;
    }
    const Bvh bvh = buildBvh(mesh, flags);
    ASSERT_GT(bvh.triangles.size(), mesh.triangleCount()) << "the GPU should see duplicated references";
    expectMatchesCpu(bvh, rays);

    size_t original = 0;  // coincident copies: ties between triangles referenced from several leaves
    expectMatchesCpu(buildBvh(beamsWithDuplicates(original), {}),
                     randomRays(2000, vec3(-14.0f, -14.0f, 0.3f), vec3(14.0f, 14.0f, 9.0f), 26));
}

TEST_F(BvhGpuTest, EmptyBvhMissesOnGpu) {
    const Bvh empty = buildBvh(TriangleMesh{}, {});
    const std::vector<ProbeResult> results =
        probe(empty, randomRays(100, vec3(-1.0f), vec3(1.0f), 3), kQueryClosest | kQueryOccluded);
    for (const ProbeResult& r : results) {
        EXPECT_EQ(r.triangle_index, 0xffffffffu);
        EXPECT_EQ(r.occluded, 0u);
    }
}

TEST_F(BvhGpuTest, ReportsRaysPerSecond) {
    // ~50k triangles (a 150x150 ground and 500 boxes), 100k random rays from inside the scene.
    const TriangleMesh scene = structuredScene(150, 500, 29);
    const Bvh bvh = buildBvh(scene, {});
    const std::vector<Ray> rays = randomRays(100000, vec3(-20.0f, -20.0f, 0.5f), vec3(20.0f, 20.0f, 8.0f), 31);
    double closest_seconds = 0.0, occluded_seconds = 0.0;
    probe(bvh, std::vector<Ray>(rays.begin(), rays.begin() + 1000), kQueryClosest);  // warm-up
    const auto closest = probe(bvh, rays, kQueryClosest, &closest_seconds);
    const auto occluded = probe(bvh, rays, kQueryOccluded, &occluded_seconds);
    size_t closest_hits = 0, occluded_hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        closest_hits += closest[i].triangle_index != 0xffffffffu;
        occluded_hits += occluded[i].occluded;
    }
    std::printf("BVH on %s: %zu triangles, %zu rays: closest hit %.2f M rays/s (%zu hits), "
                "any hit %.2f M rays/s (%zu hits) (docs/design.md 5: ~1.0 and ~0.85 on lavapipe, 2 cores)\n",
                context().deviceDescription().c_str(), scene.triangleCount(), rays.size(),
                rays.size() / closest_seconds * 1e-6, closest_hits, rays.size() / occluded_seconds * 1e-6,
                occluded_hits);
    EXPECT_EQ(closest_hits, occluded_hits);
}

}  // namespace
}  // namespace gusuku::bake
