// gusuku-lightmap-formats: what each runtime lightmap format (RuntimeOptions::lightmap_format) costs on a bake
// set: the lightmaps' GPU memory, and the composite's CIEDE2000 against the float32 lightmaps' composite, per slot.
//
// Usage: gusuku-lightmap-formats BAKESET [--size WxH] [--position E,N,U --look-at E,N,U] [--fov DEG]
//                                [--astc-quality Q[,Q...]]
// The camera frame is a flat mid grey (the composite passes it through where the building changes nothing, so
// only the building's and its ground effect's pixels can differ); the exposure puts a sunlit face of albedo 0.5
// at display value 0.6; no colour match (exposure known). Without --position the camera stands south-east of the
// building's bounds, 1.8 radii out and 0.6 up, looking at their centre. Each slot is drawn at its own instant
// (overcast slots at the first sunny slot's, with cloud cover 1). "region" is the pixels where the float32
// composite differs from the camera frame; "frame" is every pixel. The formats are the lightmap rows of
// gusuku/formats/format_table.h. ASTC HDR (each row of codec kAstcHdr), which lavapipe cannot sample: the runtime
// pack's blocks (BAKESET/pack/building_<slot><row's pack_suffix>.ktx2, read by loadRuntimePack), decoded on the CPU
// by astcenc and drawn as float32, which is what a device that samples ASTC HDR shows at its bytes a texel; and
// with --astc-quality, the EXR lightmaps encoded at each astcenc quality given (timed), decoded and drawn alike.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/formats/format_table.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku/pack_loader/runtime_pack.h"
#include "gusuku/runtime/runtime.h"
#include "format_comparison.h"
#include "gusuku_bake/astc_lightmap.h"
#include "image_metrics.h"

using namespace gusuku;

