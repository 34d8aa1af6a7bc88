#include "bake_output_checks.h"

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

}  // namespace gusuku::testing
