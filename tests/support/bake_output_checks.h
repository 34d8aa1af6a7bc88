#pragma once
// Checks shared by the tests that look at a finished bake set on disk.

#include <string>
#include <vector>

#include "gusuku/formats/bakeset_data.h"

namespace gusuku::testing {

/// Reads every .exr in dir through OpenImageIO and fails the current test (gtest EXPECT) on any NaN or infinite
/// value; returns how many images it read, so a caller can assert that the bake wrote anything at all.
int expectExrImagesFinite(const std::string& dir);

/// The .exr file names in dir, sorted.
std::vector<std::string> exrFilesIn(const std::string& dir);

/// Fails the current test unless both folders hold the same .exr names and every image is equal bit for bit (a
/// resumed or re-sliced bake against an uninterrupted one).
void expectSameBakeSets(const std::string& expected_dir, const std::string& actual_dir);

/// Fails the current test unless the two meshes' vertex streams, indices and per-triangle materials are equal
/// (a mesh written and read back; materials and textures are the caller's to compare).
void expectSameMeshGeometry(const BakeSetMesh& actual, const BakeSetMesh& expected);

}  // namespace gusuku::testing
