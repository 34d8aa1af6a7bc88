// 8-bit sky photos as skies (gusuku/assets/sky_photo.h): a shared HDR sky is photographed in the test, by an
// independent statement of the camera model (ISO 12232 saturation speed, the sRGB curve, 8-bit rounding, a clip),
// written as PNG or JPEG with its EXIF through OpenImageIO, and read back.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bake_command.h"
#include "gpu_test_support.h"
#include "mini_site.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/maths/input_error.h"
#include "gusuku/maths/sun_air_mass.h"
#include "gusuku_bake/slot_lighting.h"

namespace {

using gusuku::ImageRGBA;
using gusuku::InputError;
using gusuku::SkyConfig;
using gusuku::SkyPhotoConfig;

/// The camera of the test, stated from the standards rather than the code under test: ISO 12232 saturation
/// speed (H_sat = 78 / S lx s, H = q L t / N^2, q = 0.65) and Radiance's 179 lm/W for the HDR's units.
struct TestCamera {
    double exposure_time_s = 1.0 / 1000.0;
    double f_number = 8.0;
    double iso = 100.0;
    double ev100() const { return std::log2(f_number * f_number / exposure_time_s) - std::log2(iso / 100.0); }
    /// HDR units (W sr^-1 m^-2, 179 cd m^-2 per unit of Y) that saturate the sensor.
    double saturatingRadiance() const {
        const double white_luminance = 78.0 / (0.65 * iso) * f_number * f_number / exposure_time_s;
        return white_luminance / 179.0;
    }
};

/// 8-bit code of an HDR channel photographed by `camera`: sRGB-encoded, clipped, rounded.
int photographedCode(double radiance, const TestCamera& camera) {
    const double linear = std::min(1.0, radiance / camera.saturatingRadiance());
    return int(std::lround(255.0 * gusuku::srgbEncode(linear)));
}

struct WriteOptions {
    bool jpeg = false;
    bool exif = true;
    double exposure_time_override = 0.0;  ///< written instead of the camera's when not 0
    int width = 0, height = 0;            ///< crop to this size when not 0
};

void writePhoto(const std::string& path, const ImageRGBA& hdr, const TestCamera& camera,
                const WriteOptions& options = {}) {
    const int width = options.width ? options.width : hdr.width;
    const int height = options.height ? options.height : hdr.height;
    std::vector<unsigned char> codes(size_t(width) * size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                codes[(size_t(y) * width + x) * 3 + c] = (unsigned char)photographedCode(hdr.texel(x, y)[c], camera);
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (options.exif) {
        spec.attribute("ExposureTime",
                       float(options.exposure_time_override != 0.0 ? options.exposure_time_override
                                                                   : camera.exposure_time_s));
        spec.attribute("FNumber", float(camera.f_number));
        spec.attribute("Exif:PhotographicSensitivity", int(camera.iso));
    }
    if (options.jpeg) {
        spec.attribute("Compression", "jpeg:100");
        spec.attribute("jpeg:subsampling", "4:4:4");
    }
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output && output->open(path, spec)) << OIIO::geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, codes.data()));
    ASSERT_TRUE(output->close());
}

std::string sharedSkyPath() {
    const std::string dir = gusuku::testing::sharedDataDir();
    const std::string path = dir + "/env/rooitou_park_1k.hdr";
    return (!dir.empty() && std::filesystem::exists(path)) ? path : "";
}

#define REQUIRE_SHARED_SKY()                                                                                   \
    do {                                                                                                       \
        if (sharedSkyPath().empty()) GTEST_SKIP() << "../shared/data/env/rooitou_park_1k.hdr is absent; skipped"; \
    } while (0)

