// 8-bit sky photos as skies (gusuku/assets/sky_photo.h): a shared HDR sky is photographed in the test, by an
// independent statement of the camera model (ISO 12232 saturation speed, the sRGB curve, 8-bit rounding, a clip),
// written as PNG or JPEG with its EXIF through OpenImageIO, and read back.
#include <algorithm>
#include <array>
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
#include "gusuku/assets/atomic_file.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku/assets/sky_photo.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/maths/exposure.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/sun_air_mass.h"
#include "gusuku/maths/sun_irradiance.h"
#include "gusuku_bake/sky_model.h"
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

/// A shared sunny sky and its photo at the sky exposure, both prepared as the bake prepares them.
struct PhotographedSharedSky {
    gusuku::bake::PreparedSky hdr, photo;
    double elevation_deg = 0.0;      ///< the HDR's sun
    double measured = 0.0;           ///< the HDR's E_sun, luminance
};

std::optional<PhotographedSharedSky> photographSharedSky(const char* file, const std::string& dir) {
    const std::string path = gusuku::testing::sharedDataDir() + "/env/" + file;
    if (gusuku::testing::sharedDataDir().empty() || !std::filesystem::exists(path)) return std::nullopt;
    const TestCamera camera = skyCamera();
    writePhoto(dir + "/sky.png", gusuku::readRadianceMap(path), camera);
    PhotographedSharedSky sky;
    SkyConfig hdr_sky;
    hdr_sky.path = path;
    sky.hdr = gusuku::bake::prepareSky(hdr_sky);
    SkyConfig photo_sky;
    photo_sky.path = dir + "/sky.png";
    photo_sky.photos = {SkyPhotoConfig{photo_sky.path, camera.ev100()}};
    sky.photo = gusuku::bake::prepareSky(photo_sky);
    sky.elevation_deg = std::asin(sky.hdr.disc.direction_enu.z) * 180.0 / std::numbers::pi;
    sky.measured = gusuku::luminanceRec709(sky.hdr.disc.irradiance_rgb);
    return sky;
}

double elevationDeg(const gusuku::bake::SunDiscEstimate& disc) {
    return std::asin(disc.direction_enu.z) * 180.0 / std::numbers::pi;
}

// The two sunny shared skies: rooitou_park clear with a low sun, immenstadter_horn partly cloudy with its sun
// veiled (its disc holds 0.64x the diffuse light; a clear sun holds 7-10x).
constexpr const char* kSunnySharedSkies[] = {"rooitou_park_1k.hdr", "immenstadter_horn_1k.hdr"};

TEST(SkyPhoto, ClippedSunComesFromTheClearSkyModelOnTheUnclippedDiffuseLight) {
    REQUIRE_SHARED_SKY();
    for (const char* file : kSunnySharedSkies) {
        const std::optional<PhotographedSharedSky> sky =
            photographSharedSky(file, gusuku::testing::makeTemporaryDirectory("sky_photo_sun"));
        ASSERT_TRUE(sky) << file;
        ASSERT_TRUE(sky->hdr.disc.found && !sky->hdr.disc.clipped) << file;
        ASSERT_TRUE(sky->photo.disc.found) << file;
        EXPECT_TRUE(sky->photo.disc.clipped) << file;
        EXPECT_LT(glm::degrees(std::acos(glm::dot(sky->photo.disc.direction_enu, sky->hdr.disc.direction_enu))), 1.0);
        bool from_model = false;
        const double photo_sun = bakeSunLuminance(sky->photo, &from_model);
        EXPECT_TRUE(from_model);
        // The same model on the HDR's own diffuse light: what the photo can at best give.
        const double h = sky->elevation_deg;
        const double model_on_hdr = gusuku::luminanceRec709(
            gusuku::calibratedClearSkySunRgb(sky->hdr.diffuse_horizontal_rgb, h, h));
        std::printf("%s: sun at %.2f deg: measured in the HDR %.2f; clear-sky model on the photo %.2f (x%.3f), on "
                    "the HDR %.2f (x%.3f); diffuse horizontal luminance photo / HDR %.4f\n",
                    file, h, sky->measured, photo_sun, photo_sun / sky->measured, model_on_hdr,
                    model_on_hdr / sky->measured,
                    sky->photo.diffuse_horizontal_luminance / sky->hdr.diffuse_horizontal_luminance);
        // The 8-bit photo loses no more than 10 % against the model on the HDR.
        EXPECT_NEAR(photo_sun / model_on_hdr, 1.0, 0.10) << file;
        // The model itself stands within the 1.4x that test_sun_colour allows a clear-sky fallback on the clear
        // sky (1.32x measured). On the veiled sun it is far off (13.8x): reported, not asserted.
        if (std::string(file) == "rooitou_park_1k.hdr") {
            EXPECT_NEAR(photo_sun / sky->measured, 1.0, 0.40);
        }
    }
}

