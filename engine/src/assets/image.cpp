// Image files through OpenImageIO, with the colour encoding decided explicitly at every read and write
// (gusuku/assets/image.h). Pixels in memory are always linear float RGBA. Reading is in image_read.cpp.
#include "gusuku/assets/image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "gusuku/assets/atomic_file.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {

namespace {

// Copies linear RGBA into a packed buffer of `channel_count` channels.
std::vector<float> packChannels(const ImageRGBA& image, int channel_count) {
    const size_t texel_count = size_t(image.width) * size_t(image.height);
    std::vector<float> packed(texel_count * size_t(channel_count));
    for (size_t i = 0; i < texel_count; ++i)
        for (int c = 0; c < channel_count; ++c) packed[i * size_t(channel_count) + size_t(c)] = image.texels[i * 4 + size_t(c)];
    return packed;
}

void checkWritable(const std::string& path, const ImageRGBA& image) {
    if (image.width <= 0 || image.height <= 0 ||
        image.texels.size() != size_t(image.width) * size_t(image.height) * 4)
        throw std::invalid_argument(path + ": cannot write an image of " + std::to_string(image.width) + " x " +
                                    std::to_string(image.height) + " with " +
                                    std::to_string(image.texels.size()) + " floats");
}

// Writes through OpenImageIO onto a temporary path that keeps the extension (OpenImageIO picks the format from
// it), then renames: a failed or interrupted write never leaves a half-written file at `path`.
void writeWithOiio(const std::string& path, OIIO::ImageSpec spec, const void* pixels) {
    writeFileAtomicallyKeepingExtension(path, [&](const std::string& temporary_path) {
        std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(temporary_path);
        if (!output) throw std::runtime_error(path + ": no image writer: " + OIIO::geterror());
        if (!output->open(temporary_path, spec))
            throw std::runtime_error(path + ": cannot open for writing: " + output->geterror());
        if (!output->write_image(spec.format, pixels))
            throw std::runtime_error(path + ": cannot write image: " + output->geterror());
        if (!output->close()) throw std::runtime_error(path + ": cannot finish image: " + output->geterror());
    });
}

// 8-bit sRGB bytes and the matching spec, shared by the PNG file and in-memory writers.
struct SrgbPngPixels {
    OIIO::ImageSpec spec;
    std::vector<unsigned char> bytes;
};

SrgbPngPixels quantiseToSrgb(const ImageRGBA& image, bool with_alpha) {
    ImageRGBA encoded = image;
    for (float& value : encoded.texels) value = std::clamp(std::isnan(value) ? 0.0f : value, 0.0f, 1.0f);
    srgbEncodeImage(encoded);
    const int channel_count = with_alpha ? 4 : 3;
    const std::vector<float> packed = packChannels(encoded, channel_count);
    // Quantise here (round to nearest) rather than leave it to the writer, so the 1/255 bound is ours.
    std::vector<unsigned char> bytes(packed.size());
    for (size_t i = 0; i < packed.size(); ++i)
        bytes[i] = static_cast<unsigned char>(std::lround(std::clamp(packed[i], 0.0f, 1.0f) * 255.0f));
    OIIO::ImageSpec spec(image.width, image.height, channel_count, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // alpha is straight: do not un-premultiply
    spec.attribute("oiio:ColorSpace", "sRGB");
    return {spec, std::move(bytes)};
}

}  // namespace

void writeExr(const std::string& path, const ImageRGBA& image, bool with_alpha) {
    checkWritable(path, image);
    const int channel_count = with_alpha ? 4 : 3;
    const std::vector<float> packed = packChannels(image, channel_count);
    OIIO::ImageSpec spec(image.width, image.height, channel_count, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip");
    // Same pixels, same bytes: OpenImageIO stamps the write time into the header (DateTime -> capDate) unless
    // the spec has one, so give it an empty one. Nothing else in the header depends on the clock or the
    // software version (tests/test_bake_bytes.cpp compares whole files).
    spec.attribute("DateTime", "");
    writeWithOiio(path, spec, packed.data());
}

void writePngSrgb(const std::string& path, const ImageRGBA& image, bool with_alpha) {
    checkWritable(path, image);
    const SrgbPngPixels pixels = quantiseToSrgb(image, with_alpha);
    writeWithOiio(path, pixels.spec, pixels.bytes.data());
}

void writePngRgba8(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba8) {
    if (width <= 0 || height <= 0 || rgba8.size() != size_t(width) * size_t(height) * 4)
        throw std::invalid_argument(path + ": cannot write " + std::to_string(rgba8.size()) + " bytes as a " +
                                    std::to_string(width) + " x " + std::to_string(height) + " RGBA8 image");
    OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    // Encoded in memory, then written through writeBytesAtomically, which checks every write and the flush: the
    // PNG writer does not report a full disk, and a 0-byte file would be renamed into place as if it were done.
    std::vector<unsigned char> png;
    OIIO::Filesystem::IOVecOutput writer(png);
    const std::string name = "memory.png";
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(name, &writer);
    if (!output) throw std::runtime_error(path + ": cannot create a PNG writer: " + OIIO::geterror());
    if (!output->open(name, spec) || !output->write_image(spec.format, rgba8.data()) || !output->close())
        throw std::runtime_error(path + ": cannot encode PNG: " + output->geterror());
    writeBytesAtomically(path, png.data(), png.size());
}

std::vector<unsigned char> encodePngSrgb(const ImageRGBA& image, bool with_alpha) {
    checkWritable("PNG in memory", image);
    const SrgbPngPixels pixels = quantiseToSrgb(image, with_alpha);
    std::vector<unsigned char> png;
    OIIO::Filesystem::IOVecOutput writer(png);
    const std::string name = "memory.png";
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(name, &writer);
    if (!output) throw std::runtime_error("cannot create a PNG writer: " + OIIO::geterror());
    if (!output->open(name, pixels.spec)) throw std::runtime_error("cannot encode PNG: " + output->geterror());
    if (!output->write_image(pixels.spec.format, pixels.bytes.data()) || !output->close())
        throw std::runtime_error("cannot encode PNG: " + output->geterror());
    return png;
}

std::vector<unsigned char> encodePng8(int width, int height, int channels, const std::vector<uint8_t>& bytes) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        bytes.size() != size_t(width) * size_t(height) * size_t(channels))
        throw std::invalid_argument("PNG in memory: cannot encode " + std::to_string(bytes.size()) + " bytes as a " +
                                    std::to_string(width) + " x " + std::to_string(height) + " image of " +
                                    std::to_string(channels) + " 8-bit channels");
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    std::vector<unsigned char> png;
    OIIO::Filesystem::IOVecOutput writer(png);
    const std::string name = "memory.png";
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(name, &writer);
    if (!output) throw std::runtime_error("cannot create a PNG writer: " + OIIO::geterror());
    if (!output->open(name, spec) || !output->write_image(spec.format, bytes.data()) || !output->close())
        throw std::runtime_error("cannot encode PNG: " + output->geterror());
    return png;
}

