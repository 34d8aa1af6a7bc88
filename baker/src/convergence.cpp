#include "gusuku_bake/convergence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>

#include "bake_geometry.h"
#include "bake_outputs.h"
#include "gusuku/maths/colour.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/adaptive_sampling.h"
#include "gusuku_bake/bake_progress.h"
#include "gusuku_bake/irradiance_tracer.h"
#include "gusuku_bake/slot_lighting.h"

namespace gusuku::bake {

namespace {

using Clock = std::chrono::steady_clock;

// Copies of texel points traced in one accumulator: 48 MB of query points, well inside any device's storage
// buffer range, however many extra samples a large lightmap plans.
constexpr size_t kExtraCopiesPerBatch = size_t(1) << 20;

// Relative RMS of luminance over texels valid in both (and set in `mask`, when one is given), against the
// reference.
double relativeRms(const std::vector<glm::vec4>& estimate, const std::vector<glm::vec4>& reference,
                   const std::vector<uint8_t>& mask = {}) {
    double squared_error = 0.0, reference_sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < reference.size(); ++i) {
        if (reference[i].a <= 0.0f || estimate[i].a <= 0.0f) continue;
        if (!mask.empty() && mask[i] == 0) continue;
        const double reference_luminance = luminanceRec709(glm::vec3(reference[i]));
        const double error = luminanceRec709(glm::vec3(estimate[i])) - reference_luminance;
        squared_error += error * error;
        reference_sum += reference_luminance;
        ++count;
    }
    if (count == 0 || reference_sum <= 0.0) return 0.0;
    return std::sqrt(squared_error / double(count)) / (reference_sum / double(count));
}

double logLogSlope(const std::vector<ConvergencePoint>& points, bool denoised) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int n = 0;
    for (const ConvergencePoint& point : points) {
        const double rms = denoised ? point.relative_rms_denoised : point.relative_rms;
        if (rms <= 0.0) continue;
        const double x = std::log(double(point.samples)), y = std::log(rms);
        sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
    }
    const double denominator = n * sxx - sx * sx;
    return n >= 2 && denominator > 0.0 ? (n * sxy - sx * sy) / denominator : 0.0;
}

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// The slot options.slot_name names, or the site's first when it names none.
const BakeSlot& studiedSlot(const SiteConfig& site, const ConvergenceOptions& options) {
    const BakeSlot* slot = site.bake.slots.empty() ? nullptr : &site.bake.slots.front();
    for (const BakeSlot& candidate : site.bake.slots)
        if (candidate.name == options.slot_name) slot = &candidate;
    if (slot == nullptr || (!options.slot_name.empty() && slot->name != options.slot_name))
        throw std::invalid_argument("no slot named " + quotedForMessage(options.slot_name) + " in " + site.file);
    return *slot;
}

/// One query point per lightmap texel, at its centre (the study traces no footprints).
std::vector<QueryPointGpu> texelCentrePoints(const BakeGeometry& geometry) {
    std::vector<QueryPointGpu> points;
    for (const LightmapTexel& texel : geometry.texels)
        points.push_back({glm::vec4(texel.position, 1.0f), glm::vec4(texel.shading_normal, 0.0f),
                          glm::vec4(texel.geometric_normal, 0.0f)});
    return points;
}

/// What every step of the study traces with.
struct StudyScene {
    const BakeGeometry& geometry;
    const std::vector<QueryPointGpu>& points;
    IrradianceTracer& tracer;
    const TracePass& pass;
    BakeProgress& progress;
};

/// The converged lightmap the study's errors are measured against, and its two halves.
struct ReferenceLightmap {
    std::vector<glm::vec4> texels;          ///< per texel of geometry.texels: the mean of both halves
    std::vector<glm::vec4> half_texels[2];  ///< each half alone (the second empty with a reference of 1 sample)
    bool has_two_halves = false;
    double seconds = 0.0;                   ///< the halves' tracing
};