// With the lux meter's reading at the capture (here the HDR's own global horizontal illuminance: its diffuse light
// plus its measured sun on the horizontal, at 179 lm per unit), one clipped photo's sun comes back by energy.
TEST(SkyPhoto, ClippedSunFromALuxReadingIsWithinTenPercentOfTheMeasuredSun) {
    REQUIRE_SHARED_SKY();
    for (const char* file : kSunnySharedSkies) {
        const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_lux");
        const std::optional<PhotographedSharedSky> sky = photographSharedSky(file, dir);
        ASSERT_TRUE(sky && sky->photo.disc.found && sky->photo.disc.clipped) << file;
        const double h_photo = elevationDeg(sky->photo.disc);
        const double lux = gusuku::kRadianceWhiteEfficacy *
                           (sky->hdr.diffuse_horizontal_luminance +
                            sky->measured * std::sin(sky->elevation_deg * std::numbers::pi / 180.0));
        const glm::dvec3 sun = gusuku::bake::sunFromGlobalHorizontalLux(sky->photo, lux, h_photo, h_photo, "site.json");
        const double ratio = gusuku::luminanceRec709(sun) / sky->measured;
        std::printf("%s: global horizontal %.1f lux: sun from the reading x%.4f the HDR's\n", file, lux, ratio);
        EXPECT_NEAR(ratio, 1.0, 0.10) << file;
        // Its colour is the clear-sky fallback's.
        const glm::dvec3 model = gusuku::calibratedClearSkySunRgb(sky->photo.diffuse_horizontal_rgb, h_photo, h_photo);
        EXPECT_NEAR(sun.r / sun.b, model.r / model.b, 1e-9 * model.r / model.b);
    }
    // A reading at or below the photo's own diffuse light is a shaded meter or a wrong exposure.
    const std::optional<PhotographedSharedSky> sky =
        photographSharedSky(kSunnySharedSkies[0], gusuku::testing::makeTemporaryDirectory("sky_photo_lux_low"));
    const double diffuse_lux = gusuku::kRadianceWhiteEfficacy * sky->photo.diffuse_horizontal_luminance;
    const std::string error = expectInputError(
        [&] { gusuku::bake::sunFromGlobalHorizontalLux(sky->photo, 0.5 * diffuse_lux, 10.0, 10.0, "site.json"); });
    EXPECT_EQ(error.rfind("site.json: /skies/sunny/global_horizontal_lux: ", 0), 0u) << error;
    EXPECT_NE(error.find("is not above the photos' own diffuse horizontal illuminance"), std::string::npos) << error;
}

