// Reading image files through OpenImageIO into linear float RGBA (gusuku/assets/image.h). The header is checked before
// a texel is decoded, large images are box-downsampled band by band while they are decoded (never held at full
// size), and whatever OpenImageIO or its codecs print on stderr (libpng's "libpng error: ...") is captured and
// folded into the one-line InputError.
#include "gusuku/assets/image.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "gusuku/formats/input_error.h"
#include "one_line.h"
#include "regular_file.h"

namespace gusuku {

namespace {

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

// libpng (under OpenImageIO's PNG reader) prints "libpng error: ..." to stderr before OpenImageIO reports the
// same failure through geterror(). While an image is opened or decoded, file descriptor 2 points at a temporary
// file; the captured text is handed back so it can be folded into the error, and nothing reaches the terminal.
// One capture at a time (the descriptor is process-wide).
class StderrCapture {
public:
    StderrCapture() : lock_(mutex()) {
        std::fflush(stderr);
        capture_ = std::tmpfile();
        saved_descriptor_ = capture_ ? dup(STDERR_FILENO) : -1;
        if (saved_descriptor_ >= 0) dup2(fileno(capture_), STDERR_FILENO);
    }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;
    ~StderrCapture() { restore(); }

    /// Restores stderr and returns what was written to it meanwhile.
    std::string restore() {
        std::string text;
        if (saved_descriptor_ < 0) return text;
        std::fflush(stderr);
        dup2(saved_descriptor_, STDERR_FILENO);
        close(saved_descriptor_);
        saved_descriptor_ = -1;
        std::rewind(capture_);
        char buffer[512];
        size_t count;
        while ((count = std::fread(buffer, 1, sizeof buffer, capture_)) > 0 && text.size() < 4096)
            text.append(buffer, count);
        std::fclose(capture_);
        capture_ = nullptr;
        return text;
    }

private:
    static std::mutex& mutex() {
        static std::mutex instance;
        return instance;
    }
    std::unique_lock<std::mutex> lock_;
    FILE* capture_ = nullptr;
    int saved_descriptor_ = -1;
};

// The library's own error if it gave one, else what it printed; one line either way.
std::string libraryError(const std::string& reported, StderrCapture& capture) {
    const std::string printed = oneLine(capture.restore());
    const std::string folded = oneLine(reported);
    return folded.empty() ? (printed.empty() ? "unknown error" : printed) : folded;
}

// Keep straight (unassociated) alpha as stored: OpenImageIO would otherwise premultiply PNG colour by alpha.
OIIO::ImageSpec readConfig() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// Checks the header's dimensions before anything is allocated for them.
void checkHeader(const std::string& name, const OIIO::ImageSpec& spec) {
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth != 1)
        throw InputError(name, "", "image has no pixels or is not 2D (" + std::to_string(spec.width) + " x " +
                                       std::to_string(spec.height) + " x " + std::to_string(spec.depth) + ", " +
                                       std::to_string(spec.nchannels) + " channels)");
    if (int64_t(spec.width) * int64_t(spec.height) > kMaxImageFileTexels)
        throw InputError(name, "", "image header declares " + std::to_string(spec.width) + " x " +
                                       std::to_string(spec.height) + " texels, more than the " +
                                       std::to_string(kMaxImageFileTexels) +
                                       " (16384 x 16384) this reader decodes; refused before decoding");
}

// Grey, grey + alpha, RGB or RGBA values to RGBA (grey copied to R, G and B; `opaque` where there is no alpha).
template <typename T>
void expandToRgba(const T* in, int channels, size_t texel_count, T opaque, T* out) {
    for (size_t i = 0; i < texel_count; ++i, in += channels, out += 4) {
        if (channels <= 2) {  // grey, or grey + alpha
            out[0] = out[1] = out[2] = in[0];
            out[3] = channels == 2 ? in[1] : opaque;
        } else {
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
            out[3] = channels >= 4 ? in[3] : opaque;
        }
    }
}

// Reads rows [y_begin, y_end) of subimage 0, mip level 0 (file channels [0, channels)) as `format` into `rows`,
// from a scanline file or a tiled one alike. A tiled file (as Nuke, Blender and maketx write OpenEXR) can only be
// read by whole tiles, and read_scanlines on one fails deep inside the codec, so the tile rows that cover the range
// are read into `tile_rows` and the wanted rows copied out of them.
bool readFileRows(const std::string& name, OIIO::ImageInput& input, int y_begin, int y_end, int channels,
                  OIIO::TypeDesc format, void* rows, std::vector<unsigned char>& tile_rows) {
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.tile_width <= 0 || spec.tile_height <= 0)
        return input.read_scanlines(0, 0, spec.y + y_begin, spec.y + y_end, 0, 0, channels, format, rows);
    const int tile_height = spec.tile_height;
    // One row of tiles is held at a time; real files use tiles of 32 to 256 texels, so a header whose row of
    // tiles alone would take more than kMaxTileRowBytes is refused rather than allocated.
    constexpr uint64_t kMaxTileRowBytes = uint64_t(256) << 20;
    const uint64_t tile_row_bytes = uint64_t(spec.width) * uint64_t(std::min(tile_height, spec.height)) *
                                    uint64_t(channels) * uint64_t(format.size());
    if (tile_row_bytes > kMaxTileRowBytes)
        throw InputError(name, "", "tiles of " + std::to_string(spec.tile_width) + " x " +
                                       std::to_string(spec.tile_height) + " texels: a row of them takes " +
                                       std::to_string(tile_row_bytes >> 20) + " MiB, more than the " +
                                       std::to_string(kMaxTileRowBytes >> 20) + " MiB this reader holds");
    const int tiles_begin = (y_begin / tile_height) * tile_height;
    const int tiles_end = std::min(spec.height, ((y_end + tile_height - 1) / tile_height) * tile_height);
    const size_t row_bytes = size_t(spec.width) * size_t(channels) * format.size();
    tile_rows.resize(row_bytes * size_t(tiles_end - tiles_begin));
    if (!input.read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + tiles_begin, spec.y + tiles_end, spec.z,
                          spec.z + std::max(1, spec.depth), 0, channels, format, tile_rows.data()))
        return false;
    std::memcpy(rows, tile_rows.data() + row_bytes * size_t(y_begin - tiles_begin),
                row_bytes * size_t(y_end - y_begin));
    return true;
}

