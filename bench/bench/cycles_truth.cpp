// The bench's check against Cycles' renders (see cycles_truth.h).

#include "cycles_truth.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "camera_response.h"
#include "gusuku/assets/atomic_file.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"

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
    for (int half = 0; half < 2; ++half) {
        const std::string suffix = half == 0 ? ".exr" : "_b.exr";
        view.with_building[half] = readSized(folder + "/" + name + "_building" + suffix, width, height);
        view.without_building[half] = readSized(folder + "/" + name + "_site" + suffix, width, height);
    }
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

ImageRGBA meanOf(const ImageRGBA& a, const ImageRGBA& b) {
    ImageRGBA mean = a;
    for (size_t i = 0; i < mean.texels.size(); ++i) mean.texels[i] = 0.5f * (a.texels[i] + b.texels[i]);
    return mean;
}

FrameDifference frameDifference(const ImageRGBA& frame, const ImageRGBA& reference, float exposure,
                                const std::vector<uint8_t>& mask) {
    const CameraResponse neutral = benchCameraResponses()[0];
    const std::vector<double> de00 = ciede2000PerPixel(applyCameraResponse(frame, exposure, neutral),
                                                       applyCameraResponse(reference, exposure, neutral));
    double de00_sum = 0.0, de00_squares = 0.0, luminance_squares = 0.0, frame_sum = 0.0, reference_sum = 0.0;
    size_t count = 0;
    for (size_t pixel = 0; pixel < de00.size(); ++pixel) {
        if (!mask.empty() && mask[pixel] == 0) continue;
        const double a = luminanceAt(frame, pixel), b = luminanceAt(reference, pixel);
        de00_sum += de00[pixel];
        de00_squares += de00[pixel] * de00[pixel];
        luminance_squares += (a - b) * (a - b);
        frame_sum += a;
        reference_sum += b;
        ++count;
    }
    FrameDifference difference;
    if (count == 0 || !(reference_sum > 0.0)) return difference;
    difference.pixels = count;
    difference.mean_de00 = de00_sum / double(count);
    difference.rms_de00 = std::sqrt(de00_squares / double(count));
    difference.rms_relative_luminance = std::sqrt(luminance_squares / double(count)) / (reference_sum / double(count));
    difference.luminance_bias = frame_sum / reference_sum - 1.0;
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
                colour.cycles[c] += 0.5 * (cycles.with_building[0].texels[4 * pixel + c] +
                                           cycles.with_building[1].texels[4 * pixel + c]);
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
    return {{"mean_de00", difference.mean_de00}, {"rms_de00", difference.rms_de00},
            {"rms_relative_luminance", difference.rms_relative_luminance},
            {"luminance_bias", difference.luminance_bias}};
}

// One frame (with or without the building) of one pose: the tracer (two seeds) against Cycles (two seeds).
// Cycles' estimate is the mean of its two renders; their difference has 4 times its mean square, which is taken
// out of the tracer's difference from it (independent noises add in squares). Without a bias, what is left is
// the tracer's own noise, 1/sqrt(2) of its seed-to-seed difference; a bias as large as that noise makes the two
// equal, so the check is: left-over difference at most the seed-to-seed difference.
struct FrameCheck {
    FrameDifference tracer_vs_cycles, seed_to_seed, cycles_half_to_half;
    double rms_de00_noise_out = 0.0, rms_relative_luminance_noise_out = 0.0;
    bool held = false;
};

double withoutNoise(double measured, double reference_halves) {
    return std::sqrt(std::max(measured * measured - reference_halves * reference_halves / 4.0, 0.0));
}

