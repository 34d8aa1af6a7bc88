// gusuku-texture-formats: what the runtime pack's ASTC 6x6 sRGB base-colour textures (RuntimeOptions::
// texture_compression_astc_ldr) cost on a bake set: their GPU memory and pack bytes against RGBA8 with mips, each
// level's decoding error against the RGBA8 chain the runtime makes, and the composite's CIEDE2000 against the
// RGBA8 textures' composite from each view.
//
// Usage: gusuku-texture-formats BAKESET [--size WxH] [--view E,N,U:E,N,U]... [--fov DEG] [--time ISO8601]
// Lavapipe cannot sample ASTC, so the ASTC composite draws each texture's level 0 decoded by astcenc as RGBA8,
// with the chain the runtime makes from it: level 0 is what a device shows close up; farther levels are the
// per-level table's (the blocks of a level decode within a few codes of the RGBA8 chain's, printed here). The
// camera frame is a flat mid grey (the composite passes it through where the building changes nothing); the
// exposure puts a sunlit face of albedo 0.5 at display value 0.6; no colour match; the first sunny slot's instant
// unless --time. "region" is the pixels where the RGBA8 composite differs from the camera frame.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/ktx2.h"
#include "gusuku/maths/srgb_mip_chain.h"
#include "gusuku/maths/texture_coverage.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/runtime/runtime.h"
#include "format_comparison.h"
#include "gusuku_bake/astc_texture.h"
#include "image_metrics.h"

using namespace gusuku;