// The reduced image's size: the shorter side divided by `factor`, rounded up, and the longer side in the file's
// proportion to it (rounded, and at most side_limit). Dividing both sides by the factor and rounding each up
// broke an exactly 2:1 sky photo of 8194 x 4097 into 4097 x 2049; in proportion it becomes 4098 x 2049.
struct ReducedSize {
    int width = 0, height = 0;
};
ReducedSize reducedSize(int width, int height, int factor, int side_limit) {
    if (factor <= 1) return {width, height};
    const bool wide = width >= height;
    const int long_side = wide ? width : height;
    const int short_side = wide ? height : width;
    const int reduced_short = (short_side + factor - 1) / factor;
    const int64_t proportional_long = (int64_t(long_side) * reduced_short * 2 + short_side) / (int64_t(short_side) * 2);
    const int reduced_long = int(std::clamp<int64_t>(proportional_long, 1, std::min(side_limit, long_side)));
    return wide ? ReducedSize{reduced_long, reduced_short} : ReducedSize{reduced_short, reduced_long};
}

// The reduced texel that file texel `file_index` (of `file_count` along a side) falls in, when `reduced_count`
// reduced texels share that side evenly: floor(file_index x reduced_count / file_count).
int reducedIndex(int file_index, int reduced_count, int file_count) {
    return int(int64_t(file_index) * reduced_count / file_count);
}

// The first file texel along a side that falls in reduced texel `reduced_index` (file_count past the last):
// ceil(reduced_index x file_count / reduced_count), the inverse of reducedIndex.
int firstFileIndex(int reduced_index, int reduced_count, int file_count) {
    return int((int64_t(reduced_index) * file_count + reduced_count - 1) / reduced_count);
}