// The estimators on a sky known in closed form: the CIE standard clear sky (its circumsolar indicatrix the
// aureole) with a sun disc whose DNI / DHI is ESRA's clear-sky ratio at its elevation, so the clear-sky fallback's
// premise holds exactly. Photographed so that the disc clips, both estimators recover the beam: the clear-sky model
// from the photo's diffuse light and the lux reading by energy. Tolerance 3 %: the disc's removal replaces the
// aureole's texels around it with its ring's mean, and the sky's darker texels are held by a few 8-bit codes.
/// The analytic clear sky below, photographed, with what the estimators should give.
struct AnalyticPhoto {
    SkyConfig config;
    gusuku::bake::PreparedSky photo;
    double beam = 0.0;                     ///< the spec's DNI (the sun's colour has luminance 1)
    double global_horizontal_lux = 0.0;    ///< what a lux meter under it reads
    double diffuse_horizontal = 0.0;       ///< the spec's DHI
};

AnalyticPhoto photographAnalyticClearSky(const std::string& dir) {
    const double elevation = 30.0;
    gusuku::bake::ClearSkySpec spec;
    const double e = glm::radians(elevation);
    spec.sun_direction = glm::dvec3(0.0, std::cos(e), std::sin(e));
    spec.direct_normal_to_diffuse_horizontal = gusuku::clearSkyDirectToDiffuseRatio(elevation);
    const gusuku::bake::ClearSkyModel model(spec);
    // The exposure that saturates at 1.5x the brightest channel of the sky 0.5 deg from the sun: the disc clips,
    // the aureole does not (the CIE sky's circumsolar brightening is broad, its luminance halving only from 0.5 to
    // 12 deg, so a clip taking part of it would leave a bright core wider than extractSunDisc takes for a sun).
    const double off = glm::radians(elevation + 0.5);
    const glm::dvec3 aureole = model.radiance(glm::dvec3(0.0, std::cos(off), std::sin(off)));
    const double saturating = 1.5 * std::max({aureole.r, aureole.g, aureole.b});
    const TestCamera camera{1.2 * 64.0 / (179.0 * saturating), 8.0, 100.0};
    writePhoto(dir + "/sky.png", gusuku::bake::renderClearSky(spec, 1024, 512, 0.0), camera);
    AnalyticPhoto analytic;
    analytic.config.path = dir + "/sky.png";
    analytic.config.photos = {SkyPhotoConfig{analytic.config.path, camera.ev100()}};
    analytic.photo = gusuku::bake::prepareSky(analytic.config);
    analytic.beam = model.directNormalIrradiance();
    analytic.global_horizontal_lux = gusuku::kRadianceWhiteEfficacy * model.globalHorizontalIrradiance();
    analytic.diffuse_horizontal = spec.diffuse_horizontal_irradiance;
    return analytic;
}

// The estimators on a sky known in closed form: the CIE standard clear sky (its circumsolar indicatrix the
// aureole) with a sun disc whose DNI / DHI is ESRA's clear-sky ratio at its elevation (30 deg), so the clear-sky
// fallback's premise holds exactly. Photographed so that the disc clips, both estimators recover the beam: the
// clear-sky model from the photo's diffuse light and the lux reading by energy. Tolerance 1 % (0.06 % measured):
// the disc's removal replaces the aureole's texels around it with its ring's mean, and the sky's darker texels are
// held by a few 8-bit codes.
TEST(SkyPhoto, ClippedSunOfAnAnalyticClearSkyIsRecoveredByBothEstimators) {
    const AnalyticPhoto analytic = photographAnalyticClearSky(gusuku::testing::makeTemporaryDirectory("sky_analytic"));
    const gusuku::bake::PreparedSky& photo = analytic.photo;
    ASSERT_TRUE(photo.disc.found);
    ASSERT_TRUE(photo.disc.clipped);
    const double h = elevationDeg(photo.disc);
    EXPECT_NEAR(h, 30.0, 0.3);
    const double from_model =
        gusuku::luminanceRec709(gusuku::calibratedClearSkySunRgb(photo.diffuse_horizontal_rgb, h, h));
    const double from_lux = gusuku::luminanceRec709(
        gusuku::bake::sunFromGlobalHorizontalLux(photo, analytic.global_horizontal_lux, h, h, "site.json"));
    std::printf("analytic clear sky, sun at %.2f deg, DNI %.3f, removed texels %d: clear-sky model x%.4f, lux "
                "x%.4f; diffuse horizontal photo / spec %.4f\n",
                h, analytic.beam, photo.disc.texel_count, from_model / analytic.beam, from_lux / analytic.beam,
                photo.diffuse_horizontal_luminance / analytic.diffuse_horizontal);
    EXPECT_NEAR(from_model / analytic.beam, 1.0, 0.01);
    EXPECT_NEAR(from_lux / analytic.beam, 1.0, 0.01);
}