namespace {

struct View {
    glm::dvec3 position, look_at;
};

struct Request {
    std::string folder;
    uint32_t width = 640, height = 360;
    std::vector<View> views;
    double fov_deg = 60.0;
    std::string utc;
};

Request readRequest(int argc, char** argv) {
    Request request;
    auto read_option = [&](const std::string& option, const char* value) {
        if (option == "--size") {
            bench_common::parseFrameSizeOption(value, request.width, request.height);
        } else if (option == "--view") {
            const std::string text = value;
            const size_t colon = text.find(':');
            if (colon == std::string::npos) throw std::invalid_argument("--view: '" + text + "' is not E,N,U:E,N,U");
            request.views.push_back({bench_common::parsePointOption(option, text.substr(0, colon)),
                                     bench_common::parsePointOption(option, text.substr(colon + 1))});
        } else if (option == "--fov") {
            request.fov_deg = std::atof(value);
        } else if (option == "--time") {
            request.utc = value;
        } else {
            return false;
        }
        return true;
    };
    request.folder = bench_common::readFolderAndOptions(
        argc, argv, "usage: gusuku-texture-formats BAKESET [--size WxH] ...", read_option);
    return request;
}

// Without --view: south-east of the building's bounds, looking at their centre (format_comparison.h).
void placeDefaultView(const BakeSetData& bake_set, Request& request) {
    if (!request.views.empty()) return;
    const bench_common::BuildingView view = bench_common::southEastViewOf(bake_set);
    request.views.push_back({view.position, view.look_at});
}

std::vector<uint8_t> composite(const BakeSetData& bake_set, const Request& request, const View& view,
                               const std::vector<uint8_t>& camera) {
    RuntimeOptions options;
    options.frame_width = request.width;
    options.frame_height = request.height;
    std::unique_ptr<Runtime> runtime = Runtime::openHeadless(bake_set, options);
    size_t slot = 0;
    while (slot < bake_set.manifest.slots.size() && bake_set.manifest.slots[slot].sky != BakeSetSky::Sunny) ++slot;
    if (slot == bake_set.manifest.slots.size()) throw std::invalid_argument(request.folder + ": no sunny slot");
    const BakeSetSlot& info = bake_set.manifest.slots[slot];
    FrameInput frame;
    frame.camera_rgba8 = camera.data();
    frame.intrinsics = CameraIntrinsics::fromFieldOfView(request.width, request.height, request.fov_deg);
    frame.pose = CameraPose::lookingAt(view.position, view.look_at);
    frame.utc_unix_seconds = parseIso8601Utc(request.utc.empty() ? info.utc : request.utc);
    frame.exposure =
        bench_common::sunlitGreyExposure(bake_set.slots[slot].building, luminanceRec709(info.sun.irradiance_rgb));
    frame.colour_match = ColourMatch::kOff;
    std::vector<uint8_t> pixels(camera.size());
    for (int warm_up = 0; warm_up < 2; ++warm_up) runtime->renderFrame(frame, pixels.data());
    return pixels;
}

// Mean |code| over RGB; for a masked texture (coverage_alpha in (0, 1]) over the texels the reference keeps
// (alpha at or above it), since a discarded texel's colour is never seen.
double meanCodeError(const std::vector<uint8_t>& decoded, const std::vector<uint8_t>& reference, float coverage_alpha) {
    double sum = 0.0, count = 0.0;
    for (size_t texel = 0; texel < reference.size() / 4; ++texel) {
        if (keepsAlphaCoverage(coverage_alpha) && reference[texel * 4 + 3] / 255.0f < coverage_alpha) continue;
        for (int channel = 0; channel < 3; ++channel)
            sum += std::abs(int(decoded[texel * 4 + channel]) - int(reference[texel * 4 + channel]));
        count += 3.0;
    }
    return count > 0.0 ? sum / count : 0.0;
}

// Per texture: sizes, and each level's blocks decoded against the RGBA8 chain (mean |code| over RGB).
void reportTextures(const BakeSetData& exr, const BakeSetData& pack) {
    const std::vector<float> coverage_alpha = textureCoverageAlphas(exr.building);
    uint64_t rgba8_bytes = 0, astc_bytes = 0;
    for (size_t index = 0; index < exr.building.textures.size(); ++index) {
        const BakeSetTexture& texture = exr.building.textures[index];
        const std::vector<std::vector<uint8_t>>& blocks = pack.building.textures[index].astc6x6_levels;
        const uint32_t width = uint32_t(texture.width), height = uint32_t(texture.height);
        const uint32_t levels = ktx2FullLevelCount(width, height);
        const std::vector<std::vector<uint8_t>> chain =
            boxFilteredSrgbMipLevels(texture.rgba8.data(), width, height, levels, coverage_alpha[index]);
        std::printf("texture %zu: %ux%u%s, level error (mean |code|, RGB of the texels drawn):", index, width, height,
                    keepsAlphaCoverage(coverage_alpha[index]) ? " (alpha-masked)" : "");
        for (uint32_t level = 0; level < levels; ++level) {
            const uint32_t w = std::max(1u, width >> level), h = std::max(1u, height >> level);
            rgba8_bytes += uint64_t(w) * h * 4;
            astc_bytes += blocks[level].size();
            if (level > 4 && w < 64 && h < 64) continue;
            const std::vector<uint8_t>& expected = level == 0 ? texture.rgba8 : chain[level - 1];
            const std::vector<uint8_t> decoded = bake::decodeAstcTextureLevel(blocks[level], w, h);
            std::printf(" L%u %.2f", level, meanCodeError(decoded, expected, coverage_alpha[index]));
            if (keepsAlphaCoverage(coverage_alpha[index]))  // the share of texels kept, RGBA8 chain / blocks
                std::printf(" (kept %.3f / %.3f)", alphaCoverage(expected.data(), size_t(w) * h, coverage_alpha[index]),
                            alphaCoverage(decoded.data(), size_t(w) * h, coverage_alpha[index]));
        }
        std::printf("\n");
    }
    std::printf("textures on the GPU with mips: RGBA8 %.2f MiB, ASTC 6x6 %.2f MiB (%.1fx less)\n",
                double(rgba8_bytes) / 1048576.0, double(astc_bytes) / 1048576.0,
                double(rgba8_bytes) / double(std::max<uint64_t>(astc_bytes, 1)));
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Request request = readRequest(argc, argv);
        const BakeSetData bake_set = loadBakeSet(request.folder);
        if (!std::filesystem::exists(request.folder + "/pack/manifest.json"))
            throw std::invalid_argument(request.folder + ": has no runtime pack (gusuku-bake pack " + request.folder + ")");
        const BakeSetData pack = loadRuntimePack(request.folder);
        for (const BakeSetTexture& texture : pack.building.textures)
            if (texture.astc6x6_levels.empty())
                throw std::invalid_argument(request.folder + "/pack: has no ASTC textures (written before them: "
                                            "gusuku-bake pack " + request.folder + " adds them)");
        placeDefaultView(bake_set, request);
        reportTextures(bake_set, pack);
        BakeSetData decoded = bake_set;
        for (size_t index = 0; index < decoded.building.textures.size(); ++index) {
            BakeSetTexture& texture = decoded.building.textures[index];
            texture.rgba8 = bake::decodeAstcTextureLevel(pack.building.textures[index].astc6x6_levels[0],
                                                         uint32_t(texture.width), uint32_t(texture.height));
        }
        const std::vector<uint8_t> camera(size_t(request.width) * request.height * 4, 128);
        for (const View& view : request.views) {
            const std::vector<uint8_t> reference = composite(bake_set, request, view, camera);
            const std::vector<uint8_t> astc = composite(decoded, request, view, camera);
            const std::vector<uint8_t> region = bench_common::changedRegion(reference, camera);
            const bench::ErrorSummary summary = bench::summariseError(astc, reference, region);
            std::printf("view %.1f,%.1f,%.1f -> %.1f,%.1f,%.1f, %ux%u: ASTC 6x6 vs RGBA8 dE00 region mean %.4f p95 "
                        "%.4f (%zu px)\n",
                        view.position.x, view.position.y, view.position.z, view.look_at.x, view.look_at.y,
                        view.look_at.z, request.width, request.height, summary.mean_de00, summary.p95_de00,
                        summary.pixel_count);
        }
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-texture-formats: %s\n", error.what());
        return 1;
    }
}
