// The sun read from the site's shadows in the camera frame: see gusuku/maths/sun_evidence.h.

#include "gusuku/maths/sun_evidence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/glm.hpp>

#include "gusuku/maths/colour.h"

namespace gusuku {

namespace {

using Histogram = std::array<uint32_t, kSunEvidenceBins>;

double lowerBinEdge(uint32_t bin, double lowest, double span) {
    return lowest + span * double(bin) / double(kSunEvidenceBins);
}

double sumOf(const Histogram& counts) {
    double total = 0.0;
    for (uint32_t count : counts) total += count;
    return total;
}

// The bin holding the median: the first whose cumulative count reaches half the total (sunEvidenceQuantile's).
uint32_t medianBin(const Histogram& counts) {
    const double half = 0.5 * sumOf(counts);
    double before = 0.0;
    for (uint32_t bin = 0; bin < kSunEvidenceBins; ++bin) {
        if (counts[bin] > 0 && before + counts[bin] >= half) return bin;
        before += counts[bin];
    }
    return 0;
}

bool inWindow(uint32_t bin, uint32_t median) {
    return bin + kSunEvidenceWindowBins >= median && bin <= median + kSunEvidenceWindowBins;
}

// A cell's height by column and row from the south, or -infinity where there is no ground (it never blocks).
double columnHeight(const GroundMatchScene& scene, long column, long row_from_south) {
    const GroundGrid& grid = scene.grid;
    if (column < 0 || column >= grid.columns || row_from_south < 0 || row_from_south >= grid.rows)
        return -std::numeric_limits<double>::infinity();
    const GroundMatchCell& cell = scene.cells[size_t((grid.rows - 1 - row_from_south) * long(grid.columns) + column)];
    return cell.ground ? double(cell.height_m) : -std::numeric_limits<double>::infinity();
}

}  // namespace

bool sunEvidenceRayReachesCell(const GroundMatchScene& scene, const glm::dvec3& origin, const glm::dvec3& direction,
                               size_t cell, double ground_top_m) {
    const GroundGrid& grid = scene.grid;
    const double t_hit = (double(scene.cells[cell].height_m) - origin.z) / direction.z;
    // Grid units (columns, rows from the south) of the hit, and the walk back towards the origin: s = t_hit - t.
    const glm::dvec2 hit = (glm::dvec2(origin) + t_hit * glm::dvec2(direction) - grid.origin_enu_m) / grid.cell_m;
    const glm::dvec2 back = -glm::dvec2(direction) / grid.cell_m;
    long column = long(cell % size_t(grid.columns));
    long row_from_south = long(grid.rows) - 1 - long(cell / size_t(grid.columns));
    const long step_column = back.x > 0.0 ? 1 : -1, step_row = back.y > 0.0 ? 1 : -1;
    const double infinity = std::numeric_limits<double>::infinity();
    // The walk's parameter at the next edge across each axis, and between edges.
    double next_x = back.x != 0.0 ? (double(column + (back.x > 0.0 ? 1 : 0)) - hit.x) / back.x : infinity;
    double next_y = back.y != 0.0 ? (double(row_from_south + (back.y > 0.0 ? 1 : 0)) - hit.y) / back.y : infinity;
    const double delta_x = back.x != 0.0 ? 1.0 / std::abs(back.x) : infinity;
    const double delta_y = back.y != 0.0 ? 1.0 / std::abs(back.y) : infinity;
    for (uint32_t crossing = 0; crossing < kSunEvidenceMaxCrossings; ++crossing) {
        const double s = std::min(next_x, next_y);
        if (!(s < t_hit)) return true;  // back at the origin: nothing in the way
        const double ray_height = origin.z + (t_hit - s) * direction.z;
        if (ground_top_m <= ray_height + kSunEvidenceStepToleranceM) return true;  // above every step from here
        const double left = columnHeight(scene, column, row_from_south);
        if (next_x < next_y) {
            column += step_column;
            next_x += delta_x;
        } else {
            row_from_south += step_row;
            next_y += delta_y;
        }
        const double entered = columnHeight(scene, column, row_from_south);
        if (std::max(left, entered) > ray_height + kSunEvidenceStepToleranceM) return false;
    }
    return true;
}

double sunEvidenceGroundTop(const GroundMatchScene& scene) {
    double top = -std::numeric_limits<double>::infinity();
    for (const GroundMatchCell& cell : scene.cells)
        if (cell.ground) top = std::max(top, double(cell.height_m));
    return top;
}

uint32_t sunEvidenceBin(double value, double lowest, double span) {
    const double index = std::floor((value - lowest) / span * double(kSunEvidenceBins));
    if (!(index >= 0.0)) return 0;  // below, and NaN
    return uint32_t(std::min(index, double(kSunEvidenceBins - 1)));
}

double sunEvidenceQuantile(ConstSpan<uint32_t> counts, double quantile, double lowest, double span) {
    double total = 0.0;
    for (uint32_t count : counts) total += count;
    if (!(total > 0.0)) return lowest;
    const double target = quantile * total;
    double before = 0.0;
    for (uint32_t bin = 0; bin < counts.size(); ++bin) {
        const double count = counts[bin];
        if (count > 0.0 && before + count >= target) {
            const double within = std::clamp((target - before) / count, 0.0, 1.0);
            return lowerBinEdge(bin, lowest, span) + within * span / double(kSunEvidenceBins);
        }
        before += count;
    }
    return lowest + span;
}

namespace {

// One side's reading of the response: its samples split at their mean predicted level x; in each half the trimmed
// mean of the ratio about its median (kSunEvidenceWindowBins) and the mean x of the samples kept. Medians, not a
// least-squares line: pixels of a fixed brightness that are not the cell (a wall in front, a person) run at slope
// -1 and would pull a line.
struct ResponseSide {
    bool valid = false;
    double samples = 0.0, level_apart = 0.0, ratio_apart = 0.0;  // n, and the lighter half's x and r less the darker's
};

ResponseSide responseSide(ConstSpan<SunEvidenceSample> samples, SunEvidenceSampleKind kind) {
    auto binOf = [](const SunEvidenceSample& sample) {
        return sunEvidenceBin(sample.log2_ratio, kSunEvidenceLowestLog2Ratio, kSunEvidenceLog2RatioSpan);
    };
    // Single-precision sums in sample order, as the GPU's lanes keep them (its order differs: a last-digit matter).
    float n = 0.0f, sum_x = 0.0f;
    for (const SunEvidenceSample& sample : samples)
        if (sample.kind == kind) n += 1.0f, sum_x += sample.log2_predicted;
    ResponseSide side;
    side.samples = n;
    if (n < float(kSunEvidenceMinSamples)) return side;
    const float split = sum_x / n;
    std::array<Histogram, 2> halves{};
    for (const SunEvidenceSample& sample : samples)
        if (sample.kind == kind) ++halves[sample.log2_predicted >= split][binOf(sample)];
    float kept[2] = {0.0f, 0.0f}, ratio[2] = {0.0f, 0.0f}, level[2] = {0.0f, 0.0f};
    const uint32_t median[2] = {medianBin(halves[0]), medianBin(halves[1])};
    for (const SunEvidenceSample& sample : samples) {
        if (sample.kind != kind) continue;
        const int half = sample.log2_predicted >= split;
        if (!inWindow(binOf(sample), median[half])) continue;
        kept[half] += 1.0f;
        ratio[half] += sample.log2_ratio;
        level[half] += sample.log2_predicted;
    }
    const float half_samples = 0.5f * float(kSunEvidenceMinSamples);
    if (kept[0] < half_samples || kept[1] < half_samples) return side;
    side.level_apart = double(level[1] / kept[1]) - double(level[0] / kept[0]);
    side.ratio_apart = double(ratio[1] / kept[1]) - double(ratio[0] / kept[0]);
    side.valid = side.level_apart >= kSunEvidenceMinResponseSpreadLog2;
    return side;
}

// The camera response's power (sun_evidence.h: the response): each side's slope, pooled by its samples and spread.
double responseGamma(ConstSpan<SunEvidenceSample> samples) {
    double spread = 0.0, moved = 0.0;
    for (SunEvidenceSampleKind kind : {SunEvidenceSampleKind::kShadowed, SunEvidenceSampleKind::kLit}) {
        const ResponseSide side = responseSide(samples, kind);
        if (!side.valid) continue;
        spread += side.samples * side.level_apart * side.level_apart;
        moved += side.samples * side.level_apart * side.ratio_apart;
    }
    if (!(spread > 0.0)) return 1.0;
    return std::clamp(1.0 + moved / spread, kSunEvidenceMinResponseGamma, kSunEvidenceMaxResponseGamma);
}

}  // namespace

SunEvidenceEstimate estimateSunEvidence(ConstSpan<SunEvidenceSample> samples) {
    SunEvidenceEstimate estimate;
    // The ratios linearised through the response: r' = (r + x) / gamma - x (unchanged when gamma is 1).
    const double gamma = responseGamma(samples);
    estimate.response_gamma = float(gamma);
    auto ratioOf = [gamma = float(gamma)](const SunEvidenceSample& sample) {
        return gamma == 1.0f ? sample.log2_ratio
                             : (sample.log2_ratio + sample.log2_predicted) / gamma - sample.log2_predicted;
    };
    Histogram shade{};
    for (const SunEvidenceSample& sample : samples)
        if (sample.kind == SunEvidenceSampleKind::kShadowed)
            ++shade[sunEvidenceBin(ratioOf(sample), kSunEvidenceLowestLog2Ratio, kSunEvidenceLog2RatioSpan)];
    const double shadowed = sumOf(shade);
    // The trimmed mean about the median: the samples within kSunEvidenceWindowBins bins of the median's.
    const uint32_t shade_median = medianBin(shade);
    double shade_sum = 0.0, shade_kept = 0.0;
    for (const SunEvidenceSample& sample : samples)
        if (sample.kind == SunEvidenceSampleKind::kShadowed &&
            inWindow(sunEvidenceBin(ratioOf(sample), kSunEvidenceLowestLog2Ratio, kSunEvidenceLog2RatioSpan),
                     shade_median)) {
            shade_sum += ratioOf(sample);
            shade_kept += 1.0;
        }
    // Too little shade in view (kMeteredGround): the lit samples are read against the app's exposure, g = 1.
    const bool boundary_shade = shadowed >= double(kSunEvidenceMinSamples);
    const double shade_log2 = boundary_shade && shade_kept > 0.0 ? shade_sum / shade_kept : 0.0;

    // Each lit sample's strength against the shade's level: ratio / g = 1 + s q.
    auto strengthOf = [&](const SunEvidenceSample& sample) {
        return (std::exp2(ratioOf(sample) - float(shade_log2)) - 1.0f) / sample.sun_share;
    };
    auto counts = [](const SunEvidenceSample& sample) {
        return sample.kind == SunEvidenceSampleKind::kLit && sample.sun_share >= kSunEvidenceMinSunShare;
    };
    Histogram strength{};
    for (const SunEvidenceSample& sample : samples)
        if (counts(sample))
            ++strength[sunEvidenceBin(strengthOf(sample), kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan)];
    const double lit = sumOf(strength);
    estimate.shadowed_samples = uint32_t(shadowed);
    estimate.lit_samples = uint32_t(lit);
    const double fewest = std::min(shadowed, lit);
    if (lit < double(kSunEvidenceMinSamples)) return estimate;  // no lit ground in view: the prior decides

    const uint32_t strength_median = medianBin(strength);
    double strength_sum = 0.0, strength_kept = 0.0;
    for (const SunEvidenceSample& sample : samples)
        if (counts(sample)) {
            const float s_i = strengthOf(sample);
            if (inWindow(sunEvidenceBin(s_i, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan), strength_median)) {
                strength_sum += s_i;
                strength_kept += 1.0;
            }
        }
    const double s = strength_sum / strength_kept;  // the median's bin is in the window: never empty
    const double interquartile =
        sunEvidenceQuantile(strength, 0.75, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan) -
        sunEvidenceQuantile(strength, 0.25, kSunEvidenceLowestStrength, kSunEvidenceStrengthSpan);
    // The median's standard error for a normal spread (sigma = IQR / 1.349; se = sqrt(pi / 2) sigma / sqrt(n)).
    const double standard_error = 1.2533 * (interquartile / 1.349) / std::sqrt(lit);
    const double width = std::max(kSunEvidenceMinWidth, standard_error);
    const double probability = 1.0 / (1.0 + std::exp(-(s - kSunEvidenceOutStrength) / width));
    // The metered ground's confidence stays 0 here: it holds only for an app whose exposure is metered
    // (sunEvidenceForFilter).
    const double confidence = boundary_shade ? std::min(1.0, fewest / double(kSunEvidenceFullSamples)) *
                                                   std::clamp(1.0 - standard_error / kSunEvidenceOutStrength, 0.0, 1.0)
                                             : 0.0;
    estimate.cue = boundary_shade ? SunEvidenceCue::kSiteShadowBoundary : SunEvidenceCue::kMeteredGround;
    estimate.shade_log2_ratio = float(shade_log2);
    estimate.strength = float(s);
    estimate.strength_standard_error = float(standard_error);
    estimate.evidence.sun_out_probability = float(probability);
    estimate.evidence.confidence = float(confidence);
    estimate.evidence.sun_strength = probability >= 0.5 ? float(s) : -1.0f;
    return estimate;
}

std::vector<SunEvidenceSample> sunEvidenceSamples(ConstSpan<uint8_t> rgba8, uint32_t width, uint32_t height,
                                                  uint32_t stride, const GroundMatchScene& scene,
                                                  const GroundMatchView& view,
                                                  const glm::dvec3& clear_sun_irradiance_rgb,
                                                  const SiteVisibility& site_visibility) {
    const ColourStatisticsGrid grid = colourStatisticsGrid(width, height, stride);
    std::vector<SunEvidenceSample> samples(size_t(grid.sampleCount()));
    const glm::dvec3 sun = view.sun_direction_enu;
    if (!(sun.z > 0.0)) return samples;  // no sun to cast a shadow
    const double ground_top_m = sunEvidenceGroundTop(scene);
    GroundMatchView without_sun = view;
    without_sun.sun_shines = false;
    for (uint32_t j = 0; j < grid.samples_y; ++j)
        for (uint32_t i = 0; i < grid.samples_x; ++i) {
            const uint32_t x = grid.offset + i * grid.stride, y = grid.offset + j * grid.stride;
            const std::optional<size_t> cell = groundMatchCellOfPixel(scene, view, x, y);
            if (!cell) continue;
            // The march's ray (groundMatchCellOfPixel's): does it show this cell, or the side of a step before it?
            const glm::dvec3 ray = view.camera_to_enu * glm::dvec3((double(x) + 0.5 - view.cx) / view.fx,
                                                                   (double(y) + 0.5 - view.cy) / view.fy, 1.0);
            if (!sunEvidenceRayReachesCell(scene, view.camera_position_enu, ray, *cell, ground_top_m)) continue;
            const uint8_t* pixel = &rgba8[(size_t(y) * width + x) * 4];
            if (isClippedCameraPixel(pixel[0], pixel[1], pixel[2])) continue;
            const glm::dvec3 predicted = groundMatchPredictedRadiance(scene, without_sun, *cell);
            const double predicted_luminance = luminanceRec709(predicted);
            if (!(predicted_luminance >= kGroundMatchMinPredicted)) continue;
            const glm::dvec3 observed(srgbDecode(pixel[0] / 255.0), srgbDecode(pixel[1] / 255.0),
                                      srgbDecode(pixel[2] / 255.0));
            const GroundMatchCell& ground = scene.cells[*cell];
            const double cosine = glm::dot(glm::dvec3(ground.normal), sun);
            const glm::dvec3 albedo(ground.albedo);
            // q from the cell's albedo-weighted irradiances (exposure and 1/pi cancel).
            const double sun_luminance = luminanceRec709(albedo * clear_sun_irradiance_rgb) * std::max(0.0, cosine);
            SunEvidenceSample& sample = samples[size_t(j) * grid.samples_x + i];
            sample.log2_ratio = float(std::log2(luminanceRec709(observed) / predicted_luminance));
            sample.sun_share = float(sun_luminance * view.exposure / std::numbers::pi / predicted_luminance);
            sample.log2_predicted = float(std::log2(predicted_luminance));
            if (cosine <= 0.0) {
                sample.kind = SunEvidenceSampleKind::kShadowed;  // the face turns from the sun
                continue;
            }
            const glm::dvec2 centre = groundCellCentreEnu(scene.grid, groundCellFromIndex(scene.grid, *cell));
            const double visibility = site_visibility(glm::dvec3(centre, ground.height_m));
            if (visibility <= kSunEvidenceShadowedVisibility) sample.kind = SunEvidenceSampleKind::kShadowed;
            else if (visibility >= kSunEvidenceLitVisibility) sample.kind = SunEvidenceSampleKind::kLit;
        }
    return samples;
}

}  // namespace gusuku