FrameCheck checkFrame(const ImageRGBA& tracer, const ImageRGBA& tracer_seed2, const ImageRGBA (&cycles)[2],
                      float exposure, const std::vector<uint8_t>& mask) {
    FrameCheck check;
    check.tracer_vs_cycles = frameDifference(tracer, meanOf(cycles[0], cycles[1]), exposure, mask);
    check.seed_to_seed = frameDifference(tracer, tracer_seed2, exposure, mask);
    check.cycles_half_to_half = frameDifference(cycles[0], cycles[1], exposure, mask);
    check.rms_de00_noise_out = withoutNoise(check.tracer_vs_cycles.rms_de00, check.cycles_half_to_half.rms_de00);
    check.rms_relative_luminance_noise_out = withoutNoise(check.tracer_vs_cycles.rms_relative_luminance,
                                                          check.cycles_half_to_half.rms_relative_luminance);
    check.held = check.rms_de00_noise_out <= check.seed_to_seed.rms_de00 &&
                 check.rms_relative_luminance_noise_out <= check.seed_to_seed.rms_relative_luminance;
    return check;
}

Json frameCheckJson(const FrameCheck& check) {
    return {{"tracer_vs_cycles", differenceJson(check.tracer_vs_cycles)},
            {"tracer_seed_to_seed", differenceJson(check.seed_to_seed)},
            {"cycles_half_to_half", differenceJson(check.cycles_half_to_half)},
            {"tracer_vs_cycles_rms_de00_cycles_noise_out", check.rms_de00_noise_out},
            {"tracer_vs_cycles_rms_relative_luminance_cycles_noise_out", check.rms_relative_luminance_noise_out},
            {"within_noise", check.held}};
}

std::string frameCheckRow(const std::string& pose, const std::string& frame, const FrameCheck& check) {
    return "| " + pose + " | " + frame + " | " + fixed(check.tracer_vs_cycles.mean_de00) + " / " +
           fixed(check.seed_to_seed.mean_de00) + " / " + fixed(check.cycles_half_to_half.mean_de00) + " | " +
           fixed(check.rms_de00_noise_out) + " / " + fixed(check.seed_to_seed.rms_de00) + " | " +
           fixed(100.0 * check.rms_relative_luminance_noise_out, 2) + " / " +
           fixed(100.0 * check.seed_to_seed.rms_relative_luminance, 2) + " % | " +
           fixed(100.0 * check.tracer_vs_cycles.luminance_bias, 2) + " % | " + (check.held ? "within" : "OVER") + " |";
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
    const FrameCheck with_building = checkFrame(frames.truth, truth_seed2, cycles.with_building, frames.exposure, mask);
    const FrameCheck without_building =
        checkFrame(frames.camera, camera_seed2, cycles.without_building, frames.exposure, {});
    agrees = agrees && with_building.held && without_building.held;
    bench.say(frameCheckRow(named.name, "with building (" + std::to_string(with_building.seed_to_seed.pixels) +
                                            " mask px)", with_building));
    bench.say(frameCheckRow(named.name, "without (every px)", without_building));
    Json materials = Json::array();
    for (const MaterialColour& colour : materialColours(cycles, composite, frames.exposure, frames.truth)) {
        if (colour.pixels == 0) continue;
        bench.say("| " + named.name + " | material " + colour.name + " (" + std::to_string(colour.pixels) +
                  " px) | runtime " + rgbText(colour.runtime) + " G/R, B/R " + chromaText(colour.runtime) +
                  " | tracer " + rgbText(colour.tracer) + " " + chromaText(colour.tracer) + " | Cycles " +
                  rgbText(colour.cycles) + " " + chromaText(colour.cycles) + " | | |");
        materials.push_back({{"name", colour.name}, {"pixels", colour.pixels},
                             {"runtime_rgb", {colour.runtime.r, colour.runtime.g, colour.runtime.b}},
                             {"tracer_rgb", {colour.tracer.r, colour.tracer.g, colour.tracer.b}},
                             {"cycles_rgb", {colour.cycles.r, colour.cycles.g, colour.cycles.b}}});
    }
    return {{"folder", *settings.cycles_truth}, {"with_building_mask", frameCheckJson(with_building)},
            {"without_building_whole", frameCheckJson(without_building)},
            {"within_noise", with_building.held && without_building.held}, {"materials_linear_rgb", materials}};
}

}  // namespace gusuku::bench