// A sunny slot of a site whose photo clips the sun takes the lux reading when site.json gives one, and says how to
// do better when it does not.
TEST(SkyPhoto, SlotTakesTheLuxReadingForAClippedSun) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_analytic_slot");
    const AnalyticPhoto analytic = photographAnalyticClearSky(dir);
    gusuku::SiteConfig site = gusuku::testing::loadMiniSite(dir, 4);
    site.sunny_sky = analytic.config;
    const gusuku::BakeSlot& slot = site.bake.slots.front();
    ASSERT_EQ(slot.sky, gusuku::SlotSky::Sunny);
    const gusuku::bake::SlotLighting without = gusuku::bake::lightSlot(site, slot, analytic.photo, nullptr);
    ASSERT_TRUE(without.sun.present);
    EXPECT_EQ(without.sun_irradiance_source, "clear-sky model (map's sun disc is clipped)");
    ASSERT_EQ(without.warnings.size(), 1u);
    EXPECT_NE(without.warnings[0].find("/skies/sunny/global_horizontal_lux"), std::string::npos) << without.warnings[0];
    // The same clipped sun in an HDR map (site.json names no photos): a lux reading cannot scale the map's own
    // units, so the advice is to merge the map from a bracket that holds the disc.
    gusuku::SiteConfig map_site = site;
    map_site.sunny_sky.photos.clear();
    const gusuku::bake::SlotLighting from_map = gusuku::bake::lightSlot(map_site, slot, analytic.photo, nullptr);
    ASSERT_EQ(from_map.warnings.size(), 1u);
    EXPECT_NE(from_map.warnings[0].find("merge the map from a bracket whose darkest exposure shows the sun"),
              std::string::npos)
        << from_map.warnings[0];

    site.sunny_sky.global_horizontal_lux = analytic.global_horizontal_lux;
    const gusuku::bake::SlotLighting with = gusuku::bake::lightSlot(site, slot, analytic.photo, nullptr);
    EXPECT_EQ(with.sun_irradiance_source.rfind("global_horizontal_lux less the photos' diffuse light", 0), 0u);
    EXPECT_TRUE(with.warnings.empty());
    const double h = elevationDeg(analytic.photo.disc);
    const glm::dvec3 expected = gusuku::bake::sunFromGlobalHorizontalLux(
        analytic.photo, analytic.global_horizontal_lux, h, with.sun_position.apparent_elevation_deg, site.file);
    EXPECT_EQ(with.sun.irradiance_rgb, expected);

    // A shaded meter's reading (under the sky's own diffuse light) is refused, naming site.json and the field.
    site.sunny_sky.global_horizontal_lux = 0.9 * gusuku::kRadianceWhiteEfficacy * analytic.diffuse_horizontal;
    const std::string error = expectInputError([&] { gusuku::bake::lightSlot(site, slot, analytic.photo, nullptr); });
    EXPECT_EQ(error.rfind(site.file + ": /skies/sunny/global_horizontal_lux: ", 0), 0u) << error;
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

