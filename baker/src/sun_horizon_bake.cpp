// The baker's sun horizons (gusuku_bake/sun_horizon_bake.h).

#include "gusuku_bake/sun_horizon_bake.h"

#include <algorithm>
#include <atomic>
#include <thread>

#include <glm/vec4.hpp>

namespace gusuku::bake {
namespace {

// Off the surface so that the texel's own triangle is not met at t ~ 0 (float positions 100 m from the site's
// origin hold 8 um), and small against a tile's centimetres: it lowers a horizon 5 cm away by 0.2 degrees.
constexpr float kRayOffsetM = 2e-4f;
constexpr double kLadderStepDeg = 6.0;
constexpr int kBisections = 4;  // 6 / 2^4 = 0.375 degrees, about a code step (0.353)

}  // namespace

double traceSunHorizonDeg(const Bvh& bvh, const glm::vec3& point, const glm::vec3& normal, double azimuth_deg,
                          double radius_m, uint32_t skip_flags) {
    const glm::vec3 origin = point + kRayOffsetM * normal;
    auto blocked = [&](double elevation_deg) {
        return occludedCpu(bvh, origin, glm::vec3(sunHorizonDirection(azimuth_deg, elevation_deg)), float(radius_m),
                           skip_flags);
    };
    // The highest blocked rung: a horizon is not monotonic in general (a tile's crest blocks low rays, the open
    // sky above it does not, an eave above blocks high ones again); the highest blocked one is what a low sun sees
    // last.
    double lowest_open_above = -1.0;
    for (double rung = 90.0 - kLadderStepDeg; rung >= -1e-9; rung -= kLadderStepDeg)
        if (blocked(rung)) {
            lowest_open_above = rung;
            break;
        }
    if (lowest_open_above < 0.0) return 0.0;
    double low = lowest_open_above, high = std::min(lowest_open_above + kLadderStepDeg, 90.0);
    for (int step = 0; step < kBisections; ++step) {
        const double middle = 0.5 * (low + high);
        (blocked(middle) ? low : high) = middle;
    }
    return 0.5 * (low + high);
}

BakeSetSunHorizon bakeSunHorizons(const Bvh& bvh, const std::vector<LightmapTexel>& texels, int resolution,
                                  const std::vector<int32_t>& reader_charts, double radius_m, uint32_t skip_flags) {
    const size_t texel_count = size_t(resolution) * size_t(resolution);
    // Three images of (horizon, horizon, horizon, valid), for the dilation, whose alpha marks what it keeps.
    constexpr int kImages = 3;
    std::vector<std::vector<glm::vec4>> images(kImages, std::vector<glm::vec4>(texel_count, glm::vec4(0.0f)));
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < texels.size(); i = next++) {
            const LightmapTexel& texel = texels[i];
            const size_t index = size_t(texel.y) * size_t(resolution) + size_t(texel.x);
            for (int azimuth = 0; azimuth < kSunHorizonAzimuths; ++azimuth)
                images[azimuth / 3][index][azimuth % 3] = float(traceSunHorizonDeg(
                    bvh, texel.position, texel.geometric_normal, azimuth * kSunHorizonAzimuthStepDeg, radius_m,
                    skip_flags));
            for (auto& image : images) image[index].a = 1.0f;
        }
    };
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (std::thread& thread : pool) thread.join();
    if (!reader_charts.empty())
        for (auto& image : images) dilateLightmapWithinCharts(image, reader_charts, resolution, 8);

    BakeSetSunHorizon horizon;
    horizon.width = horizon.height = resolution;
    horizon.rgba8.assign(size_t(kSunHorizonLayers) * texel_count * 4, 0);
    for (size_t index = 0; index < texel_count; ++index)
        for (int azimuth = 0; azimuth < kSunHorizonAzimuths; ++azimuth) {
            const int layer = azimuth / 4, channel = azimuth % 4;
            horizon.rgba8[(size_t(layer) * texel_count + index) * 4 + size_t(channel)] =
                encodeSunHorizonDeg(images[azimuth / 3][index][azimuth % 3]);
        }
    return horizon;
}

int sunHorizonResolution(int lightmap_resolution, double texels_per_metre) {
    int factor = 1;
    while (factor < kMaxSunHorizonFactor && texels_per_metre * factor * kSunHorizonTargetTexelM < 1.0 &&
           lightmap_resolution * (factor + 1) <= kMaxSunHorizonResolution)
        ++factor;
    return std::clamp(lightmap_resolution * factor, kMinSunHorizonResolution, kMaxSunHorizonResolution);
}

}  // namespace gusuku::bake