// Reads subimage 0 of an opened input into linear RGBA, box-averaging onto `size` (reducedSize): each reduced
// texel is the mean of the file texels that fall in it (reducedIndex; `factor` x `factor` blocks when the sides
// divide by the factor), band by band, so at most one band of the file's rows is held at its full width.
ImageRGBA decodeReduced(const std::string& name, OIIO::ImageInput& input, bool is_srgb, int factor,
                        ReducedSize size, StderrCapture& capture) {
    const OIIO::ImageSpec spec = input.spec();
    const int file_channels = std::min(spec.nchannels, 4);  // colour and alpha; further channels are not read
    ImageRGBA image;
    image.width = size.width;
    image.height = size.height;
    // Reserved, not filled: the rows are added band by band as they decode, so a header that declares a large
    // image over a file that ends early fails after touching one band's memory, not the whole image's (a
    // fuzzed 8192^2 EXR took 6 s of page faults zero-filling a gigabyte before its first row failed).
    image.texels.reserve(size_t(image.width) * size_t(image.height) * 4);

    // A band is a whole number of block rows, about a million file texels.
    const int block_rows_per_band = std::max(1, int((size_t(1) << 20) / (size_t(spec.width) * size_t(factor))));
    // 8-bit sRGB files are read as bytes and decoded by table (srgbDecodeBytes: the same values as decoding
    // them as floats, without a pow per channel).
    const bool byte_srgb = is_srgb && spec.format == OIIO::TypeDesc::UINT8;
    std::vector<float> file_values;
    std::vector<uint8_t> file_bytes, rgba_bytes;
    std::vector<unsigned char> tile_rows;  // a tiled file's covering tile rows (readFileRows)
    ImageRGBA band;
    std::vector<double> sums(size_t(image.width) * 4);
    std::vector<int> counts(size_t(image.width));
    for (int first_out_row = 0; first_out_row < image.height; first_out_row += block_rows_per_band) {
        const int out_rows = std::min(block_rows_per_band, image.height - first_out_row);
        const int y_begin = firstFileIndex(first_out_row, image.height, spec.height);
        const int y_end = firstFileIndex(first_out_row + out_rows, image.height, spec.height);
        const int band_rows = y_end - y_begin;
        const size_t band_texels = size_t(spec.width) * size_t(band_rows);
        band.width = spec.width;
        band.height = band_rows;
        band.texels.resize(band_texels * 4);
        if (byte_srgb) {
            // 8-bit sRGB (most textures): bytes to RGBA bytes, then one table lookup per channel.
            file_bytes.resize(band_texels * size_t(file_channels));
            if (!readFileRows(name, input, y_begin, y_end, file_channels, OIIO::TypeDesc::UINT8, file_bytes.data(),
                              tile_rows))
                throw InputError(name, "", "cannot decode image: " + libraryError(input.geterror(), capture));
            rgba_bytes.resize(band_texels * 4);
            expandToRgba(file_bytes.data(), file_channels, band_texels, uint8_t(255), rgba_bytes.data());
            srgbDecodeBytes(rgba_bytes.data(), band_texels, band.texels.data());
        } else {
            file_values.resize(band_texels * size_t(file_channels));
            if (!readFileRows(name, input, y_begin, y_end, file_channels, OIIO::TypeDesc::FLOAT, file_values.data(),
                              tile_rows))
                throw InputError(name, "", "cannot decode image: " + libraryError(input.geterror(), capture));
            expandToRgba(file_values.data(), file_channels, band_texels, 1.0f, band.texels.data());
            if (is_srgb) srgbDecodeImage(band);
        }

        image.texels.resize(size_t(image.width) * size_t(first_out_row + out_rows) * 4);
        for (int out_row = 0; out_row < out_rows; ++out_row) {
            const int row_begin = firstFileIndex(first_out_row + out_row, image.height, spec.height) - y_begin;
            const int row_end = firstFileIndex(first_out_row + out_row + 1, image.height, spec.height) - y_begin;
            std::fill(sums.begin(), sums.end(), 0.0);
            std::fill(counts.begin(), counts.end(), 0);
            for (int y = row_begin; y < row_end; ++y) {
                for (int x = 0; x < spec.width; ++x) {
                    const int out_x = reducedIndex(x, image.width, spec.width);
                    const float* texel = band.texel(x, y);
                    for (int c = 0; c < 4; ++c) sums[size_t(out_x) * 4 + size_t(c)] += texel[c];
                    ++counts[size_t(out_x)];
                }
            }
            float* out = image.texel(0, first_out_row + out_row);
            for (size_t i = 0; i < sums.size(); ++i) out[i] = float(sums[i] / counts[i / 4]);
        }
    }
    return image;
}

// True when every line of a decoder's report is libjpeg's JWRN_EXTRANEOUS_DATA, as OpenImageIO 2.4 words it:
// 'JPEG error: Corrupt JPEG data: 3 extraneous bytes before marker 0xda ("sky.jpg")': bytes skipped between
// segments, every pixel decoded.
bool onlyExtraneousBytes(const std::string& report) {
    static const std::regex extraneous(
        R"(JPEG error: Corrupt JPEG data: \d+ extraneous bytes before marker 0x[0-9a-fA-F]+.*)");
    std::istringstream lines(report);
    bool any = false;
    for (std::string line; std::getline(lines, line);) {
        if (line.empty()) continue;
        if (!std::regex_match(line, extraneous)) return false;
        any = true;
    }
    return any;
}