std::string expectInputError(const std::function<void()>& action) {
    try {
        action();
    } catch (const InputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

/// The larger half of the radiance interval that rounds to `code` for a camera (the curve is convex, so the
/// half above the code's value): what 8-bit rounding may move a value by.
double halfCodeStep(int code, const TestCamera& camera) {
    const double at = gusuku::srgbDecode(code / 255.0);
    const double up = gusuku::srgbDecode(std::min(255.0, code + 0.5) / 255.0);
    const double down = gusuku::srgbDecode(std::max(0.0, code - 0.5) / 255.0);
    return std::max(up - at, at - down) * camera.saturatingRadiance();
}

int brightestCode(const ImageRGBA& hdr, int x, int y, const TestCamera& camera) {
    int code = 0;
    for (int c = 0; c < 3; ++c) code = std::max(code, photographedCode(hdr.texel(x, y)[c], camera));
    return code;
}

// The sky exposure: the diffuse sky is held, the sun and its glare clip.
TestCamera skyCamera() { return {1.0 / 1000.0, 8.0, 100.0}; }  // EV100 15.97

TEST(SkyPhoto, PngAtAKnownExposureReadsBackWithinItsQuantisation) {
    REQUIRE_SHARED_SKY();
    const ImageRGBA hdr = gusuku::readRadianceMap(sharedSkyPath());
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_png");
    const TestCamera camera = skyCamera();
    writePhoto(dir + "/sky.png", hdr, camera);
    // OpenImageIO 2.4 writes no EXIF into PNG: site.json's ev100 gives the exposure.
    gusuku::SkyPhotoSummary summary;
    const ImageRGBA back = gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/sky.png", camera.ev100()}}, &summary);
    ASSERT_EQ(back.width, hdr.width);
    ASSERT_EQ(back.height, hdr.height);
    size_t unclipped = 0, clipped = 0, outside = 0;
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) {
            const bool texel_clipped = brightestCode(hdr, x, y, camera) >= gusuku::kSkyPhotoClippedCode;
            texel_clipped ? ++clipped : ++unclipped;
            for (int c = 0; c < 3; ++c) {
                const double truth = hdr.texel(x, y)[c];
                if (photographedCode(truth, camera) >= gusuku::kSkyPhotoClippedCode) {  // the lower bound
                    EXPECT_NEAR(back.texel(x, y)[c], camera.saturatingRadiance(), 1e-4 * camera.saturatingRadiance());
                    continue;
                }
                const double allowed = halfCodeStep(photographedCode(truth, camera), camera) * 1.0001 + 1e-7;
                if (std::abs(back.texel(x, y)[c] - truth) > allowed) ++outside;
            }
        }
    std::printf("EV100 %.2f: %zu texels unclipped, %zu clipped (the sun and its glare)\n", camera.ev100(), unclipped,
                clipped);
    EXPECT_EQ(outside, 0u);
    EXPECT_EQ(summary.clipped_texel_count, clipped);
    EXPECT_GT(clipped, 3u);
    EXPECT_GT(unclipped, size_t(0.99 * hdr.width * hdr.height));
}

TEST(SkyPhoto, JpegExposureFromExifReadsBackWithinAFewCodes) {
    REQUIRE_SHARED_SKY();
    const ImageRGBA hdr = gusuku::readRadianceMap(sharedSkyPath());
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_jpeg");
    const TestCamera camera{1.0 / 500.0, 11.0, 200.0};
    WriteOptions jpeg;
    jpeg.jpeg = true;
    writePhoto(dir + "/sky.jpg", hdr, camera, jpeg);
    EXPECT_NEAR(gusuku::skyPhotoEv100(dir + "/sky.jpg", std::nullopt), camera.ev100(), 1e-5);
    SkyConfig sky;
    sky.path = dir + "/sky.jpg";  // a bare .jpg path: exposure from EXIF
    const ImageRGBA back = gusuku::readSkyRadiance(sky);
    // JPEG at quality 100 without chroma subsampling still rounds its DCT: allow 3 codes (6 half steps).
    size_t outside = 0, unclipped = 0;
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) {
            if (brightestCode(hdr, x, y, camera) >= gusuku::kSkyPhotoClippedCode - 8) continue;  // and its ringing
            ++unclipped;
            for (int c = 0; c < 3; ++c) {
                const double truth = hdr.texel(x, y)[c];
                const int code = photographedCode(truth, camera);
                if (std::abs(back.texel(x, y)[c] - truth) > 6.0 * halfCodeStep(code + 3, camera) + 1e-7) ++outside;
            }
        }
    std::printf("JPEG: %zu of %zu unclipped texel channels more than 3 codes off\n", outside, 3 * unclipped);
    EXPECT_LT(double(outside), 1e-3 * 3.0 * double(unclipped));
}

