#include "bake_output_checks.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "gusuku/assets/image.h"

namespace gusuku::testing {

int expectExrImagesFinite(const std::string& dir) {
    int images = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".exr") continue;
        const ImageRGBA image = readImage(entry.path().string());
        size_t non_finite = 0;
        for (float value : image.texels) non_finite += std::isfinite(value) ? 0 : 1;
        EXPECT_EQ(non_finite, 0u) << entry.path();
        ++images;
    }
    return images;
}

std::vector<std::string> exrFilesIn(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".exr") names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

void expectSameBakeSets(const std::string& expected_dir, const std::string& actual_dir) {
    const std::vector<std::string> names = exrFilesIn(expected_dir);
    ASSERT_FALSE(names.empty());
    ASSERT_EQ(names, exrFilesIn(actual_dir));
    for (const std::string& name : names) {
        const ImageRGBA expected = readImage(expected_dir + "/" + name);
        const ImageRGBA actual = readImage(actual_dir + "/" + name);
        ASSERT_EQ(expected.width, actual.width) << name;
        ASSERT_EQ(expected.height, actual.height) << name;
        ASSERT_EQ(expected.texels.size(), actual.texels.size()) << name;
        size_t differing = 0;
        for (size_t i = 0; i < expected.texels.size(); ++i) differing += expected.texels[i] != actual.texels[i];
        EXPECT_EQ(differing, 0u) << name << ": resumed bake differs from the uninterrupted one";
    }
}

void expectSameMeshGeometry(const BakeSetMesh& actual, const BakeSetMesh& expected) {
    EXPECT_EQ(actual.positions, expected.positions);
    EXPECT_EQ(actual.normals, expected.normals);
    EXPECT_EQ(actual.uv0, expected.uv0);
    EXPECT_EQ(actual.uv1, expected.uv1);
    EXPECT_EQ(actual.indices, expected.indices);
    EXPECT_EQ(actual.triangle_material, expected.triangle_material);
}

}  // namespace gusuku::testing
