#pragma once
// An image in memory: linear float RGBA, row 0 at the top. The type alone, with no I/O, so that the maths library
// (meshes carry their textures) needs no image reader; files are read and written by gusuku/assets/image.h.

#include <cstddef>
#include <vector>

namespace gusuku {

struct ImageRGBA {
    int width = 0;
    int height = 0;
    std::vector<float> texels;  ///< width * height * 4 floats, linear, row-major, row 0 at the top

    float* texel(int x, int y) { return texels.data() + (size_t(y) * size_t(width) + size_t(x)) * 4; }
    const float* texel(int x, int y) const {
        return texels.data() + (size_t(y) * size_t(width) + size_t(x)) * 4;
    }
};

}  // namespace gusuku
