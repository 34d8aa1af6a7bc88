// 8-bit sky photos (one, or an exposure bracket of one view) to a radiance map in the bake's units; the
// calibration, the clipping rule and the bracket weights are stated in gusuku/assets/sky_photo.h.
#include "gusuku/assets/sky_photo.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include <OpenImageIO/imageio.h>

#include "gusuku/assets/image.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"

namespace gusuku {

namespace {

// The bracket weight falls linearly to 0 over this many codes below the clip (the upper half of a hat): a
// camera's shoulder and JPEG's ringing make the last codes the least trustworthy, and the taper keeps the merge
// free of a seam where a member starts to clip.
constexpr double kClipTaperCodes = 32.0;
// Added to every unclipped member's weight so that a texel dark in every member still gets their mean.
constexpr double kMinimumWeight = 1e-6;

std::string lowerCaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

// Photos are held as 8-bit codes in 1/256ths (uint16): exact for the file's integer codes, fine enough for the
// fractional ones of a downsampled photo, and 6 bytes a texel where float RGBA takes 16 (a bracket of three
// 8192 x 4096 photos: 0.6 GB, not 1.6 GB). Decoding and weights are tables over these values.
constexpr int kFixedPerCode = 256;
constexpr int kFixedMaximum = 255 * kFixedPerCode;
constexpr int kFixedClipped = kSkyPhotoClippedCode * kFixedPerCode;

/// Weight of a member whose brightest channel has code m (0..255, fractional after downsampling): the inverse
/// square of the relative quantisation step of the sRGB code there (dL/L per code: 1/m in the curve's linear
/// foot, about 2.4 / (m + 14) above), so each member counts by how precisely its 8 bits hold the texel,
/// tapered to 0 at the clip.
double bracketWeight(double code) {
    const double step =
        srgbDecode(std::min(code + 0.5, 255.0) / 255.0) - srgbDecode(std::max(code - 0.5, 0.0) / 255.0);
    const double linear = srgbDecode(code / 255.0);
    const double precision = linear > 0.0 ? (linear / step) * (linear / step) : 0.0;
    const double taper = std::clamp((kSkyPhotoClippedCode - code) / kClipTaperCodes, 0.0, 1.0);
    return precision * taper + kMinimumWeight;
}

/// srgbDecode and bracketWeight of every fixed-point code.
struct CodeTables {
    std::vector<double> linear, weight;
    CodeTables() : linear(kFixedMaximum + 1), weight(kFixedMaximum + 1) {
        for (int i = 0; i <= kFixedMaximum; ++i) {
            const double code = double(i) / kFixedPerCode;
            linear[size_t(i)] = srgbDecode(code / 255.0);
            weight[size_t(i)] = bracketWeight(code);
        }
    }
};

const CodeTables& codeTables() {
    static const CodeTables tables;
    return tables;
}

/// One photo's codes (RGB, fixed point) and scale.
struct EncodedPhoto {
    std::string path;
    double ev100 = 0.0;
    double radiance_scale = 0.0;  ///< bake units of linear 1
    int width = 0, height = 0;
    std::vector<uint16_t> codes;  ///< width * height * 3, code x 256

