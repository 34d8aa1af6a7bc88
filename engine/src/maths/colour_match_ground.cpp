// CPU reference of the runtime's ground colour match (gusuku/maths/colour_match.h, mode kGround): the ground cell
// under each sampled pixel, its predicted radiance, the trimmed von Kries gain and its smoothing, in double, with
// the same steps as shaders/runtime/colour_statistics_ground.comp and its reduce.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "gusuku/formats/bakeset_data.h"
#include "gusuku/maths/colour_match.h"

namespace gusuku {

namespace {

double luminance(const glm::dvec3& rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

// The cell whose square holds (x, y), or -1 outside the grid (column 0 west, row 0 north).
long cellAt(const GroundGrid& grid, double x, double y) {
    const double column = std::floor((x - grid.origin_enu_m.x) / grid.cell_m);
    const double row_from_south = std::floor((y - grid.origin_enu_m.y) / grid.cell_m);
    if (!(column >= 0.0 && column < double(grid.columns) && row_from_south >= 0.0 &&
          row_from_south < double(grid.rows)))
        return -1;
    const long row = long(grid.rows) - 1 - long(row_from_south);
    return row * long(grid.columns) + long(column);
}

}  // namespace

std::optional<GroundMatchScene> groundMatchSceneFrom(const BakeSetData& bake_set) {
    const GroundGrid& grid = bake_set.manifest.ground_grid.grid;
    const size_t cells = grid.cellCount();
    const size_t floats = cells * 4;
    if (cells == 0 || bake_set.ground_albedo.rgba.size() != floats || bake_set.ground_geometry.rgba.size() != floats)
        return std::nullopt;
    GroundMatchScene scene;
    scene.grid = grid;
    scene.cells.resize(cells);
    double height_sum = 0.0;
    size_t ground_cells = 0;
    const std::vector<float>& albedo = bake_set.ground_albedo.rgba;
    const std::vector<float>& geometry = bake_set.ground_geometry.rgba;
    const bool any_slot = !bake_set.slots.empty();
    for (size_t i = 0; i < cells; ++i) {
        GroundMatchCell& cell = scene.cells[i];
        cell.albedo = {albedo[4 * i], albedo[4 * i + 1], albedo[4 * i + 2]};
        cell.normal = {geometry[4 * i], geometry[4 * i + 1], geometry[4 * i + 2]};
        cell.height_m = geometry[4 * i + 3];
        // Ground needs both files to say so: albedo alpha and the irradiance's presence.
        const bool present = !any_slot || bake_set.slots[0].ground_without.rgba.size() != floats ||
                             bake_set.slots[0].ground_without.rgba[4 * i + 3] > 0.5f;
        cell.ground = albedo[4 * i + 3] > 0.5f && present;
        if (cell.ground) {
            height_sum += cell.height_m;
            ++ground_cells;
        }
    }
    if (ground_cells == 0) return std::nullopt;
    scene.start_height_m = float(height_sum / double(ground_cells));
    for (const BakeSetSlotImages& slot : bake_set.slots) {
        std::vector<glm::vec3> without(cells, glm::vec3(0.0f));
        if (slot.ground_without.rgba.size() == floats)
            for (size_t i = 0; i < cells; ++i)
                without[i] = {slot.ground_without.rgba[4 * i], slot.ground_without.rgba[4 * i + 1],
                              slot.ground_without.rgba[4 * i + 2]};
        scene.irradiance_without.push_back(std::move(without));
    }
    return scene;
}

std::optional<size_t> groundMatchCellOfPixel(const GroundMatchScene& scene, const GroundMatchView& view, uint32_t x,
                                             uint32_t y) {
    const glm::dvec3 camera_ray((double(x) + 0.5 - view.cx) / view.fx, (double(y) + 0.5 - view.cy) / view.fy, 1.0);
    const glm::dvec3 direction = view.camera_to_enu * camera_ray;
    const glm::dvec3& origin = view.camera_position_enu;
    if (!(direction.z < -1e-6)) return std::nullopt;  // the ray never comes down to the ground
    double height = scene.start_height_m;
    long cell = -1, previous = -1;
    for (int step = 0; step <= kGroundMatchHeightIterations; ++step) {
        const double t = (height - origin.z) / direction.z;
        if (!(t > 0.0)) return std::nullopt;
        previous = cell;
        cell = cellAt(scene.grid, origin.x + t * direction.x, origin.y + t * direction.y);
        if (cell < 0 || !scene.cells[size_t(cell)].ground) return std::nullopt;
        // Settled: the next step would start from this same cell's height, so every later step repeats it (the
        // GPU stops here too: on flat ground after the second step instead of the fifth).
        if (cell == previous) return size_t(cell);
        height = scene.cells[size_t(cell)].height_m;
    }
    return std::nullopt;  // not settled on one cell
}

glm::dvec3 groundMatchPredictedRadiance(const GroundMatchScene& scene, const GroundMatchView& view, size_t cell) {
    const GroundMatchCell& ground = scene.cells[cell];
    glm::dvec3 irradiance(0.0);
    for (int k = 0; k < 3; ++k) {
        const int slot = view.slots[k];
        if (slot < 0 || size_t(slot) >= scene.irradiance_without.size() || !(view.weights[k] > 0.0f)) continue;
        irradiance += double(view.weights[k]) * glm::dvec3(scene.irradiance_without[size_t(slot)][cell]);
    }
    if (view.sun_shines)
        irradiance += view.sun_irradiance_rgb *
                      std::max(0.0, glm::dot(glm::dvec3(ground.normal), view.sun_direction_enu));
    return view.exposure * glm::dvec3(ground.albedo) / std::numbers::pi * irradiance;
}

uint32_t groundMatchStride(uint32_t width, uint32_t height, uint32_t statistics_stride) {
    const double pixels = double(width) * double(height);
    const double stride = std::floor(std::sqrt(pixels / double(kGroundMatchTargetSamples)));
    return uint32_t(std::clamp(stride, 1.0, double(std::max(statistics_stride, 1u))));
}

uint32_t groundMatchBin(const glm::dvec3& observed, const glm::dvec3& predicted) {
    const double ratio = std::log2(luminance(observed) / luminance(predicted));
    const double bin = std::floor((ratio - kGroundMatchLowestLog2Ratio) * kGroundMatchBinsPerStop);
    return uint32_t(std::clamp(bin, 0.0, double(kGroundMatchBins - 1)));
}

GroundColourEstimate measureGroundColourGain(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
                                             uint32_t stride, const GroundMatchScene& scene,
                                             const GroundMatchView& view, float gain_limit) {
    const ColourStatisticsGrid grid = colourStatisticsGrid(width, height, stride);
    if (rgba8.size() < size_t(width) * height * 4)
        throw std::invalid_argument("ground colour match: camera image: " + std::to_string(rgba8.size()) +
                                    " bytes for " + std::to_string(width) + " x " + std::to_string(height));
    struct Bin {
        uint64_t count = 0;
        glm::dvec3 observed{0.0}, predicted{0.0};
    };
    Bin bins[kGroundMatchBins];
    GroundColourEstimate estimate;
    for (uint32_t j = 0; j < grid.samples_y; ++j)
        for (uint32_t i = 0; i < grid.samples_x; ++i) {
            const uint32_t x = grid.offset + i * stride, y = grid.offset + j * stride;
            const std::optional<size_t> cell = groundMatchCellOfPixel(scene, view, x, y);
            if (!cell) continue;
            const uint8_t* pixel = &rgba8[(size_t(y) * width + x) * 4];
            if (isClippedCameraPixel(pixel[0], pixel[1], pixel[2])) {
                ++estimate.clipped_samples;
                continue;
            }
            const glm::dvec3 predicted = groundMatchPredictedRadiance(scene, view, *cell);
            if (!(luminance(predicted) >= kGroundMatchMinPredicted)) continue;
            const glm::dvec3 observed(srgbDecode(pixel[0] / 255.0), srgbDecode(pixel[1] / 255.0),
                                      srgbDecode(pixel[2] / 255.0));
            Bin& bin = bins[groundMatchBin(observed, predicted)];
            ++bin.count;
            bin.observed += observed;
            bin.predicted += predicted;
            ++estimate.ground_samples;
        }
    if (estimate.ground_samples == 0) return estimate;
    uint64_t cumulative = 0;
    for (uint32_t b = 0; b < kGroundMatchBins; ++b) {
        cumulative += bins[b].count;
        if (2 * cumulative >= estimate.ground_samples) {
            estimate.median_bin = int(b);
            break;
        }
    }
    const int first = std::max(0, estimate.median_bin - int(kGroundMatchWindowBins));
    const int last = std::min(int(kGroundMatchBins) - 1, estimate.median_bin + int(kGroundMatchWindowBins));
    for (int b = first; b <= last; ++b) {
        estimate.kept_samples += bins[b].count;
        estimate.observed_sum += bins[b].observed;
        estimate.predicted_sum += bins[b].predicted;
    }
    const double limit = std::max(1.0, double(gain_limit));
    estimate.accepted = estimate.kept_samples >= colourStatisticsMinValidSamples(grid.sampleCount());
    for (int c = 0; c < 3; ++c) {
        if (!(estimate.predicted_sum[c] > 0.0)) {
            estimate.accepted = false;
            continue;
        }
        estimate.gain[c] = std::clamp(estimate.observed_sum[c] / estimate.predicted_sum[c], 1.0 / limit, limit);
    }
    if (!estimate.accepted) estimate.gain = glm::dvec3(1.0);
    return estimate;
}

SmoothedGroundGain smoothGroundGain(const SmoothedGroundGain& previous, const GroundColourEstimate& frame,
                                    double smoothing_weight, bool reset) {
    SmoothedGroundGain next = reset ? SmoothedGroundGain{} : previous;
    if (!frame.accepted) return next;
    next.gain = next.valid ? next.gain + smoothing_weight * (frame.gain - next.gain) : frame.gain;
    next.valid = true;
    ++next.frames_accepted;
    return next;
}

}  // namespace gusuku