/// E_sun (luminance, bake units x sr) from a prepared sky as the bake takes it: the disc when unclipped, else
/// the clear-sky model calibrated on the diffuse light at the photo's sun (slot_lighting.cpp's rule).
double bakeSunLuminance(const gusuku::bake::PreparedSky& sky, bool* from_model) {
    const double elevation = std::asin(sky.disc.direction_enu.z) * 180.0 / std::numbers::pi;
    *from_model = sky.disc.clipped;
    const glm::dvec3 rgb = sky.disc.clipped
                               ? gusuku::calibratedClearSkySunRgb(sky.diffuse_horizontal_rgb, elevation, elevation)
                               : sky.disc.irradiance_rgb;
    return gusuku::luminanceRec709(rgb);
}

TEST(SkyPhoto, ClippedSunComesFromTheClearSkyModelOnTheUnclippedDiffuseLight) {
    REQUIRE_SHARED_SKY();
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_sun");
    const TestCamera camera = skyCamera();
    writePhoto(dir + "/sky.png", gusuku::readRadianceMap(sharedSkyPath()), camera);
    SkyConfig hdr_sky;
    hdr_sky.path = sharedSkyPath();
    const gusuku::bake::PreparedSky hdr = gusuku::bake::prepareSky(hdr_sky);
    ASSERT_TRUE(hdr.disc.found && !hdr.disc.clipped);
    SkyConfig photo_sky;
    photo_sky.path = dir + "/sky.png";
    photo_sky.photos = {SkyPhotoConfig{photo_sky.path, camera.ev100()}};
    const gusuku::bake::PreparedSky photo = gusuku::bake::prepareSky(photo_sky);
    ASSERT_TRUE(photo.disc.found);
    EXPECT_TRUE(photo.disc.clipped);
    EXPECT_LT(glm::degrees(std::acos(glm::dot(photo.disc.direction_enu, hdr.disc.direction_enu))), 1.0);
    bool from_model = false;
    const double measured = gusuku::luminanceRec709(hdr.disc.irradiance_rgb);
    const double photo_sun = bakeSunLuminance(photo, &from_model);
    EXPECT_TRUE(from_model);
    // The same model on the HDR's own diffuse light: what the photo can at best give.
    const double elevation = std::asin(hdr.disc.direction_enu.z) * 180.0 / std::numbers::pi;
    const double model_on_hdr = gusuku::luminanceRec709(
        gusuku::calibratedClearSkySunRgb(hdr.diffuse_horizontal_rgb, elevation, elevation));
    std::printf("sun at %.2f deg: measured in the HDR %.1f; clear-sky model on the photo %.1f (x%.3f), on the HDR "
                "%.1f (x%.3f); diffuse horizontal luminance photo / HDR %.4f\n",
                elevation, measured, photo_sun, photo_sun / measured, model_on_hdr, model_on_hdr / measured,
                photo.diffuse_horizontal_luminance / hdr.diffuse_horizontal_luminance);
    // The 8-bit photo loses no more than 10 % against the model on the HDR; the model itself stands within the
    // 1.4x that test_sun_colour allows a clear-sky fallback on this sky (1.32x measured).
    EXPECT_NEAR(photo_sun / model_on_hdr, 1.0, 0.10);
    EXPECT_NEAR(photo_sun / measured, 1.0, 0.40);
}

/// Three exposures of one view, about 7 stops apart (EV100 9.91, 16.88, 24.0): the brightest holds the shade,
/// the darkest the sun's disc (its peak at code 209).
std::vector<TestCamera> bracketCameras() {
    return {{1.0 / 60.0, 4.0, 100.0}, {1.0 / 1000.0, 11.0, 100.0}, {1.0 / 8000.0, 32.0, 50.0}};
}