// Rewrites the one EXIF rational num/den (little-endian, as OpenImageIO writes JPEG EXIF) in the file at `path`.
void patchExifRational(const std::string& path, std::array<uint32_t, 2> from, std::array<uint32_t, 2> to) {
    std::string bytes = gusuku::readWholeFile(path);
    const auto little_endian = [](std::array<uint32_t, 2> rational) {
        std::string text;
        for (uint32_t value : rational)
            for (int shift = 0; shift < 32; shift += 8) text += char((value >> shift) & 0xFF);
        return text;
    };
    const std::string pattern = little_endian(from);
    const size_t found = bytes.find(pattern);
    ASSERT_NE(found, std::string::npos);
    ASSERT_EQ(bytes.find(pattern, found + 1), std::string::npos) << "the rational is not unique in the file";
    bytes.replace(found, pattern.size(), little_endian(to));
    gusuku::writeBytesAtomically(path, bytes.data(), bytes.size());
}

// A corrupt EXIF exposure (issue 39 item 6): an FNumber of 2.1e9 gives EV100 71.9, an ExposureTime of 4.7e-10 s
// EV100 37.0 (log2(N^2 / t) at ISO 100), both beyond site.json's own ev100 range, [-10, 30]. Each passed `check`
// and cost a whole bake; each is refused by the photo reader, naming the photo, the EXIF fields and their values.
// Inside the range a photo still reads: f/64 at 1/1000 s and ISO 1 is EV100 28.6.
TEST(SkyPhoto, ExifExposureOutsideSiteJsonsEv100RangeIsRefused) {
    ImageRGBA grey;
    grey.width = 64;
    grey.height = 32;
    grey.texels.assign(64 * 32 * 4, 1.0f);
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_exif_range");
    EXPECT_EQ(gusuku::kSkyPhotoEv100Range.minimum, -10.0);
    EXPECT_EQ(gusuku::kSkyPhotoEv100Range.maximum, 30.0);
    const TestCamera huge_f_number{1.0 / 1000.0, 2.1e9, 100.0};
    writePhoto(dir + "/f_number.jpg", grey, huge_f_number, WriteOptions{true, true, 0.0, 0, 0});
    const std::string f_message =
        expectInputError([&] { gusuku::skyPhotoEv100(dir + "/f_number.jpg", std::nullopt); });
    EXPECT_EQ(f_message.rfind(dir + "/f_number.jpg: EXIF exposure: ExposureTime 0.001 s, FNumber 2.1e+09, "
                                    "Exif:PhotographicSensitivity 100 give EV100 71.9",
                              0),
              0u)
        << f_message;
    EXPECT_NE(f_message.find("outside [-10, 30]"), std::string::npos) << f_message;
    EXPECT_EQ(f_message.find('\n'), std::string::npos);

    // OpenImageIO writes no ExposureTime under about 1e-4 s (its rationals' denominators are small), so 1/1000 s
    // is written and its rational patched to 1/2127659574 (4.7e-10 s) in the file.
    writePhoto(dir + "/time.jpg", grey, skyCamera(), WriteOptions{true, true, 0.0, 0, 0});
    patchExifRational(dir + "/time.jpg", {1, 1000}, {1, 2127659574});
    const std::string t_message = expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/time.jpg", {}}}); });
    EXPECT_EQ(t_message.rfind(dir + "/time.jpg: EXIF exposure: ExposureTime 4.7e-10 s, FNumber 8, ", 0), 0u)
        << t_message;
    EXPECT_NE(t_message.find("give EV100 37.0, outside [-10, 30]"), std::string::npos) << t_message;

    const TestCamera near_the_edge{1.0 / 1000.0, 64.0, 1.0};  // log2(64^2 x 1000) - log2(1 / 100) = 28.6
    writePhoto(dir + "/edge.jpg", grey, near_the_edge, WriteOptions{true, true, 0.0, 0, 0});
    EXPECT_NEAR(gusuku::skyPhotoEv100(dir + "/edge.jpg", std::nullopt), near_the_edge.ev100(), 1e-4);
    // site.json's ev100 and a given one are held to the same range.
    EXPECT_EQ(expectInputError([&] { gusuku::skyPhotoEv100(dir + "/edge.jpg", 30.5); }),
              dir + "/edge.jpg: ev100: 30.5 is outside [-10, 30]");
}