// Reference: two halves with seeds independent of the study's and of each other. Their mean is the reference;
// their difference measures its own noise (independent estimates: the mean square of the difference of two
// halves is 4 times that of their mean), which the study then takes out of its errors.
ReferenceLightmap traceReference(const StudyScene& scene, uint32_t reference_samples, uint32_t bake_seed) {
    const uint32_t half_samples[2] = {reference_samples - reference_samples / 2, reference_samples / 2};
    ReferenceLightmap reference;
    std::vector<glm::vec4> reference_sums(scene.points.size(), glm::vec4(0.0f));
    const auto reference_start = Clock::now();
    uint32_t reference_done = 0;
    for (int half = 0; half < 2; ++half) {
        if (half_samples[half] == 0) continue;
        TracePass reference_pass = scene.pass;
        reference_pass.seed = bake_seed ^ (half == 0 ? 0x5eed5eedu : 0x7a11c0deu);
        PointAccumulator accumulator = scene.tracer.createAccumulator(scene.points);
        while (accumulator.samples_done < half_samples[half]) {
            const uint32_t chunk = std::min(8u, half_samples[half] - accumulator.samples_done);
            const auto chunk_start = Clock::now();
            const uint64_t rays = scene.tracer.addSamples(accumulator, chunk, reference_pass);
            reference_done += chunk;
            scene.progress.advance("reference", reference_done, reference_samples,
                                   double(chunk) * scene.points.size(), rays, secondsSince(chunk_start));
        }
        const std::vector<glm::vec4> sums = scene.tracer.readSums(accumulator);
        for (size_t i = 0; i < sums.size(); ++i) reference_sums[i] += sums[i];
        reference.half_texels[half] = processBuildingLightmap(scene.geometry, sums, half_samples[half], false).per_texel;
    }
    reference.seconds = secondsSince(reference_start);
    reference.has_two_halves = half_samples[1] > 0;
    reference.texels = processBuildingLightmap(scene.geometry, reference_sums, reference_samples, false).per_texel;
    return reference;
}

/// options.error_mask (an image of the lightmap) read per texel of geometry.texels, where the errors are summed;
/// empty without a mask. Fills the study's mask counts.
std::vector<uint8_t> errorMaskPerTexel(const ConvergenceOptions& options, const BakeGeometry& geometry,
                                       const std::vector<glm::vec4>& reference_texels, ConvergenceStudy& study) {
    std::vector<uint8_t> mask;
    if (options.error_mask.empty()) return mask;
    const size_t resolution = size_t(geometry.lightmap_resolution);
    if (options.error_mask.size() != resolution * resolution) {
        throw InputError(options.error_mask_name, "size",
                         std::to_string(options.error_mask.size()) + " texels is not the lightmap's " +
                             std::to_string(resolution) + " x " + std::to_string(resolution));
    }
    study.error_mask_name = options.error_mask_name;
    mask.resize(geometry.texels.size());
    for (size_t i = 0; i < geometry.texels.size(); ++i) {
        mask[i] = options.error_mask[size_t(geometry.texels[i].y) * resolution + size_t(geometry.texels[i].x)];
        if (mask[i] != 0 && reference_texels[i].a > 0.0f) ++study.common_texel_count;
    }
    // Every other texel of the mask is either no texel of the lightmap (a texel has one owner) or invalid.
    const size_t mask_texels = size_t(std::count_if(options.error_mask.begin(), options.error_mask.end(),
                                                    [](uint8_t flag) { return flag != 0; }));
    study.mask_texels_not_valid = mask_texels - study.common_texel_count;
    return mask;
}

/// A measured error with the reference's own noise taken out: sqrt(rms^2 - reference^2), never below zero.
double correctedRms(double measured, double reference_own_rms) {
    return std::sqrt(std::max(measured * measured - reference_own_rms * reference_own_rms, 0.0));
}

/// The study's estimate, grown as the sample count doubles: uniform samples on one accumulator (cumulative:
/// each point's pilot continues the last one's), and, when adaptive, extra samples on copies of the noisy points
/// traced afresh for every point. Keeps the trace time and rays of both.
class StudyEstimate {
public:
    explicit StudyEstimate(const StudyScene& scene)
        : scene_(scene), estimate_(scene.tracer.createAccumulator(scene.points)) {}

    /// The estimate's sums after tracing up to uniform_samples per point (nothing when it has them already).
    SetSums traceUniformTo(uint32_t uniform_samples, uint32_t max_samples) {
        if (uniform_samples > estimate_.samples_done) {
            const auto start = Clock::now();
            const uint32_t chunk = uniform_samples - estimate_.samples_done;
            const uint64_t chunk_rays = scene_.tracer.addSamples(estimate_, chunk, scene_.pass);
            const double chunk_seconds = secondsSince(start);
            uniform_seconds_ += chunk_seconds;
            uniform_rays_ += chunk_rays;
            scene_.progress.advance("study", estimate_.samples_done, max_samples,
                                    double(chunk) * scene_.points.size(), chunk_rays, chunk_seconds);
        }
        return SetSums{scene_.tracer.readSums(estimate_), scene_.tracer.readLuminanceSquareSums(estimate_),
                       std::vector<uint32_t>(scene_.points.size(), uniform_samples)};
    }