TEST(SkyPhoto, BracketOfThreeMergesToTheHdrAndHoldsTheSun) {
    REQUIRE_SHARED_SKY();
    const ImageRGBA hdr_map = gusuku::readRadianceMap(sharedSkyPath());
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_bracket");
    std::vector<SkyPhotoConfig> photos;
    const std::vector<TestCamera> cameras = bracketCameras();
    for (size_t i = 0; i < cameras.size(); ++i) {
        const std::string path = dir + "/bracket_" + std::to_string(i) + ".png";
        writePhoto(path, hdr_map, cameras[i]);
        photos.push_back({path, cameras[i].ev100()});
    }
    const ImageRGBA merged = gusuku::readSkyPhotos(photos);
    std::vector<double> errors;
    double error_sum = 0.0, truth_sum = 0.0;
    for (int y = 0; y < hdr_map.height; ++y)
        for (int x = 0; x < hdr_map.width; ++x) {
            bool held = false;
            for (const TestCamera& camera : cameras)
                held = held || brightestCode(hdr_map, x, y, camera) < gusuku::kSkyPhotoClippedCode;
            if (!held) continue;
            const double truth = gusuku::luminanceRec709(glm::dvec3(hdr_map.texel(x, y)[0], hdr_map.texel(x, y)[1],
                                                                    hdr_map.texel(x, y)[2]));
            const float* m = merged.texel(x, y);
            const double back = gusuku::luminanceRec709(glm::dvec3(m[0], m[1], m[2]));
            errors.push_back(std::abs(back - truth) / std::max(truth, 1e-9));
            error_sum += std::abs(back - truth) * gusuku::equirectTexelSolidAngle(y, hdr_map.width, hdr_map.height);
            truth_sum += truth * gusuku::equirectTexelSolidAngle(y, hdr_map.width, hdr_map.height);
        }
    ASSERT_EQ(errors.size(), size_t(hdr_map.width) * size_t(hdr_map.height));  // every texel held by one of them
    std::sort(errors.begin(), errors.end());
    const double median = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100];
    std::printf("bracket: relative luminance error median %.4f, 99th percentile %.4f, largest %.4f; "
                "solid-angle weighted %.5f\n",
                median, p99, errors.back(), error_sum / truth_sum);
    EXPECT_LT(median, 0.01);
    EXPECT_LT(p99, 0.04);
    EXPECT_LT(error_sum / truth_sum, 0.01);

    // The darkest member holds the disc unclipped, so the merged map's sun is measured, not modelled.
    SkyConfig hdr_sky;
    hdr_sky.path = sharedSkyPath();
    const gusuku::bake::PreparedSky hdr = gusuku::bake::prepareSky(hdr_sky);
    SkyConfig bracket_sky;
    bracket_sky.path = photos.front().path;
    bracket_sky.photos = photos;
    const gusuku::bake::PreparedSky bracket = gusuku::bake::prepareSky(bracket_sky);
    ASSERT_TRUE(bracket.disc.found);
    bool from_model = true;
    const double sun = bakeSunLuminance(bracket, &from_model);
    const double measured = gusuku::luminanceRec709(hdr.disc.irradiance_rgb);
    std::printf("bracket's sun %.1f, the HDR's %.1f (x%.4f)\n", sun, measured, sun / measured);
    EXPECT_FALSE(from_model);
    EXPECT_NEAR(sun / measured, 1.0, 0.10);
}

// The command line end to end: the mini site's sunny sky as a bracket of two JPEGs with their EXIF, checked and
// baked; the manifest lists both photos as the sunny sky's inputs and reads back.
TEST(SkyPhoto, BakeTakesABracketOfJpegsFromSiteJson) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_bake");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    const ImageRGBA hdr = gusuku::readRadianceMap(dir + "/sky_sunny.hdr");
    WriteOptions jpeg;
    jpeg.jpeg = true;
    // The mini sky is dim: a long exposure. Not 1/2 s: OpenImageIO 2.4's EXIF writer stores a power-of-two float
    // time as a broken rational (0.5 and 0.25 read back inf, 1 and 2 are dropped).
    writePhoto(dir + "/bright.jpg", hdr, TestCamera{0.4, 2.0, 100.0}, jpeg);
    writePhoto(dir + "/dark.jpg", hdr, TestCamera{1.0 / 60.0, 2.0, 100.0}, jpeg);
    nlohmann::json site = nlohmann::json::parse(std::ifstream(site_path));
    site["skies"]["sunny"] = {{"bracket", nlohmann::json::array({{{"path", "bright.jpg"}}, {{"path", "dark.jpg"}}})}};
    std::ofstream(site_path, std::ios::trunc) << site.dump(2);

    const gusuku::testing::CommandResult check = gusuku::testing::runBakeCommand({"check", site_path}, dir);
    ASSERT_EQ(check.exit_code, 0) << check.stderr_text;
    EXPECT_NE(check.stdout_text.find("8-bit photos (an exposure bracket) at EV100 3.32 7.91;"), std::string::npos)
        << check.stdout_text;
    const gusuku::testing::CommandResult bake = gusuku::testing::runBakeCommand(
        {"bake", site_path, "-o", dir + "/bakeset", "--samples", "4", "--quiet"}, dir);
    ASSERT_EQ(bake.exit_code, 0) << bake.stderr_text;
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir + "/bakeset/manifest.json"));
    std::vector<std::string> sunny_inputs;
    for (const nlohmann::json& input : manifest["inputs"])
        if (input["role"] == "sunny_sky") sunny_inputs.push_back(input["path"]);
    EXPECT_EQ(sunny_inputs, (std::vector<std::string>{"../bright.jpg", "../dark.jpg"}));
}