// `check` refuses the corrupt EXIF (it passed before, and the bake then traced every slot), and so does the bake's
// setup, before it writes anything into the output folder.
TEST(SkyPhoto, CheckAndBakeRefuseACorruptExifExposureBeforeTracing) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_exif_check");
    const std::string site_path = gusuku::testing::writeMiniSite(dir);
    writePhoto(dir + "/corrupt.jpg", gusuku::readRadianceMap(dir + "/sky_sunny.hdr"), TestCamera{1.0 / 1000.0, 2.1e9, 100.0},
               WriteOptions{true, true, 0.0, 0, 0});
    nlohmann::json site = nlohmann::json::parse(std::ifstream(site_path));
    site["skies"]["sunny"] = {{"path", "corrupt.jpg"}};
    std::ofstream(site_path, std::ios::trunc) << site.dump(2);
    const gusuku::testing::CommandResult check = gusuku::testing::runBakeCommand({"check", site_path}, dir);
    EXPECT_EQ(check.exit_code, 1) << check.stdout_text << check.stderr_text;
    EXPECT_NE(check.stderr_text.find("corrupt.jpg: EXIF exposure: "), std::string::npos) << check.stderr_text;
    EXPECT_NE(check.stderr_text.find("FNumber 2.1e+09"), std::string::npos) << check.stderr_text;
    const gusuku::testing::CommandResult bake =
        gusuku::testing::runBakeCommand({"bake", site_path, "-o", dir + "/bakeset", "--quiet"}, dir);
    EXPECT_EQ(bake.exit_code, 1) << bake.stdout_text << bake.stderr_text;
    EXPECT_NE(bake.stderr_text.find("corrupt.jpg: EXIF exposure: "), std::string::npos) << bake.stderr_text;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bakeset/manifest.json"));
}

// An exactly 2:1 photo above kMaxImageSide with an odd height (issue 39 item 8): 8194 x 4097 is downsampled by 2
// to 4098 x 2049, still 2:1 (it was refused as "4097 x 2049 is not the 2:1 of an equirectangular sky").
TEST(SkyPhoto, ATwoToOnePhotoAboveTheSideLimitStaysTwoToOne) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("sky_photo_odd_2to1");
    const int width = 8194, height = 4097;
    std::vector<unsigned char> codes(size_t(width) * size_t(height) * 3, 128);
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    const std::string path = dir + "/sky.png";
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(output && output->open(path, spec)) << OIIO::geterror();
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, codes.data()));
    ASSERT_TRUE(output->close());
    codes = {};
    gusuku::SkyPhotoSummary summary;
    const ImageRGBA sky = gusuku::readSkyPhotos({SkyPhotoConfig{path, 12.0}}, &summary);
    EXPECT_EQ(sky.width, 4098);
    EXPECT_EQ(sky.height, 2049);
    // Code 128 everywhere: srgbDecode(128 / 255) x 1.2 x 2^12 / 179 in every texel.
    const float expected = float(gusuku::srgbDecode(128.0 / 255.0) * 1.2 * std::exp2(12.0) / 179.0);
    EXPECT_NEAR(sky.texel(4097, 2048)[0], expected, 1e-3f * expected);
    // A file that is not 2:1 is named by its own size, not the downsample's.
    ImageRGBA grey;
    grey.width = 66;
    grey.height = 32;
    grey.texels.assign(66 * 32 * 4, 0.5f);
    writePhoto(dir + "/wide.png", grey, skyCamera());
    EXPECT_EQ(expectInputError([&] { gusuku::readSkyPhotos({SkyPhotoConfig{dir + "/wide.png", 12.0}}); }),
              dir + "/wide.png: size: 66 x 32 is not the 2:1 of an equirectangular sky");
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