    /// Adds the adaptive extras planned from the pilot's noise to `set`, so that it reads as `target` samples.
    void traceAdaptiveExtrasTo(SetSums& set, uint32_t pilot_samples, uint32_t target) {
        const auto start = Clock::now();
        std::vector<float> variance(scene_.points.size());
        for (size_t i = 0; i < scene_.points.size(); ++i)
            variance[i] = luminanceVarianceOfMean(set.sums[i], set.luminance_square_sums[i], pilot_samples);
        traceAdaptiveExtras(set, scene_.points, variance, 1, pilot_samples, target, kExtraCopiesPerBatch,
                            [&](size_t, const std::vector<QueryPointGpu>& copies, std::vector<glm::vec4>& sums,
                                std::vector<float>& square_sums) {
                                PointAccumulator extra = scene_.tracer.createAccumulator(copies);
                                extra_rays_ += scene_.tracer.addSamples(extra, kAdaptiveSamplesPerCopy, scene_.pass);
                                sums = scene_.tracer.readSums(extra);
                                square_sums = scene_.tracer.readLuminanceSquareSums(extra);
                                return true;
                            });
        extra_seconds_ = secondsSince(start);
    }

    /// Starts a point: the extras of the last one are not part of this one.
    void startPoint() {
        extra_seconds_ = 0.0;
        extra_rays_ = 0;
    }
    /// The current point's cumulative cost: the uniform samples' so far plus this point's own extras.
    double pointSeconds() const { return uniform_seconds_ + extra_seconds_; }
    uint64_t pointRays() const { return uniform_rays_ + extra_rays_; }
    /// Ends a point: its extras count towards the study's rays per second.
    void endPoint() {
        total_seconds_ += extra_seconds_;
        total_rays_ += extra_rays_;
    }
    /// Every ray traced for the study's points over the time they took (the uniform ones once).
    double raysPerSecond() const {
        const double seconds = total_seconds_ + uniform_seconds_;
        return seconds > 0.0 ? double(total_rays_ + uniform_rays_) / seconds : 0.0;
    }

private:
    const StudyScene& scene_;
    PointAccumulator estimate_;
    double uniform_seconds_ = 0.0;
    uint64_t uniform_rays_ = 0;
    double extra_seconds_ = 0.0;
    uint64_t extra_rays_ = 0;
    double total_seconds_ = 0.0;  // every point's extras
    uint64_t total_rays_ = 0;
};

/// The errors of `set` read as `target` samples, raw and filtered, against the reference (and over the mask).
ConvergencePoint measurePoint(const BakeGeometry& geometry, const SetSums& set, uint32_t target,
                              const ReferenceLightmap& reference, const std::vector<uint8_t>& mask,
                              const ConvergenceStudy& study) {
    const std::vector<glm::vec4>& sums = set.sums;
    std::vector<float> variance(sums.size());
    for (size_t i = 0; i < sums.size(); ++i)
        variance[i] = luminanceVarianceOfMean(sums[i], set.luminance_square_sums[i], target);
    ConvergencePoint point;
    point.samples = target;
    const std::vector<glm::vec4> raw = processBuildingLightmap(geometry, sums, target, false).per_texel;
    point.relative_rms = relativeRms(raw, reference.texels);
    const auto denoise_start = Clock::now();
    const ProcessedLightmap denoised = processBuildingLightmap(geometry, sums, target, true, variance);
    point.denoise_seconds = secondsSince(denoise_start);
    point.relative_rms_denoised = relativeRms(denoised.per_texel, reference.texels);
    point.relative_rms_corrected = correctedRms(point.relative_rms, study.reference_own_rms);
    point.relative_rms_denoised_corrected = correctedRms(point.relative_rms_denoised, study.reference_own_rms);
    if (!mask.empty()) {
        point.common_relative_rms_corrected =
            correctedRms(relativeRms(raw, reference.texels, mask), study.common_reference_own_rms);
        point.common_relative_rms_denoised_corrected =
            correctedRms(relativeRms(denoised.per_texel, reference.texels, mask), study.common_reference_own_rms);
    }
    return point;
}