TEST(SkyPhoto, CheckWarnsOfAnOverexposedSky) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_overexposed");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    // Four stops over the bracket test's brighter photo: most of the mini sky clips.
    writePhoto(dir + "/over.jpg", gusuku::readRadianceMap(dir + "/sky_sunny.hdr"), TestCamera{0.4, 2.0, 1600.0},
               WriteOptions{true, true, 0.0, 0, 0});
    nlohmann::json site = nlohmann::json::parse(std::ifstream(site_path));
    site["skies"]["sunny"] = {{"path", "over.jpg"}};
    std::ofstream(site_path, std::ios::trunc) << site.dump(2);
    const gusuku::testing::CommandResult check = gusuku::testing::runBakeCommand({"check", site_path}, dir);
    ASSERT_EQ(check.exit_code, 0) << check.stderr_text;
    EXPECT_NE(check.stdout_text.find("texels clipped in every photo, more than a sun's glare"), std::string::npos)
        << check.stdout_text;
}

TEST(SkyPhoto, BadPhotosAreRefusedInOneLineNamingFileAndField) {
    ImageRGBA grey;
    grey.width = 64;
    grey.height = 32;
    grey.texels.assign(64 * 32 * 4, 1.0f);
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_bad");
    const TestCamera camera = skyCamera();
    WriteOptions no_exif;
    no_exif.jpeg = true;
    no_exif.exif = false;
    writePhoto(dir + "/no_exif.jpg", grey, camera, no_exif);
    EXPECT_EQ(expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/no_exif.jpg", {}}}); }),
              dir + "/no_exif.jpg: ExposureTime: absent from the photo's EXIF; give the sky's exposure as \"ev100\" "
                    "in site.json instead");
    // With ev100 given, the same photo reads.
    EXPECT_NO_THROW(gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/no_exif.jpg", 12.0}}));

    WriteOptions zero_time;
    zero_time.jpeg = true;
    // EXIF stores ExposureTime as an unsigned rational: a negative time written through OpenImageIO reads back 0.
    zero_time.exposure_time_override = -1.0;
    writePhoto(dir + "/zero_time.jpg", grey, camera, zero_time);
    const std::string zero =
        expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/zero_time.jpg", {}}}); });
    std::printf("%s\n", zero.c_str());
    EXPECT_EQ(zero.rfind(dir + "/zero_time.jpg: ExposureTime: ", 0), 0u) << zero;
    EXPECT_NE(zero.find("is not a positive, finite exposure value"), std::string::npos) << zero;
    EXPECT_EQ(zero.find('\n'), std::string::npos);

    WriteOptions square;
    square.width = 32;
    square.height = 32;
    writePhoto(dir + "/square.png", grey, camera, square);
    EXPECT_EQ(expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/square.png", 12.0}}); }),
              dir + "/square.png: size: 32 x 32 is not the 2:1 of an equirectangular sky");

    writePhoto(dir + "/small.png", grey, camera, WriteOptions{false, true, 0.0, 32, 16});
    writePhoto(dir + "/large.png", grey, camera);
    EXPECT_EQ(expectInputError([&] {
                  gusuku::readSkyPhotos(
                      {SkyPhotoConfig{dir + "/large.png", 12.0}, SkyPhotoConfig{dir + "/small.png", 9.0}});
              }),
              dir + "/small.png: size: 32 x 16 differs from the bracket's first photo " + dir +
                  "/large.png (64 x 32): a bracket is one view");
    // An HDR renamed .png is no 8-bit photo.
    gusuku::writeHdr(dir + "/renamed.hdr", grey);
    std::filesystem::copy_file(dir + "/renamed.hdr", dir + "/renamed.png");
    EXPECT_EQ(expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/renamed.png", 12.0}}); }),
              dir + "/renamed.png: holds hdr data: an 8-bit sky photo must be PNG or JPEG");
}

}  // namespace