ImageRGBA readOpenedImage(const std::string& name, OIIO::ImageInput& input, ImageEncoding encoding, int max_side,
                          StderrCapture& capture) {
    const OIIO::ImageSpec& spec = input.spec();
    checkHeader(name, spec);
    const int side_limit = max_side > 0 ? std::min(max_side, kMaxImageSide) : kMaxImageSide;
    const int longest_side = std::max(spec.width, spec.height);
    const int factor = longest_side > side_limit ? (longest_side + side_limit - 1) / side_limit : 1;
    const bool is_srgb = encoding == ImageEncoding::Srgb ||
                         (encoding == ImageEncoding::Auto && !isFloatFormat(spec.format));
    ImageRGBA image = decodeReduced(name, input, is_srgb, factor,
                                    reducedSize(spec.width, spec.height, factor, side_limit), capture);
    // A decoder that works around missing or corrupt data still returns every row but says so through the
    // input's error: libjpeg's "Premature end of JPEG file" on a truncated JPEG, whose missing rows it fills
    // with grey (a sky cut to 44 % of its bytes became flat grey without a word). Such an image is refused.
    // One libjpeg warning is about no pixel: "extraneous bytes before marker", padding that some cameras and
    // editors write between segments; an image whose only report is that one is read as it is.
    if (const std::string report = input.geterror(); !report.empty() && !onlyExtraneousBytes(report))
        throw InputError(name, "", "damaged image data, refused rather than read in part: " + oneLine(report));
    capture.restore();  // a codec's warnings on stderr for a good image are dropped
    return image;
}

// A PNG is a signature and a chain of chunks (length, type, data, CRC) ending with IEND. When the data ends inside
// a chunk, OpenImageIO 2.4's PNG reader reports it from libpng's read callback and libpng long-jumps over the
// reader's C++ frames, leaking its error string; so the chain is walked here first and a truncated file is refused
// before the codec sees it. `read(offset, count, out)` returns the bytes it could read at `offset`.
template <typename ReadAt>
std::string truncatedPngProblem(uint64_t size, ReadAt read) {
    uint64_t offset = 8;
    unsigned char header[8];
    while (offset + 8 <= size) {
        if (read(offset, 8, header) != 8) return "cannot read the PNG chunk header at byte " + std::to_string(offset);
        const uint64_t length = (uint64_t(header[0]) << 24) | (uint64_t(header[1]) << 16) |
                                (uint64_t(header[2]) << 8) | uint64_t(header[3]);
        const uint64_t end = offset + 12 + length;
        if (end > size)
            return "truncated PNG: the chunk at byte " + std::to_string(offset) + " needs " + std::to_string(end) +
                   " bytes, the data has " + std::to_string(size);
        if (std::memcmp(header + 4, "IEND", 4) == 0) return "";
        offset = end;
    }
    return "truncated PNG: no IEND chunk before the data ends at byte " + std::to_string(size);
}

bool hasPngSignature(const unsigned char* bytes, size_t size) {
    return size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
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

std::unique_ptr<OIIO::ImageInput> openFile(const std::string& path, StderrCapture& capture) {
    if (const std::string problem = regularFileProblem(path); !problem.empty()) throw InputError(path, "", problem);
    if (std::ifstream file(path, std::ios::binary); file) {
        unsigned char signature[8] = {};
        file.read(reinterpret_cast<char*>(signature), 8);
        if (hasPngSignature(signature, size_t(file.gcount()))) {
            const uint64_t size = std::filesystem::file_size(path);
            const std::string problem =
                truncatedPngProblem(size, [&](uint64_t offset, size_t count, unsigned char* out) {
                    file.clear();
                    file.seekg(std::streamoff(offset));
                    file.read(reinterpret_cast<char*>(out), std::streamsize(count));
                    return size_t(file.gcount());
                });
            if (!problem.empty()) throw InputError(path, "", problem);
        }
    }
    const OIIO::ImageSpec config = readConfig();
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path, &config);
    if (!input) throw InputError(path, "", "cannot read image: " + libraryError(OIIO::geterror(), capture));
    return input;
}

}  // namespace

ImageRGBA readImage(const std::string& path, ImageEncoding encoding, int max_side) {
    StderrCapture capture;
    std::unique_ptr<OIIO::ImageInput> input = openFile(path, capture);
    return readOpenedImage(path, *input, encoding, max_side, capture);
}