    const uint16_t* texel(int x, int y) const { return codes.data() + (size_t(y) * size_t(width) + size_t(x)) * 3; }
};

/// The reader's checks, then that the data is 8-bit PNG or JPEG: what the file holds decides, not its name.
void checkPhotoFormat(const std::string& path) {
    readImageSize(path);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw InputError(path, "", "cannot read image: " + OIIO::geterror());
    const std::string format = input->format_name();
    if (format != "png" && format != "jpeg")
        throw InputError(path, "", "holds " + format + " data: an 8-bit sky photo must be PNG or JPEG");
    if (input->spec().format != OIIO::TypeDesc::UINT8)
        throw InputError(path, "", std::string("holds ") + input->spec().format.c_str() +
                                       " channels: an 8-bit sky photo must have 8 bits a channel");
}

EncodedPhoto readEncodedPhoto(const SkyPhotoConfig& config) {
    if (!isSkyPhotoExtension(lowerCaseExtension(config.path)))
        throw InputError(config.path, "", "an 8-bit sky photo must be .jpg, .jpeg or .png");
    checkPhotoFormat(config.path);
    // The file's own size decides (the reader keeps a 2:1 file 2:1 when it downsamples one above kMaxImageSide).
    const ImageSize file_size = readImageSize(config.path);
    if (int64_t(file_size.width) != 2 * int64_t(file_size.height))
        throw InputError(config.path, "size",
                         std::to_string(file_size.width) + " x " + std::to_string(file_size.height) +
                             " is not the 2:1 of an equirectangular sky");
    EncodedPhoto photo;
    photo.path = config.path;
    photo.ev100 = skyPhotoEv100(config.path, config.ev100);
    photo.radiance_scale = skyPhotoRadianceScale(photo.ev100);
    // ImageEncoding::Linear reads 8-bit data as code / 255, undecoded (box-averaged when downsampled).
    const ImageRGBA encoded = readImage(config.path, ImageEncoding::Linear);
    if (encoded.width != 2 * encoded.height)  // a reader that broke the proportion; never a user's mistake
        throw InputError(config.path, "size",
                         std::to_string(file_size.width) + " x " + std::to_string(file_size.height) + " read as " +
                             std::to_string(encoded.width) + " x " + std::to_string(encoded.height) +
                             ", not 2:1: the reader's downsample broke the sky's proportion");
    photo.width = encoded.width;
    photo.height = encoded.height;
    photo.codes.resize(size_t(encoded.width) * size_t(encoded.height) * 3);
    for (size_t i = 0, n = size_t(encoded.width) * size_t(encoded.height); i < n; ++i)
        for (size_t c = 0; c < 3; ++c)
            photo.codes[i * 3 + c] = uint16_t(std::lround(
                std::clamp(double(encoded.texels[i * 4 + c]), 0.0, 1.0) * double(kFixedMaximum)));
    return photo;
}

/// Merges one texel from every photo; returns false when every photo holds it clipped. Then it is the least
/// radiance the darkest photo's codes allow: a clipped channel its saturation white, the others their value.
bool mergeTexel(const std::vector<EncodedPhoto>& photos, const CodeTables& tables, int x, int y,
                float* radiance_out) {
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    double weight_sum = 0.0;
    const EncodedPhoto* darkest = &photos.front();
    for (const EncodedPhoto& photo : photos) {
        const uint16_t* codes = photo.texel(x, y);
        if (photo.radiance_scale > darkest->radiance_scale) darkest = &photo;
        const uint16_t brightest = std::max({codes[0], codes[1], codes[2]});
        if (brightest >= kFixedClipped) continue;
        const double weight = photos.size() == 1 ? 1.0 : tables.weight[brightest];
        for (int c = 0; c < 3; ++c) sum[c] += weight * tables.linear[codes[c]] * photo.radiance_scale;
        weight_sum += weight;
    }
    radiance_out[3] = 1.0f;
    if (weight_sum > 0.0) {
        for (int c = 0; c < 3; ++c) radiance_out[c] = float(sum[c] / weight_sum);
        return true;
    }
    const uint16_t* codes = darkest->texel(x, y);
    for (int c = 0; c < 3; ++c)
        radiance_out[c] = float((codes[c] >= kFixedClipped ? 1.0 : tables.linear[codes[c]]) * darkest->radiance_scale);
    return false;
}

}  // namespace

ImageRGBA readSkyPhotos(const std::vector<SkyPhotoConfig>& configs, SkyPhotoSummary* summary) {
    if (configs.empty()) throw InputError("", "bracket", "no sky photo given");
    std::vector<EncodedPhoto> photos;
    photos.reserve(configs.size());
    for (const SkyPhotoConfig& config : configs) {
        photos.push_back(readEncodedPhoto(config));
        const EncodedPhoto& first = photos.front();
        const EncodedPhoto& last = photos.back();
        if (last.width != first.width || last.height != first.height)
            throw InputError(last.path, "size",
                             std::to_string(last.width) + " x " + std::to_string(last.height) +
                                 " differs from the bracket's first photo " + first.path + " (" +
                                 std::to_string(first.width) + " x " + std::to_string(first.height) +
                                 "): a bracket is one view");
    }
    const CodeTables& tables = codeTables();
    ImageRGBA radiance;
    radiance.width = photos.front().width;
    radiance.height = photos.front().height;
    radiance.texels.assign(size_t(radiance.width) * size_t(radiance.height) * 4, 0.0f);
    size_t clipped = 0;
    for (int y = 0; y < radiance.height; ++y)
        for (int x = 0; x < radiance.width; ++x)
            if (!mergeTexel(photos, tables, x, y, radiance.texel(x, y))) ++clipped;
    if (summary) {
        summary->ev100.clear();
        for (const EncodedPhoto& photo : photos) summary->ev100.push_back(photo.ev100);
        summary->clipped_texel_count = clipped;
        summary->texel_count = size_t(radiance.width) * size_t(radiance.height);
    }
    return radiance;
}

ImageRGBA readSkyRadiance(const SkyConfig& sky, SkyPhotoSummary* summary) {
    if (!sky.photos.empty()) return readSkyPhotos(sky.photos, summary);
    if (isSkyPhotoExtension(lowerCaseExtension(sky.path)))
        return readSkyPhotos({SkyPhotoConfig{sky.path, {}}}, summary);  // a bare photo path: EXIF exposure
    if (summary) *summary = SkyPhotoSummary{};
    return readRadianceMap(sky.path);
}

}  // namespace gusuku
