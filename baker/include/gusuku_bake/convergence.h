#pragma once
// Convergence study of the building lightmap: RMS error against a converged reference as samples double, with
// and without the edge-keeping filter, and the time each step cost. Monte Carlo error should fall as
// 1/sqrt(samples) (a slope of -1/2 on log-log axes); the study measures it rather than assuming it.

#include <cstdint>
#include <string>
#include <vector>

#include "gusuku/assets/site.h"
#include "gusuku/gpu/vulkan_context.h"
#include "gusuku_bake/irradiance_tracer.h"

namespace gusuku::bake {

struct ConvergenceOptions {
    std::string slot_name;             ///< empty: the site's first slot
    uint32_t reference_samples = 1024; ///< the converged bake (an independent seed)
    uint32_t max_samples = 128;        ///< the study doubles from 1 up to this
    int max_texture_size = 512;
    bool show_progress = true;
    SkySampling sky_sampling = SkySampling::Automatic;  ///< the study and its reference both use it
    /// As the bake samples (adaptive_sampling.h): from 32 samples on, each study point is a pilot
    /// (adaptivePilotSamples: a quarter, at least 16), every texel alike, and the rest planned by each texel's
    /// noise; its time and rays are the pilot's (cumulative, as for uniform points) plus its own extra
    /// samples'. false: every texel alike.
    bool adaptive = true;
    /// Texels whose errors are also measured on their own (the "common" columns): resolution^2 flags in the
    /// lightmap's layout (row 0 at the top), e.g. the texels another baker bakes too, so that two bakers'
    /// errors cover the same texels. Empty: none. A size other than the lightmap's is an InputError naming
    /// error_mask_name.
    std::vector<uint8_t> error_mask;
    std::string error_mask_name;
};

struct ConvergencePoint {
    uint32_t samples = 0;
    uint64_t rays = 0;            ///< cumulative
    double seconds = 0.0;         ///< cumulative trace time
    double denoise_seconds = 0.0; ///< time the edge-keeping filter took on this point's lightmap
    double relative_rms = 0.0;    ///< RMS(E - E_ref) / mean(E_ref), luminance, over valid texels
    double relative_rms_denoised = 0.0;
    /// The same with the reference's own noise taken out: sqrt(max(rms^2 - reference_own_rms^2, 0)) (the two are
    /// independent, so their mean squares add). What the error against the exact answer is estimated to be.
    double relative_rms_corrected = 0.0;
    double relative_rms_denoised_corrected = 0.0;
    /// The corrected errors over the texels of ConvergenceOptions::error_mask only (0 without a mask).
    double common_relative_rms_corrected = 0.0;
    double common_relative_rms_denoised_corrected = 0.0;
};

struct ConvergenceStudy {
    std::string slot_name;
    std::string sky_sampling;  ///< the method used, resolved ("cosine" or "cosine + map (MIS)")
    size_t texel_count = 0;
    uint32_t reference_samples = 0;
    double reference_seconds = 0.0;
    /// Time before the first ray: sky tables and sun, charts and texels, BVH, pipelines. A bake pays it once per
    /// slot; a fair wall-time comparison with another baker adds it to the trace time.
    double setup_seconds = 0.0;
    /// The reference's own expected error: the study's fitted power law (log_log_slope) extended from its last
    /// point to the reference's sample count. Errors near this floor are the reference's noise, not the bake's.
    double reference_noise_floor = 0.0;
    /// The reference's own relative RMS error, measured: it is traced as two halves with independent seeds, and
    /// this is the relative RMS of their difference / 2. 0 when the reference has one sample.
    double reference_own_rms = 0.0;
    /// With an error mask: its name, the texels it holds that the lightmap has valid (those its errors cover),
    /// the ones it holds that the lightmap does not (0 unless the mask is misaligned or another baker covers
    /// texels gusuku leaves out), and the reference's own noise over it.
    std::string error_mask_name;
    size_t common_texel_count = 0;
    size_t mask_texels_not_valid = 0;
    double common_reference_own_rms = 0.0;
    std::vector<ConvergencePoint> points;
    double rays_per_second = 0.0;
    double log_log_slope = 0.0;           ///< least-squares slope of log(rms) on log(samples), raw
    double log_log_slope_denoised = 0.0;
};

ConvergenceStudy runConvergenceStudy(VulkanContext& context, const SiteConfig& site, const ConvergenceOptions& options);

/// Seconds of tracing to reach `target_relative_rms`, interpolated on log-log axes between measured points;
/// negative when the study never reached it. For the denoised error, the filter's own time is included.
double secondsToReach(const ConvergenceStudy& study, double target_relative_rms, bool denoised);

/// The study as a printable table plus summary lines.
std::string formatConvergenceStudy(const ConvergenceStudy& study, double target_relative_rms);

}  // namespace gusuku::bake