/// The study's points, the sample count doubling from 1 to options.max_samples; returns the rays per second.
double traceStudyPoints(const StudyScene& scene, const ConvergenceOptions& options, const ReferenceLightmap& reference,
                        const std::vector<uint8_t>& mask, ConvergenceStudy& study) {
    StudyEstimate estimate(scene);
    for (uint32_t target = 1; target <= options.max_samples; target *= 2) {
        const bool adaptive = options.adaptive && target >= kMinAdaptiveSamples;
        // The pilot never shrinks as target doubles (16, 16, 32, ...), so the running uniform sums are the pilot.
        const uint32_t uniform_samples = adaptive ? adaptivePilotSamples(target) : target;
        SetSums set = estimate.traceUniformTo(uniform_samples, options.max_samples);
        estimate.startPoint();
        if (adaptive) estimate.traceAdaptiveExtrasTo(set, uniform_samples, target);
        estimate.endPoint();
        ConvergencePoint point = measurePoint(scene.geometry, set, target, reference, mask, study);
        point.rays = estimate.pointRays();
        point.seconds = estimate.pointSeconds();
        study.points.push_back(point);
    }
    return estimate.raysPerSecond();
}

}  // namespace

ConvergenceStudy runConvergenceStudy(VulkanContext& context, const SiteConfig& site, const ConvergenceOptions& options) {
    const BakeSlot& slot = studiedSlot(site, options);
    const auto setup_start = Clock::now();
    const PreparedSky sunny = prepareSky(site.sunny_sky);
    std::optional<PreparedSky> overcast;
    if (site.overcast_sky) overcast = prepareSky(*site.overcast_sky);
    const SlotLighting lighting = lightSlot(site, slot, sunny, overcast ? &*overcast : nullptr);
    const double elevation = lighting.sun.present ? lighting.sun_position.apparent_elevation_deg : -1.0;
    // The study traces the lightmap alone: nothing draws the building's textures, so they need no more detail.
    const BakeGeometry geometry =
        prepareBakeGeometry(site, elevation, options.max_texture_size, options.max_texture_size);
    const std::vector<QueryPointGpu> points = texelCentrePoints(geometry);
    IrradianceTracer tracer(context, geometry.scene, lighting.sky->tables, options.max_texture_size);
    TracePass pass;
    pass.max_bounces = uint32_t(site.bake.max_bounces);
    pass.sun = lighting.sun;
    pass.sky_sampling = options.sky_sampling;

    ConvergenceStudy study;
    study.slot_name = slot.name;
    study.sky_sampling = skySamplingName(tracer.resolvedSkySampling(options.sky_sampling));
    study.texel_count = points.size();
    study.reference_samples = options.reference_samples;
    study.setup_seconds = secondsSince(setup_start);
    BakeProgress progress(double(points.size()) * (options.reference_samples + options.max_samples),
                          options.show_progress);
    const StudyScene scene{geometry, points, tracer, pass, progress};

    const ReferenceLightmap reference = traceReference(scene, options.reference_samples, site.bake.seed);
    study.reference_seconds = reference.seconds;
    const std::vector<uint8_t> mask = errorMaskPerTexel(options, geometry, reference.texels, study);
    if (reference.has_two_halves) {
        // Halves of unequal size (an odd count) are near enough: the estimate is a measurement of noise anyway.
        study.reference_own_rms = relativeRms(reference.half_texels[0], reference.half_texels[1]) / 2.0;
        if (!mask.empty())
            study.common_reference_own_rms = relativeRms(reference.half_texels[0], reference.half_texels[1], mask) / 2.0;
    }

    study.rays_per_second = traceStudyPoints(scene, options, reference, mask, study);
    progress.finish();
    study.log_log_slope = logLogSlope(study.points, false);
    study.log_log_slope_denoised = logLogSlope(study.points, true);
    if (!study.points.empty()) {
        // The study's own power law, extended to the reference's sample count.
        const ConvergencePoint& last = study.points.back();
        study.reference_noise_floor =
            last.relative_rms * std::pow(double(options.reference_samples) / double(last.samples), study.log_log_slope);
    }
    return study;
}