void writeHdr(const std::string& path, const ImageRGBA& image) {
    checkWritable(path, image);
    const std::vector<float> packed = packChannels(image, 3);
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    writeWithOiio(path, spec, packed.data());
}

ImageRGBA boxDownsample(const ImageRGBA& image, int max_size) {
    const int longest_side = std::max(image.width, image.height);
    if (max_size <= 0 || longest_side <= max_size) return image;
    const int factor = (longest_side + max_size - 1) / max_size;
    ImageRGBA reduced;
    reduced.width = (image.width + factor - 1) / factor;
    reduced.height = (image.height + factor - 1) / factor;
    reduced.texels.assign(size_t(reduced.width) * size_t(reduced.height) * 4, 0.0f);
    for (int y = 0; y < reduced.height; ++y) {
        for (int x = 0; x < reduced.width; ++x) {
            // Blocks on the right and bottom edges may be partial: average what is there.
            const int x_end = std::min(image.width, (x + 1) * factor);
            const int y_end = std::min(image.height, (y + 1) * factor);
            double sum[4] = {0, 0, 0, 0};
            int count = 0;
            for (int sy = y * factor; sy < y_end; ++sy)
                for (int sx = x * factor; sx < x_end; ++sx, ++count)
                    for (int c = 0; c < 4; ++c) sum[c] += image.texel(sx, sy)[c];
            float* out = reduced.texel(x, y);
            for (int c = 0; c < 4; ++c) out[c] = float(sum[c] / count);
        }
    }
    return reduced;
}

}  // namespace gusuku