namespace {

struct Request {
    std::string folder;
    uint32_t width = 480, height = 270;
    bool placed = false;
    glm::dvec3 position{0.0}, look_at{0.0};
    double fov_deg = 55.0;
    std::vector<float> astc_qualities;  // astcenc qualities to encode the EXR lightmaps at (none: the pack's only)
};

Request readRequest(int argc, char** argv) {
    Request request;
    auto read_option = [&](const std::string& option, const char* value) {
        if (option == "--size") {
            bench_common::parseFrameSizeOption(value, request.width, request.height);
        } else if (option == "--position") {
            request.position = bench_common::parsePointOption(option, value);
            request.placed = true;
        } else if (option == "--look-at") {
            request.look_at = bench_common::parsePointOption(option, value);
        } else if (option == "--fov") {
            request.fov_deg = std::atof(value);
        } else if (option == "--astc-quality") {
            for (const char* at = value; *at != '\0';) {
                char* end = nullptr;
                const float quality = std::strtof(at, &end);
                if (end == at || !(quality >= 0.0f && quality <= 100.0f))
                    throw std::invalid_argument(std::string("--astc-quality: '") + value + "' is not Q[,Q...] in [0, 100]");
                request.astc_qualities.push_back(quality);
                at = *end == ',' ? end + 1 : end;
            }
        } else {
            return false;
        }
        return true;
    };
    request.folder = bench_common::readFolderAndOptions(
        argc, argv, "usage: gusuku-lightmap-formats BAKESET [--size WxH] ...", read_option);
    return request;
}

void placeCamera(const BakeSetData& bake_set, Request& request) {
    if (request.placed) return;
    const bench_common::BuildingView view = bench_common::southEastViewOf(bake_set);
    request.look_at = view.look_at;
    request.position = view.position;
}

struct FormatRun {
    std::string name;
    const formats::FormatRow* row;  // the format the lightmaps are held in on a device that samples it
    uint64_t device_bytes = 0;
    std::vector<std::vector<uint8_t>> composites;  // one per slot
};

// Each slot drawn with the lightmaps in `format`, at its own instant (overcast slots at sunny_utc, cloud cover 1).
void drawSlots(const BakeSetData& bake_set, LightmapFormat format, const Request& request, const std::string& sunny_utc,
               const std::vector<uint8_t>& camera, FormatRun& run) {
    RuntimeOptions options;
    options.frame_width = request.width;
    options.frame_height = request.height;
    options.lightmap_format = format;
    std::unique_ptr<Runtime> runtime = Runtime::openHeadless(bake_set, options);
    run.device_bytes = runtime->deviceMemoryBytes();
    for (size_t slot = 0; slot < bake_set.slots.size(); ++slot) {
        const BakeSetSlot& info = bake_set.manifest.slots[slot];
        const bool sunny = info.sky == BakeSetSky::Sunny;
        const double sun = sunny ? luminanceRec709(info.sun.irradiance_rgb) : 0.0;
        FrameInput frame;
        frame.camera_rgba8 = camera.data();
        frame.intrinsics = CameraIntrinsics::fromFieldOfView(request.width, request.height, request.fov_deg);
        frame.pose = CameraPose::lookingAt(request.position, request.look_at);
        frame.utc_unix_seconds = parseIso8601Utc(sunny ? info.utc : sunny_utc);
        frame.weather.cloud_cover = sunny ? 0.0f : 1.0f;
        frame.exposure = bench_common::sunlitGreyExposure(bake_set.slots[slot].building, sun);
        frame.colour_match = ColourMatch::kOff;
        std::vector<uint8_t> composite(camera.size());
        for (int warm_up = 0; warm_up < 2; ++warm_up) runtime->renderFrame(frame, composite.data());
        run.composites.push_back(composite);
    }
}

void report(const BakeSetData& bake_set, const Request& request, const std::vector<uint8_t>& camera,
            const std::vector<FormatRun>& runs) {
    const uint32_t side = uint32_t(bake_set.manifest.building.lightmap_resolution);
    std::printf("bake set: %s, %zu slots, lightmap %d^2, camera %.1f,%.1f,%.1f -> %.1f,%.1f,%.1f, %ux%u\n",
                request.folder.c_str(), bake_set.slots.size(), bake_set.manifest.building.lightmap_resolution,
                request.position.x, request.position.y, request.position.z, request.look_at.x, request.look_at.y,
                request.look_at.z, request.width, request.height);
    for (const FormatRun& run : runs) {
        const uint64_t lightmap_bytes = formats::levelBytes(*run.row, side, side) * bake_set.slots.size();
        std::printf("%-20s lightmaps %8.2f MiB on the GPU (runtime total %.2f MiB; ASTC: drawn from decoded floats)\n",
                    run.name.c_str(), double(lightmap_bytes) / 1048576.0, double(run.device_bytes) / 1048576.0);
        for (size_t slot = 0; slot < bake_set.slots.size(); ++slot) {
            const std::vector<uint8_t>& reference = runs[0].composites[slot];
            const std::vector<uint8_t> region = bench_common::changedRegion(reference, camera);
            const bench::ErrorSummary in_region = bench::summariseError(run.composites[slot], reference, region);
            const bench::ErrorSummary whole = bench::summariseError(run.composites[slot], reference);
            std::printf("  %-14s dE00 vs rgba32f: region mean %.4f p95 %.4f (%zu px), frame mean %.4f\n",
                        bake_set.manifest.slots[slot].name.c_str(), in_region.mean_de00, in_region.p95_de00,
                        in_region.pixel_count, whole.mean_de00);
        }
    }
}

// The bake set with each slot's lightmap RGB replaced by its ASTC blocks (of `row`) decoded (times `scale`),
// alpha kept.
BakeSetData withDecodedAstc(const BakeSetData& bake_set, const formats::FormatRow& row,
                            const std::vector<std::vector<uint8_t>>& blocks, float scale) {
    BakeSetData decoded = bake_set;
    for (size_t slot = 0; slot < decoded.slots.size(); ++slot) {
        BakeSetImage& lightmap = decoded.slots[slot].building;
        const BakeSetImage texels =
            bake::decodeAstcLightmap(blocks[slot], lightmap.width, lightmap.height, row.block_side);
        for (size_t index = 0; index < texels.rgba.size(); ++index)
            if (index % 4 != 3) lightmap.rgba[index] = texels.rgba[index] * scale;
    }
    return decoded;
}

// Each ASTC HDR row of the format table: the pack's blocks when it has them, and the EXR lightmaps encoded at each
// --astc-quality.
void addAstcRuns(const BakeSetData& bake_set, const Request& request, const std::string& sunny_utc,
                 const std::vector<uint8_t>& camera, std::vector<FormatRun>& runs) {
    const bool has_pack = std::filesystem::exists(request.folder + "/pack/manifest.json");
    const BakeSetData pack = has_pack ? loadRuntimePack(request.folder) : BakeSetData{};
    for (const formats::FormatRow& row : formats::kFormatRows) {
        if (row.family != formats::FormatFamily::kLightmap || row.codec != formats::TexelCodec::kAstcHdr) continue;
        if (has_pack) {
            std::vector<std::vector<uint8_t>> blocks;
            for (const BakeSetSlotImages& slot : pack.slots)
                if (slot.building_blocks.count(row.vk_format) != 0) blocks.push_back(slot.building_blocks.at(row.vk_format));
            if (!blocks.empty() && blocks.size() == pack.slots.size()) {
                runs.push_back({std::string(row.name) + " (pack)", &row});
                drawSlots(withDecodedAstc(bake_set, row, blocks, pack.building_blocks_scale), LightmapFormat::kRgba32f,
                          request, sunny_utc, camera, runs.back());
            } else {
                std::printf("the pack has no %s lightmaps (written before them: gusuku-bake pack %s adds them)\n",
                            row.name, request.folder.c_str());
            }
        }
        for (const float quality : request.astc_qualities) {
            std::vector<std::vector<uint8_t>> blocks;
            const auto start = std::chrono::steady_clock::now();
            for (const BakeSetSlotImages& slot : bake_set.slots)
                blocks.push_back(bake::encodeAstcLightmap(slot.building, 1.0f, quality, 0, row.block_side));
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            char name[64];
            std::snprintf(name, sizeof name, "%s q%g", row.name, double(quality));
            std::printf("%s: %zu slots encoded in %.2f s (%u threads)\n", name, blocks.size(), seconds,
                        std::max(1u, std::thread::hardware_concurrency()));
            runs.push_back({name, &row});
            drawSlots(withDecodedAstc(bake_set, row, blocks, 1.0f), LightmapFormat::kRgba32f, request, sunny_utc, camera,
                      runs.back());
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        Request request = readRequest(argc, argv);
        const BakeSetData bake_set = loadBakeSet(request.folder);
        placeCamera(bake_set, request);
        std::string sunny_utc;
        for (const BakeSetSlot& slot : bake_set.manifest.slots)
            if (slot.sky == BakeSetSky::Sunny && sunny_utc.empty()) sunny_utc = slot.utc;
        if (sunny_utc.empty()) throw std::invalid_argument(request.folder + ": no sunny slot to take an instant from");
        const std::vector<uint8_t> camera(size_t(request.width) * request.height * 4, 128);
        // The texel formats the runtime makes itself, the reference (rgba32f) first: every run is measured against
        // it; then the others in the table's order.
        std::vector<FormatRun> runs;
        const formats::FormatRow* reference = formats::findLightmapFormat(int(LightmapFormat::kRgba32f));
        runs.push_back({reference->name, reference});
        drawSlots(bake_set, LightmapFormat::kRgba32f, request, sunny_utc, camera, runs.back());
        for (const formats::FormatRow& row : formats::kFormatRows) {
            if (row.family != formats::FormatFamily::kLightmap || formats::isBlockCodec(row.codec) || &row == reference)
                continue;
            runs.push_back({row.name, &row});
            drawSlots(bake_set, LightmapFormat(row.c_enum), request, sunny_utc, camera, runs.back());
        }
        addAstcRuns(bake_set, request, sunny_utc, camera, runs);
        report(bake_set, request, camera, runs);
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "gusuku-lightmap-formats: %s\n", error.what());
        return 1;
    }
}
