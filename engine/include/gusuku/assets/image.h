#pragma once
// Images in memory are linear float RGBA, row 0 at the top. Files go through OpenImageIO; the colour encoding
// is explicit at every read and write: HDR formats (.hdr, .exr) hold scene-referred linear Rec.709, 8-bit
// formats (.png, .jpg) hold sRGB-encoded values.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/maths/colour.h"      // srgbEncode, srgbDecode (per value; the whole-image versions are below)
#include "gusuku/maths/image_rgba.h"  // the image type

namespace gusuku {

/// How to interpret a file's values when reading.
enum class ImageEncoding {
    Auto,    ///< by format: float formats (.hdr, .exr) linear; 8/16-bit integer formats sRGB
    Linear,  ///< values are linear already (data maps such as normal maps)
    Srgb,    ///< values are sRGB-encoded; decoded to linear on read
};

/// Reading limits. An image whose header declares more than kMaxImageFileTexels texels (16384 x 16384) is refused
/// before a texel is decoded (a corrupt or hostile header, or a decompression bomb). One larger than max_side
/// (at most kMaxImageSide) on either side is box-downsampled while it is decoded, by the smallest integer factor
/// that fits, one band of rows at a time: the full-size image is never held. The shorter side is divided by the
/// factor and rounded up, the longer one keeps the file's proportion (so an 8194 x 4097 sky becomes 4098 x 2049,
/// still 2:1); each reduced texel averages the file texels that fall in it (whole blocks, as boxDownsample, when
/// the sides divide by the factor). A decoder's report of damaged data it worked around (a truncated JPEG's
/// "Premature end of JPEG file") is an InputError, as is a truncated PNG (its chunk chain) or HDR.
constexpr int kMaxImageSide = 8192;
constexpr int64_t kMaxImageFileTexels = int64_t(1) << 28;
/// The largest radiance a radiance map may hold, in its own units: far above any sky (the sun's disc is about
/// 2e7 W m^-2 sr^-1, 1.6e9 cd m^-2) and low enough that squares summed over a whole map stay within float range.
constexpr float kMaxRadiance = 1e15f;

/// Reads an image file through OpenImageIO. Grey images are expanded to RGB; missing alpha becomes 1; channels
/// past the fourth are ignored. Throws InputError(path, ...) when the file is missing, not a regular file (a FIFO,
/// a device, a directory: never opened), unreadable, not an image or too large (above). Whatever the codec
/// prints (libpng) is folded into the one-line error, never left on stderr.
ImageRGBA readImage(const std::string& path, ImageEncoding encoding = ImageEncoding::Auto,
                    int max_side = kMaxImageSide);

/// Decodes an image held in memory (an image embedded in a .glb); `name` is used in error messages and
/// `mime_type` or the bytes' signature chooses the format. 8-bit data is taken as sRGB unless encoding says.
/// Same limits and errors as readImage.
ImageRGBA readImageFromMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                              ImageEncoding encoding = ImageEncoding::Auto, int max_side = kMaxImageSide);

/// An image file's size as its header declares it, nothing decoded (the checks and errors of readImage's open).
struct ImageSize {
    int width = 0, height = 0;
};
ImageSize readImageSize(const std::string& path);

/// Reads an OpenEXR file that must hold exactly 4 float32 channels (RGBA), as a bake set's images do. What the
/// file holds decides, not its name: a PNG renamed .exr, a half or 8-bit file, or 1, 3 or 6 channels is an
/// InputError(path, "", "holds ... : expected OpenEXR with 4 float32 channels (RGBA)"). Values are linear.
ImageRGBA readFloatRgbaExr(const std::string& path, int max_side = kMaxImageSide);

/// Reads a radiance map and checks it: the data must be Radiance RGBE (.hdr) or OpenEXR with half or float
/// channels (an 8-bit PNG or JPEG, even renamed .hdr, is refused), and every RGB texel finite, >= 0 and at most
/// kMaxRadiance. A NaN, an infinity (a value beyond float range stored in the file), a negative or a too large
/// texel is an InputError naming the texel and channel. Maps wider or taller than kMaxImageSide are
/// box-downsampled while loading.
ImageRGBA readRadianceMap(const std::string& path);

/// Writes RGB (or RGBA when with_alpha) as 32-bit float OpenEXR, atomically (temporary file, then rename).
void writeExr(const std::string& path, const ImageRGBA& image, bool with_alpha = false);

/// Writes an 8-bit sRGB-encoded PNG (linear values are encoded, clamped to [0, 1]), atomically.
void writePngSrgb(const std::string& path, const ImageRGBA& image, bool with_alpha = true);

/// Writes 8-bit RGBA bytes as they are (already sRGB-encoded, row 0 at the top: the runtime's frames) as a PNG,
/// atomically. std::invalid_argument when the byte count is not width * height * 4.
void writePngRgba8(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba8);

/// Encodes linear RGBA as an 8-bit sRGB PNG in memory (as writePngSrgb does to a file), e.g. to embed in a .glb.
std::vector<unsigned char> encodePngSrgb(const ImageRGBA& image, bool with_alpha = true);

/// Encodes 8-bit bytes as they are (no transfer function applied: the caller says what they mean, e.g. a linear
/// lightmap) as a PNG in memory: width * height * channels bytes, row 0 at the top, channels 1 to 4.
/// std::invalid_argument when the byte count or channel count is wrong.
std::vector<unsigned char> encodePng8(int width, int height, int channels, const std::vector<uint8_t>& bytes);

/// Writes a Radiance .hdr (RGBE), atomically. Values are linear.
void writeHdr(const std::string& path, const ImageRGBA& image);

// The scalar sRGB transfer function and its inverse, srgbEncode / srgbDecode, live in gusuku/maths/colour.h.

/// Whole-image sRGB transfer through OpenColorIO (the one place colour conversions go, docs/design.md 2): RGB
/// decoded to linear / encoded from linear in place, alpha untouched. Encoding expects values in [0, 1].
void srgbDecodeImage(ImageRGBA& image);
void srgbEncodeImage(ImageRGBA& image);
/// The same decode from 8-bit bytes (texel_count RGBA quadruples, alpha 255 = 1) into linear float RGBA:
/// the curve is evaluated (through OpenColorIO) once per byte value, so an 8-bit texture costs a table lookup per channel
/// instead of a pow. Byte k gives what srgbDecodeImage gives for k / 255.
void srgbDecodeBytes(const uint8_t* encoded_rgba, size_t texel_count, float* linear_rgba);

/// Box-downsamples by the smallest integer factor that brings both sides to at most max_size (averaging
/// linear values, so no energy is lost). Returns the image unchanged when it already fits or max_size <= 0.
ImageRGBA boxDownsample(const ImageRGBA& image, int max_size);

}  // namespace gusuku
