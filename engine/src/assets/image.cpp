// Image files through OpenImageIO, with the colour encoding decided explicitly at every read and write
// (gusuku/image.h). Pixels in memory are always linear float RGBA.
#include "gusuku/image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "gusuku/atomic_file.h"
#include "gusuku/input_error.h"

namespace gusuku {

namespace {

// Larger than any texture or sky this project reads (a 16k x 16k map); beyond it a header is more likely
// corrupt than real, and allocating for it would take the machine down.
constexpr size_t kMaxTexelCount = size_t(1) << 28;

std::string lowerCaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

bool isFloatFormat(OIIO::TypeDesc format) {
    return format.basetype == OIIO::TypeDesc::FLOAT || format.basetype == OIIO::TypeDesc::HALF ||
           format.basetype == OIIO::TypeDesc::DOUBLE;
}

// Reads subimage 0 of an opened input into linear RGBA. `name` is what error messages call the image.
ImageRGBA readOpenedImage(const std::string& name, OIIO::ImageInput& input, ImageEncoding encoding) {
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw InputError(name, "", "image has no pixels (" + std::to_string(spec.width) + " x " +
                                       std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) +
                                       " channels)");
    if (size_t(spec.width) * size_t(spec.height) > kMaxTexelCount)
        throw InputError(name, "", "image too large (" + std::to_string(spec.width) + " x " +
                                       std::to_string(spec.height) + ")");
    const int channel_count = spec.nchannels;
    std::vector<float> file_values(size_t(spec.width) * size_t(spec.height) * size_t(channel_count));
    if (!input.read_image(0, 0, 0, channel_count, OIIO::TypeDesc::FLOAT, file_values.data()))
        throw InputError(name, "", "cannot decode image: " + input.geterror());

    ImageRGBA image;
    image.width = spec.width;
    image.height = spec.height;
    image.texels.resize(size_t(image.width) * size_t(image.height) * 4);
    const size_t texel_count = size_t(image.width) * size_t(image.height);
    for (size_t i = 0; i < texel_count; ++i) {
        const float* in = file_values.data() + i * size_t(channel_count);
        float* out = image.texels.data() + i * 4;
        if (channel_count <= 2) {  // grey, or grey + alpha
            out[0] = out[1] = out[2] = in[0];
            out[3] = channel_count == 2 ? in[1] : 1.0f;
        } else {
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
            out[3] = channel_count >= 4 ? in[3] : 1.0f;
        }
    }

    const bool is_srgb = encoding == ImageEncoding::Srgb ||
                         (encoding == ImageEncoding::Auto && !isFloatFormat(spec.format));
    if (is_srgb) srgbDecodeImage(image);
    return image;
}

// Keep straight (unassociated) alpha as stored: OpenImageIO would otherwise premultiply PNG colour by alpha.
OIIO::ImageSpec readConfig() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// The extension OpenImageIO needs to pick a reader for bytes in memory, from the bytes' signature.
std::string extensionFromSignature(const std::vector<unsigned char>& bytes) {
    auto starts_with = [&](const char* signature, size_t length) {
        return bytes.size() >= length && std::memcmp(bytes.data(), signature, length) == 0;
    };
    if (starts_with("\x89PNG", 4)) return ".png";
    if (starts_with("\xFF\xD8\xFF", 3)) return ".jpg";
    if (starts_with("#?RADIANCE", 10) || starts_with("#?RGBE", 6)) return ".hdr";
    if (starts_with("\x76\x2F\x31\x01", 4)) return ".exr";
    if (starts_with("BM", 2)) return ".bmp";
    if (starts_with("GIF8", 4)) return ".gif";
    if (starts_with("RIFF", 4) && bytes.size() >= 12 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
        return ".webp";
    return "";
}

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

ImageRGBA readImage(const std::string& path, ImageEncoding encoding) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) throw InputError(path, "", "file not found");
    const OIIO::ImageSpec config = readConfig();
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path, &config);
    if (!input) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
    return readOpenedImage(path, *input, encoding);
}

ImageRGBA readImageFromMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                              ImageEncoding encoding) {
    if (bytes.empty()) throw InputError(name, "", "image data is empty");
    const std::string extension = extensionFromSignature(bytes);
    if (extension.empty()) throw InputError(name, "", "image data in an unknown format");
    OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
    OIIO::ImageSpec config = readConfig();
    // The proxy goes both to open() and into the config: OpenImageIO 2.4's readers look for it in the config.
    void* reader_pointer = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &reader_pointer);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open("memory" + extension, &config, &reader);
    if (!input) throw InputError(name, "", "cannot read image: " + OIIO::geterror());
    return readOpenedImage(name, *input, encoding);
}

ImageRGBA readRadianceMap(const std::string& path) {
    const std::string extension = lowerCaseExtension(path);
    if (extension != ".hdr" && extension != ".exr")
        throw InputError(path, "", "a radiance map must be .hdr or .exr (linear HDR), not '" + extension + "'");
    ImageRGBA image = readImage(path, ImageEncoding::Linear);
    static const char* const kChannelNames[3] = {"R", "G", "B"};
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float* radiance = image.texel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float value = radiance[c];
                if (std::isfinite(value) && value >= 0.0f) continue;
                std::ostringstream field;
                field << "texel (" << x << ", " << y << ") channel " << kChannelNames[c];
                std::string problem;
                if (std::isnan(value))
                    problem = "NaN radiance";
                else if (std::isinf(value))
                    problem = "infinite radiance";
                else
                    problem = "negative radiance " + std::to_string(value);
                throw InputError(path, field.str(), problem);
            }
        }
    }
    return image;
}

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