ImageRGBA readImageFromMemory(const std::string& name, const std::vector<unsigned char>& bytes,
                              ImageEncoding encoding, int max_side) {
    if (bytes.empty()) throw InputError(name, "", "image data is empty");
    const std::string extension = extensionFromSignature(bytes);
    if (extension.empty()) throw InputError(name, "", "image data in an unknown format");
    if (hasPngSignature(bytes.data(), bytes.size())) {
        const std::string problem =
            truncatedPngProblem(bytes.size(), [&](uint64_t offset, size_t count, unsigned char* out) {
                const size_t available = size_t(std::min<uint64_t>(count, bytes.size() - offset));
                std::memcpy(out, bytes.data() + offset, available);
                return available;
            });
        if (!problem.empty()) throw InputError(name, "", problem);
    }
    StderrCapture capture;
    OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
    OIIO::ImageSpec config = readConfig();
    // The proxy goes both to open() and into the config: OpenImageIO 2.4's readers look for it in the config.
    void* reader_pointer = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &reader_pointer);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open("memory" + extension, &config, &reader);
    if (!input) throw InputError(name, "", "cannot read image: " + libraryError(OIIO::geterror(), capture));
    return readOpenedImage(name, *input, encoding, max_side, capture);
}

ImageSize readImageSize(const std::string& path) {
    StderrCapture capture;
    std::unique_ptr<OIIO::ImageInput> input = openFile(path, capture);
    return {input->spec().width, input->spec().height};
}

ImageRGBA readFloatRgbaExr(const std::string& path, int max_side) {
    StderrCapture capture;
    std::unique_ptr<OIIO::ImageInput> input = openFile(path, capture);
    // What the file holds decides, not its name: OpenImageIO opens a PNG renamed .exr as a PNG.
    const std::string format = input->format_name();
    const OIIO::ImageSpec& spec = input->spec();
    bool every_channel_float = spec.format == OIIO::TypeDesc::FLOAT;
    for (const OIIO::TypeDesc& channel : spec.channelformats) every_channel_float &= channel == OIIO::TypeDesc::FLOAT;
    if (format != "openexr" || spec.nchannels != 4 || !every_channel_float)
        throw InputError(path, "", "holds " + format + " data with " + std::to_string(spec.nchannels) + " channel" +
                                       (spec.nchannels == 1 ? "" : "s") + " of " + spec.format.c_str() +
                                       ": expected OpenEXR with 4 float32 channels (RGBA)");
    return readOpenedImage(path, *input, ImageEncoding::Linear, max_side, capture);
}

ImageRGBA readRadianceMap(const std::string& path) {
    const std::string extension = lowerCaseExtension(path);
    if (extension != ".hdr" && extension != ".exr")
        throw InputError(path, "", "a radiance map must be .hdr or .exr (linear HDR), not '" + extension + "'");
    ImageRGBA image;
    {
        StderrCapture capture;
        std::unique_ptr<OIIO::ImageInput> input = openFile(path, capture);
        // OpenImageIO falls back to any reader that accepts the bytes, so a PNG renamed sky.hdr opens as a PNG:
        // the format actually read decides, not the name.
        const std::string format = input->format_name();
        if ((format != "hdr" && format != "openexr") || !isFloatFormat(input->spec().format))
            throw InputError(path, "", "holds " + (format == "png" || format == "jpeg" ? format + " 8-bit" : format) +
                                           " data (" + input->spec().format.c_str() +
                                           "): a sky must be an HDR radiance map (Radiance .hdr or OpenEXR .exr "
                                           "with half or float channels), not an 8-bit image");
        image = readOpenedImage(path, *input, ImageEncoding::Linear, kMaxImageSide, capture);
    }
    static const char* const kChannelNames[3] = {"R", "G", "B"};
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float* radiance = image.texel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float value = radiance[c];
                if (std::isfinite(value) && value >= 0.0f && value <= kMaxRadiance) continue;
                std::ostringstream field;
                field << "texel (" << x << ", " << y << ") channel " << kChannelNames[c];
                std::ostringstream problem;
                if (std::isnan(value))
                    problem << "NaN radiance";
                else if (std::isinf(value))
                    problem << "infinite radiance (a value beyond the range of the file's half or float channels)";
                else if (value < 0.0f)
                    problem << "negative radiance " << value;
                else
                    problem << "radiance " << value << " is above the limit " << kMaxRadiance
                            << " (beyond any real sky; its square would overflow float sums)";
                throw InputError(path, field.str(), problem.str());
            }
        }
    }
    return image;
}

}  // namespace gusuku