double secondsToReach(const ConvergenceStudy& study, double target, bool denoised) {
    for (size_t i = 0; i < study.points.size(); ++i) {
        const ConvergencePoint& point = study.points[i];
        const double rms = denoised ? point.relative_rms_denoised : point.relative_rms;
        if (rms > target) continue;
        const double filter_seconds = denoised ? point.denoise_seconds : 0.0;
        if (i == 0) return point.seconds + filter_seconds;
        const ConvergencePoint& before = study.points[i - 1];
        const double rms_before = denoised ? before.relative_rms_denoised : before.relative_rms;
        // Error ~ seconds^slope: interpolate log(seconds) linearly in log(rms).
        const double fraction = (std::log(rms_before) - std::log(target)) / (std::log(rms_before) - std::log(rms));
        return std::exp(std::log(before.seconds) + fraction * (std::log(point.seconds) - std::log(before.seconds))) +
               filter_seconds;
    }
    return -1.0;
}

std::string formatConvergenceStudy(const ConvergenceStudy& study, double target) {
    std::string text;
    char line[256];
    std::snprintf(line, sizeof line,
                  "slot %s, %zu lightmap texels, reference %u samples (%.1f s), setup before the first ray %.2f s, "
                  "sky sampling: %s\n",
                  study.slot_name.c_str(), study.texel_count, study.reference_samples, study.reference_seconds,
                  study.setup_seconds, study.sky_sampling.c_str());
    text += line;
    std::snprintf(line, sizeof line,
                  "reference's own noise (half against half / 2): %.4f relative RMS; *_corrected columns take it out "
                  "(sqrt(rms^2 - reference^2))\n",
                  study.reference_own_rms);
    text += line;
    const bool masked = !study.error_mask_name.empty();
    if (masked) {
        std::snprintf(line, sizeof line,
                      "error mask %s: %zu texels valid here (the common_* columns, reference's own noise %.4f over "
                      "them), %zu more not valid here\n",
                      study.error_mask_name.c_str(), study.common_texel_count, study.common_reference_own_rms,
                      study.mask_texels_not_valid);
        text += line;
    }
    text += "samples      rays   trace_s   rel_rms  rel_rms_denoised  denoise_s  rms*sqrt(spp)  rel_rms_corrected"
            "  rel_rms_denoised_corrected";
    text += masked ? "  common_rel_rms_corrected  common_rel_rms_denoised_corrected\n" : "\n";
    for (const ConvergencePoint& point : study.points) {
        std::snprintf(line, sizeof line, "%7u  %8.3g  %8.2f  %8.4f  %16.4f  %9.3f  %13.4f  %17.4f  %26.4f",
                      point.samples, double(point.rays), point.seconds, point.relative_rms,
                      point.relative_rms_denoised, point.denoise_seconds,
                      point.relative_rms * std::sqrt(double(point.samples)), point.relative_rms_corrected,
                      point.relative_rms_denoised_corrected);
        text += line;
        if (masked) {
            std::snprintf(line, sizeof line, "  %24.4f  %33.4f", point.common_relative_rms_corrected,
                          point.common_relative_rms_denoised_corrected);
            text += line;
        }
        text += "\n";
    }
    std::snprintf(line, sizeof line,
                  "log-log slope: %.3f raw, %.3f denoised (1/sqrt(samples) is -0.5)\n"
                  "reference noise floor: %.4f relative RMS\n"
                  "rays per second: %.3f M\n",
                  study.log_log_slope, study.log_log_slope_denoised, study.reference_noise_floor,
                  study.rays_per_second / 1e6);
    text += line;
    const auto describe = [](double seconds) {
        char value[64];
        if (seconds < 0.0) return std::string("not reached");
        std::snprintf(value, sizeof value, "%.2f s", seconds);
        return std::string(value);
    };
    std::vector<double> targets = {0.10, 0.05, 0.03, 0.02};
    if (std::find(targets.begin(), targets.end(), target) == targets.end()) targets.push_back(target);
    for (const double each : targets) {
        std::snprintf(line, sizeof line,
                      "trace time to %.1f %% relative RMS: %s raw, %s denoised (filter included)\n", each * 100.0,
                      describe(secondsToReach(study, each, false)).c_str(),
                      describe(secondsToReach(study, each, true)).c_str());
        text += line;
    }
    return text;
}

}  // namespace gusuku::bake
