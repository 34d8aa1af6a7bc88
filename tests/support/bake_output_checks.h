#pragma once
// Checks shared by the tests that look at a finished bake set on disk.

#include <string>

namespace gusuku::testing {

/// Reads every .exr in dir through OpenImageIO and fails the current test (gtest EXPECT) on any NaN or infinite
/// value; returns how many images it read, so a caller can assert that the bake wrote anything at all.
int expectExrImagesFinite(const std::string& dir);

}  // namespace gusuku::testing
