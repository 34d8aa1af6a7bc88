#pragma once
// Images in memory are linear float RGBA, row 0 at the top. Files go through OpenImageIO; the colour encoding
// is explicit at every read and write: HDR formats (.hdr, .exr) hold scene-referred linear Rec.709, 8-bit
// formats (.png, .jpg) hold sRGB-encoded values.

#include <cstdint>
#include <string>
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

/// How to interpret a file's values when reading.
enum class ImageEncoding {
    Auto,    ///< by format: float formats (.hdr, .exr) linear; 8/16-bit integer formats sRGB
    Linear,  ///< values are linear already (data maps such as normal maps)
    Srgb,    ///< values are sRGB-encoded; decoded to linear on read
};

/// Reads an image file through OpenImageIO. Grey images are expanded to RGB; missing alpha becomes 1.
/// Throws InputError(path, ...) when the file is missing, unreadable or not an image.
ImageRGBA readImage(const std::string& path, ImageEncoding encoding = ImageEncoding::Auto);

/// Decodes an image held in memory (an image embedded in a .glb); `name` is used in error messages and
/// `mime_type` or the bytes' signature chooses the format. 8-bit data is taken as sRGB unless encoding says.
ImageRGBA readImageFromMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                              ImageEncoding encoding = ImageEncoding::Auto);

/// Reads a radiance map (.hdr or .exr) and checks it: every RGB texel finite and >= 0. A NaN, an infinity or a
/// negative texel is an InputError naming the texel and channel.
ImageRGBA readRadianceMap(const std::string& path);

/// Writes RGB (or RGBA when with_alpha) as 32-bit float OpenEXR, atomically (temporary file, then rename).
void writeExr(const std::string& path, const ImageRGBA& image, bool with_alpha = false);

/// Writes an 8-bit sRGB-encoded PNG (linear values are encoded, clamped to [0, 1]), atomically.
void writePngSrgb(const std::string& path, const ImageRGBA& image, bool with_alpha = true);

/// Encodes linear RGBA as an 8-bit sRGB PNG in memory (as writePngSrgb does to a file), e.g. to embed in a .glb.
std::vector<unsigned char> encodePngSrgb(const ImageRGBA& image, bool with_alpha = true);

/// Writes a Radiance .hdr (RGBE), atomically. Values are linear.
void writeHdr(const std::string& path, const ImageRGBA& image);

/// sRGB transfer function (IEC 61966-2-1) and its inverse, per channel.
float srgbEncode(float linear);
float srgbDecode(float encoded);

/// Whole-image sRGB transfer through OpenColorIO (the one place colour conversions go, DESIGN.md 2): RGB
/// decoded to linear / encoded from linear in place, alpha untouched. Encoding expects values in [0, 1].
void srgbDecodeImage(ImageRGBA& image);
void srgbEncodeImage(ImageRGBA& image);

/// Box-downsamples by the smallest integer factor that brings both sides to at most max_size (averaging
/// linear values, so no energy is lost). Returns the image unchanged when it already fits or max_size <= 0.
ImageRGBA boxDownsample(const ImageRGBA& image, int max_size);

}  // namespace gusuku
