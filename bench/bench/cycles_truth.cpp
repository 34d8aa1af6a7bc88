// The bench's check against Cycles' renders (see cycles_truth.h).

#include "cycles_truth.h"

#include <cmath>
#include <filesystem>

#include "camera_response.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/maths/colour.h"
#include "gusuku/maths/input_error.h"

namespace gusuku::bench {
namespace {

ImageRGBA readSized(const std::string& path, uint32_t width, uint32_t height) {
    if (!std::filesystem::exists(path))
        throw InputError(path, "", "not found: --cycles-truth needs bench/cycles/cycles_view_render.py's renders");
    ImageRGBA image = readImage(path, ImageEncoding::Linear);
    if (image.width != int(width) || image.height != int(height))
        throw InputError(path, "", "is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                                       ", the bench's frames are " + std::to_string(width) + " x " +
                                       std::to_string(height));
    return image;
}

double luminanceAt(const ImageRGBA& image, size_t pixel) {
    const float* rgb = &image.texels[4 * pixel];
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

}  // namespace

CyclesView readCyclesView(const std::string& folder, const std::string& name, uint32_t width, uint32_t height) {
    CyclesView view;
    view.with_building = readSized(folder + "/" + name + "_building.exr", width, height);
    view.without_building = readSized(folder + "/" + name + "_site.exr", width, height);
    const ImageRGBA ids = readSized(folder + "/" + name + "_materials.exr", width, height);
    const std::string list_path = folder + "/materials.json";
    nlohmann::json list;
    try {
        list = nlohmann::json::parse(readWholeFile(list_path));
    } catch (const nlohmann::json::exception& error) {
        throw InputError(list_path, "", std::string("is not JSON: ") + error.what());
    }
    if (!list.is_array()) throw InputError(list_path, "", "is not a list of material names");
    for (const nlohmann::json& entry : list) {
        if (!entry.is_string()) throw InputError(list_path, "", "is not a list of material names");
        view.materials.push_back(entry.get<std::string>());
    }
    view.material_ids.resize(size_t(width) * height);
    for (size_t pixel = 0; pixel < view.material_ids.size(); ++pixel) {
        const long id = std::lround(ids.texels[4 * pixel]);
        if (id < 0 || id > long(view.materials.size()))
            throw InputError(folder + "/" + name + "_materials.exr", "",
                             "pixel " + std::to_string(pixel) + " names material " + std::to_string(id) + " of " +
                                 std::to_string(view.materials.size()));
        view.material_ids[pixel] = uint32_t(id);
    }
    return view;
}

FrameDifference frameDifference(const ImageRGBA& frame, const ImageRGBA& reference, float exposure,
                                const std::vector<uint8_t>& mask) {
    const CameraResponse neutral = benchCameraResponses()[0];
    FrameDifference difference;
    difference.mean_de00 = summariseError(applyCameraResponse(frame, exposure, neutral),
                                          applyCameraResponse(reference, exposure, neutral), mask)
                               .mean_de00;
    double absolute = 0.0, frame_sum = 0.0, reference_sum = 0.0;
    for (size_t pixel = 0; pixel < size_t(frame.width) * size_t(frame.height); ++pixel) {
        if (!mask.empty() && mask[pixel] == 0) continue;
        const double a = luminanceAt(frame, pixel), b = luminanceAt(reference, pixel);
        absolute += std::abs(a - b);
        frame_sum += a;
        reference_sum += b;
    }
    difference.relative_luminance = reference_sum > 0.0 ? absolute / reference_sum : 0.0;
    difference.luminance_bias = reference_sum > 0.0 ? frame_sum / reference_sum - 1.0 : 0.0;
    return difference;
}

std::vector<MaterialColour> materialColours(const CyclesView& cycles, const std::vector<uint8_t>& composite,
                                            float composite_exposure, const ImageRGBA& tracer) {
    const int width = tracer.width, height = tracer.height;
    std::vector<MaterialColour> colours(cycles.materials.size());
    for (size_t index = 0; index < colours.size(); ++index) colours[index].name = cycles.materials[index];
    for (int y = 1; y + 1 < height; ++y)
        for (int x = 1; x + 1 < width; ++x) {
            const size_t pixel = size_t(y) * width + x;
            const uint32_t id = cycles.material_ids[pixel];
            // Interior pixels only: an edge pixel mixes materials (or the ground) differently in each renderer.
            if (id == 0 || cycles.material_ids[pixel - 1] != id || cycles.material_ids[pixel + 1] != id ||
                cycles.material_ids[pixel - width] != id || cycles.material_ids[pixel + width] != id)
                continue;
            MaterialColour& colour = colours[id - 1];
            ++colour.pixels;
            for (int c = 0; c < 3; ++c) {
                colour.runtime[c] += srgbDecode(composite[4 * pixel + c] / 255.0) / composite_exposure;
                colour.tracer[c] += tracer.texels[4 * pixel + c];
                colour.cycles[c] += cycles.with_building.texels[4 * pixel + c];
            }
        }
    for (MaterialColour& colour : colours)
        if (colour.pixels > 0) {
            colour.runtime /= double(colour.pixels);
            colour.tracer /= double(colour.pixels);
            colour.cycles /= double(colour.pixels);
        }
    return colours;
}

namespace {

Json differenceJson(const FrameDifference& difference) {
    return {{"mean_de00", difference.mean_de00}, {"relative_luminance", difference.relative_luminance},
            {"luminance_bias", difference.luminance_bias}};
}

std::string rgbText(const glm::dvec3& rgb) {
    return "(" + fixed(rgb.r, 4) + ", " + fixed(rgb.g, 4) + ", " + fixed(rgb.b, 4) + ")";
}

// Per-channel ratio over red, the saturation the finding is about: G/R and B/R of a colour.
std::string chromaText(const glm::dvec3& rgb) {
    return rgb.r > 0.0 ? fixed(rgb.g / rgb.r, 3) + " / " + fixed(rgb.b / rgb.r, 3) : std::string("n/a");
}

}  // namespace

Json checkPoseAgainstCycles(Bench& bench, const NamedView& named, double utc_seconds, const ConditionFrames& frames,
                            const ImageRGBA& truth_seed2, const std::vector<uint8_t>& composite,
                            const std::vector<uint8_t>& mask, bool& agrees) {
    const Settings& settings = bench.settings;
    const uint32_t width = settings.accuracy_width, height = settings.accuracy_height;
    const CyclesView cycles = readCyclesView(*settings.cycles_truth, named.name, width, height);
    TracedFrameRequest camera_request = truthRequest(named.view, width, height, {utc_seconds, 0.0f},
                                                     settings.truth_samples, 2);
    camera_request.include_building = false;
    const ImageRGBA camera_seed2 = bench.renderer->render(camera_request).linear;
    // With the building over the bench's mask (the pixels it or its shadow changes); without it over every pixel.
    const FrameDifference truth_vs_cycles = frameDifference(frames.truth, cycles.with_building, frames.exposure, mask);
    const FrameDifference truth_noise = frameDifference(frames.truth, truth_seed2, frames.exposure, mask);
    const FrameDifference camera_vs_cycles =
        frameDifference(frames.camera, cycles.without_building, frames.exposure, {});
    const FrameDifference camera_noise = frameDifference(frames.camera, camera_seed2, frames.exposure, {});
    const bool held = truth_vs_cycles.mean_de00 <= truth_noise.mean_de00 &&
                      truth_vs_cycles.relative_luminance <= truth_noise.relative_luminance &&
                      camera_vs_cycles.mean_de00 <= camera_noise.mean_de00 &&
                      camera_vs_cycles.relative_luminance <= camera_noise.relative_luminance;
    agrees = agrees && held;
    bench.say("| " + named.name + " | with building (mask) | " + fixed(truth_vs_cycles.mean_de00) + " | " +
              fixed(truth_noise.mean_de00) + " | " + fixed(100.0 * truth_vs_cycles.relative_luminance, 1) + " % | " +
              fixed(100.0 * truth_noise.relative_luminance, 1) + " % | " +
              fixed(100.0 * truth_vs_cycles.luminance_bias, 2) + " % | " + (held ? "within" : "OVER") + " |");
    bench.say("| " + named.name + " | without (every pixel) | " + fixed(camera_vs_cycles.mean_de00) + " | " +
              fixed(camera_noise.mean_de00) + " | " + fixed(100.0 * camera_vs_cycles.relative_luminance, 1) +
              " % | " + fixed(100.0 * camera_noise.relative_luminance, 1) + " % | " +
              fixed(100.0 * camera_vs_cycles.luminance_bias, 2) + " % | " + (held ? "within" : "OVER") + " |");
    Json materials = Json::array();
    for (const MaterialColour& colour : materialColours(cycles, composite, frames.exposure, frames.truth)) {
        if (colour.pixels == 0) continue;
        bench.say("| " + named.name + " | material " + colour.name + " (" + std::to_string(colour.pixels) +
                  " px) | runtime " + rgbText(colour.runtime) + " G/R, B/R " + chromaText(colour.runtime) +
                  " | tracer " + rgbText(colour.tracer) + " " + chromaText(colour.tracer) + " | Cycles " +
                  rgbText(colour.cycles) + " " + chromaText(colour.cycles) + " | | | |");
        materials.push_back({{"name", colour.name}, {"pixels", colour.pixels},
                             {"runtime_rgb", {colour.runtime.r, colour.runtime.g, colour.runtime.b}},
                             {"tracer_rgb", {colour.tracer.r, colour.tracer.g, colour.tracer.b}},
                             {"cycles_rgb", {colour.cycles.r, colour.cycles.g, colour.cycles.b}}});
    }
    return {{"folder", *settings.cycles_truth},
            {"with_building_mask", {{"tracer_vs_cycles", differenceJson(truth_vs_cycles)},
                                    {"tracer_seed_to_seed", differenceJson(truth_noise)}}},
            {"without_building_whole", {{"tracer_vs_cycles", differenceJson(camera_vs_cycles)},
                                        {"tracer_seed_to_seed", differenceJson(camera_noise)}}},
            {"within_noise", held},
            {"materials_linear_rgb", materials}};
}

}  // namespace gusuku::bench
