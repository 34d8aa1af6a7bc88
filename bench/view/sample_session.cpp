// The sample session: a walk around the building through the bake day (see sample_session.h).

#include "sample_session.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bakeset_site.h"
#include "camera_view.h"
#include "frame_progress.h"
#include "gusuku/assets/site.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku_bake/camera_frame.h"
#include "truth_renderer.h"

namespace gusuku::view {

namespace {

// The walk: on a circle around the building's door side at a visitor's raised eye (a phone held up on the
// terrace), from south-west to east of south, always looking at the doorway; the sample's README view
// (scripts/render-composites.sh: 9,-19,5.5 towards 0,-1,1.2) lies on it.
constexpr double kWalkRadiusM = 20.0;
constexpr double kEyeHeightM = 5.5;
constexpr double kFirstBearingDeg = 205.0, kLastBearingDeg = 125.0;  // clockwise from north
const glm::dvec3 kLookAtEnu{0.0, -1.0, 1.2};

constexpr double kPi = 3.14159265358979323846;

}  // namespace

float sampleCloudCover(double site_clock_hours) {
    // A cos^2 bump: 0 outside [12.5, 14.0] hours, 0.8 at 13.25.
    constexpr double kStart = 12.5, kEnd = 14.0, kPeak = 0.8;
    if (site_clock_hours <= kStart || site_clock_hours >= kEnd) return 0.0f;
    const double phase = (site_clock_hours - kStart) / (kEnd - kStart);  // 0..1
    const double bump = std::sin(kPi * phase);
    return float(kPeak * bump * bump);
}

Session makeSampleSession(const GpuDevice& gpu, const std::string& bake_set_folder, const BakeSetData& bake_set,
                          const SampleWalkOptions& options) {
    const std::string site_json = bench_common::siteJsonOf(bake_set_folder, bake_set.manifest);
    const double midnight_utc = bench_common::bakeDateMidnightUtc(bake_set_folder, bake_set.manifest, "--sample-session");
    const int utc_offset_minutes = bake_set.manifest.site.utc_offset_minutes;
    bench::TruthRenderer renderer(gpu, loadSiteConfig(site_json), /*cache_folder=*/"", /*context_hash=*/"");

    Session session;
    session.intrinsics =
        CameraIntrinsics::fromFieldOfView(options.width, options.height, options.horizontal_fov_deg);
    std::vector<ImageRGBA> linear_frames;
    std::vector<float> middle_grey_exposures;
    const uint32_t count = std::max(options.frames, 1u);
    FrameProgress progress(count, options.show_progress, "traced");
    for (uint32_t index = 0; index < count; ++index) {
        const double along = count > 1 ? double(index) / double(count - 1) : 0.0;
        const double hours = options.first_hour + along * (options.last_hour - options.first_hour);
        const double bearing = (kFirstBearingDeg + along * (kLastBearingDeg - kFirstBearingDeg)) * kPi / 180.0;
        bench::BenchView view;
        view.position_enu = kLookAtEnu + glm::dvec3(kWalkRadiusM * std::sin(bearing),
                                                    kWalkRadiusM * std::cos(bearing), 0.0);
        view.position_enu.z = kEyeHeightM;
        view.look_at_enu = kLookAtEnu;
        view.horizontal_fov_deg = options.horizontal_fov_deg;
        // Whole seconds, so that the track's ISO 8601 text (to the second) is the instant traced.
        const double utc_seconds = std::round(midnight_utc + hours * 3600.0);
        const bench::TracedFrameRequest request = bench::siteCameraRequest(
            view, options.width, options.height, {utc_seconds, sampleCloudCover(hours)}, options.samples_per_pixel);
        bench::TracedFrame traced = renderer.render(request, /*use_cache=*/false);
        middle_grey_exposures.push_back(bake::middleGreyExposure(traced.denoised));
        linear_frames.push_back(std::move(traced.denoised));

        SessionFrame frame;
        frame.utc_seconds = utc_seconds;
        frame.time_iso = formatIso8601(utc_seconds, utc_offset_minutes);
        frame.pose = bench_common::lookAtPose(request.view.position_enu, request.view.look_at_enu);
        frame.cloud_cover = request.condition.cloud_cover;
        session.frames.push_back(std::move(frame));
        progress.advance(index + 1);
    }
    std::vector<float> sorted = middle_grey_exposures;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const float exposure = sorted[sorted.size() / 2];
    for (size_t index = 0; index < session.frames.size(); ++index) {
        session.frames[index].exposure = exposure;
        session.frames[index].rgba8 = bake::packRgba8Srgb(linear_frames[index], exposure);
    }
    return session;
}

}  // namespace gusuku::view
