// closedOutwardTriangles (gusuku_bake/closed_parts.h): which faces have an inside, so that a double-sided face seen
// from behind counts toward an invalid texel only there. Checked on meshes whose answer is known by construction.
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/maths/mesh.h"
#include "gusuku_bake/closed_parts.h"
#include "test_meshes.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::addQuad;
using gusuku::testing::closedBox;
using gusuku::testing::emptyMesh;

bool all(const std::vector<bool>& flags, bool value) {
    return std::all_of(flags.begin(), flags.end(), [value](bool flag) { return flag == value; });
}

TEST(ClosedParts, AnOutwardBoxIsClosedAndAnInwardOneIsNot) {
    // closedBox writes four vertices a face: closure needs the welding by position.
    const TriangleMesh outward = closedBox({0.0f, 0.0f, 0.0f}, {1.0f, 2.0f, 3.0f}, false, glm::vec3(0.5f));
    ASSERT_EQ(outward.triangleCount(), 12u);
    EXPECT_TRUE(all(closedOutwardTriangles(outward), true));
    // Wound inward: a room seen from inside, whose backs face the outside world: no inside to be hidden in.
    const TriangleMesh inward = closedBox({0.0f, 0.0f, 0.0f}, {1.0f, 2.0f, 3.0f}, true, glm::vec3(0.5f));
    EXPECT_TRUE(all(closedOutwardTriangles(inward), false));
}

TEST(ClosedParts, OpenSheetsAndABoxWithAMissingFaceAreOpen) {
    TriangleMesh sheet = emptyMesh(glm::vec3(0.5f));
    addQuad(sheet, {0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
    EXPECT_TRUE(all(closedOutwardTriangles(sheet), false));

    TriangleMesh box = closedBox({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, false, glm::vec3(0.5f));
    box.indices.resize(box.indices.size() - 6);  // one face (two triangles) left out
    box.triangle_material.resize(box.triangleCount());
    EXPECT_TRUE(all(closedOutwardTriangles(box), false));
}

TEST(ClosedParts, EachPartIsJudgedOnItsOwn) {
    // A closed box beside an open roof sheet over it, in one mesh: the box's 12 faces closed, the sheet's 2 not.
    TriangleMesh mesh = closedBox({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, false, glm::vec3(0.5f));
    addQuad(mesh, {-1.0f, -1.0f, 2.0f}, {2.0f, -1.0f, 2.0f}, {2.0f, 2.0f, 2.0f}, {-1.0f, 2.0f, 2.0f});
    const std::vector<bool> closed = closedOutwardTriangles(mesh);
    ASSERT_EQ(closed.size(), 14u);
    EXPECT_TRUE(std::all_of(closed.begin(), closed.begin() + 12, [](bool flag) { return flag; }));
    EXPECT_FALSE(closed[12]);
    EXPECT_FALSE(closed[13]);
}

TEST(ClosedParts, AFlippedFaceOpensItsPart) {
    // One triangle wound against its neighbours: its edges run the same way as theirs, so the part is not a
    // consistently wound closed surface and its backs say nothing reliable.
    TriangleMesh box = closedBox({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, false, glm::vec3(0.5f));
    std::swap(box.indices[1], box.indices[2]);
    EXPECT_TRUE(all(closedOutwardTriangles(box), false));
}

}  // namespace
}  // namespace gusuku::bake
