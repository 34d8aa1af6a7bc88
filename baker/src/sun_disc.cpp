// Sun disc extraction: the baked E_ind must not hold the direct sun (it is added in real time), so the disc is cut
// out of the sky photo and its light measured as E_sun. The rules and thresholds are the contract documented on
// extractSunDisc() in gusuku_bake/sky_light.h.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/sky_light.h"

namespace gusuku::bake {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// A bright core wider than this is a cloud or a clipped overcast patch, not the sun (0.27 deg) with its glare.
constexpr double kMaxCoreRadiusDeg = 10.0;
// An HDR sun is many orders above its surroundings; 50x is far above any sky gradient.
constexpr double kHdrPeakToRingRatio = 50.0;
// A clipped sun only has to stand above its ring a little (LDR skies near the sun are bright).
constexpr double kClippedPeakToRingRatio = 1.25;
// Texels within this relative distance of the peak count as "at the maximum" (the flat top of a clipped sun:
// capped texels hold the same value, bit for bit or nearly).
constexpr double kFlatTopRelativeTolerance = 1e-6;
// At least this many texels at the maximum: a disc centred on a texel edge lights the two texels beside it
// equally, so two equal texels are no sign of clipping.
constexpr size_t kFlatTopMinTexels = 3;
// Rule (b) of `clipped`: measured luminance irradiance below this fraction of pi * ring median.
constexpr double kFaintIrradianceFraction = 0.01;
// Extra texels around the bright region (its soft, partly covered edge).
constexpr int kMarginTexels = 2;

double channelOf(float value) { return (std::isfinite(value) && value > 0.0f) ? double(value) : 0.0; }

glm::dvec3 radianceOf(const ImageRGBA& image, int x, int y) {
    const float* t = image.texel(x, y);
    return {channelOf(t[0]), channelOf(t[1]), channelOf(t[2])};
}

/// Texel geometry of one map: centre directions and solid angles.
struct MapGeometry {
    int width;
    int height;
    double north_azimuth_deg;
    double texel_deg;  // angular height of a row

    glm::dvec3 direction(int x, int y) const {
        return equirectDirection((x + 0.5) / width, (y + 0.5) / height, north_azimuth_deg);
    }
    double solidAngle(int y) const { return equirectTexelSolidAngle(y, width, height); }
    /// Rows that may hold a texel centre within radius_deg of `centre`.
    void rowRange(const glm::dvec3& centre, double radius_deg, int& y_first, int& y_last) const {
        const double polar_deg = std::acos(std::clamp(centre.z, -1.0, 1.0)) / kDegToRad;
        const double reach = radius_deg + texel_deg;
        y_first = std::max(0, int(std::floor((polar_deg - reach) / texel_deg)));
        y_last = std::min(height - 1, int(std::ceil((polar_deg + reach) / texel_deg)));
    }
};

double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) / kDegToRad;
}

/// A set of texels in a band of rows (the sun's neighbourhood), as a mask; the band keeps memory small on
/// large maps.
class TexelSet {
public:
    TexelSet(int width, int y_first, int y_last)
        : width_(width), y_first_(y_first), y_last_(y_last), mask_(size_t(width) * size_t(y_last - y_first + 1), 0) {}
    bool inBand(int y) const { return y >= y_first_ && y <= y_last_; }
    bool contains(int x, int y) const { return inBand(y) && mask_[index(x, y)] != 0; }
    void insert(int x, int y) {
        if (!contains(x, y)) {
            mask_[index(x, y)] = 1;
            members_.push_back({x, y});
        }
    }
    const std::vector<std::pair<int, int>>& members() const { return members_; }

private:
    size_t index(int x, int y) const { return size_t(y - y_first_) * size_t(width_) + size_t(x); }
    int width_, y_first_, y_last_;
    std::vector<unsigned char> mask_;
    std::vector<std::pair<int, int>> members_;
};

/// Connected set (8 neighbours, columns wrap) from the seed over texels passing `accept`, kept within
/// radius_deg of `centre`. `escaped` is set when an accepted neighbour lies beyond the radius.
template <typename Accept>
TexelSet growRegion(const ImageRGBA& image, const MapGeometry& geometry, int seed_x, int seed_y,
                    const glm::dvec3& centre, double radius_deg, Accept accept, bool* escaped = nullptr) {
    int y_first = 0, y_last = 0;
    geometry.rowRange(centre, radius_deg, y_first, y_last);
    TexelSet region(geometry.width, y_first, y_last);
    const double cos_radius = std::cos(radius_deg * kDegToRad);
    if (escaped) *escaped = false;
    region.insert(seed_x, seed_y);
    for (size_t next = 0; next < region.members().size(); ++next) {
        const auto [x0, y0] = region.members()[next];
        for (int dy = -1; dy <= 1; ++dy) {
            const int y = y0 + dy;
            if (y < 0 || y >= geometry.height) continue;
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = (x0 + dx + geometry.width) % geometry.width;
                if (region.contains(x, y) || !accept(x, y)) continue;
                if (!region.inBand(y) || glm::dot(geometry.direction(x, y), centre) < cos_radius) {
                    if (escaped) *escaped = true;
                    continue;
                }
                region.insert(x, y);
            }
        }
    }
    return region;
}

/// Adds every texel within `margin` columns/rows (Chebyshev, columns wrap) of the set, kept within
/// radius_deg of centre.
TexelSet dilate(const TexelSet& region, const MapGeometry& geometry, int margin, const glm::dvec3& centre,
                double radius_deg) {
    int y_first = 0, y_last = 0;
    geometry.rowRange(centre, radius_deg, y_first, y_last);
    TexelSet grown(geometry.width, y_first, y_last);
    const double cos_radius = std::cos(radius_deg * kDegToRad);
    for (const auto& [x0, y0] : region.members()) {
        for (int dy = -margin; dy <= margin; ++dy) {
            const int y = y0 + dy;
            if (y < 0 || y >= geometry.height || !grown.inBand(y)) continue;
            for (int dx = -margin; dx <= margin; ++dx) {
                const int x = ((x0 + dx) % geometry.width + geometry.width) % geometry.width;
                if (grown.contains(x, y)) continue;
                if (!(dx == 0 && dy == 0) && glm::dot(geometry.direction(x, y), centre) < cos_radius) continue;
                grown.insert(x, y);
            }
        }
    }
    return grown;
}

struct RingStatistics {
    bool empty = true;
    double median_luminance = 0.0;
    glm::dvec3 mean_radiance{0.0};
};

/// Texels whose centres lie between the two angular radii from `centre`.
RingStatistics ringStatistics(const ImageRGBA& image, const MapGeometry& geometry, const glm::dvec3& centre,
                              double inner_deg, double outer_deg) {
    int y_first = 0, y_last = 0;
    geometry.rowRange(centre, outer_deg, y_first, y_last);
    const double cos_inner = std::cos(inner_deg * kDegToRad);
    const double cos_outer = std::cos(outer_deg * kDegToRad);
    std::vector<double> luminances;
    glm::dvec3 sum(0.0);
    for (int y = y_first; y <= y_last; ++y) {
        for (int x = 0; x < geometry.width; ++x) {
            const double c = glm::dot(geometry.direction(x, y), centre);
            if (c > cos_inner || c < cos_outer) continue;
            const glm::dvec3 radiance = radianceOf(image, x, y);
            luminances.push_back(luminanceRec709(radiance));
            sum += radiance;
        }
    }
    RingStatistics ring;
    if (luminances.empty()) return ring;
    ring.empty = false;
    const auto middle = luminances.begin() + std::ptrdiff_t(luminances.size() / 2);
    std::nth_element(luminances.begin(), middle, luminances.end());
    ring.median_luminance = *middle;
    ring.mean_radiance = sum / double(luminances.size());
    return ring;
}

}  // namespace

double sunDiscSolidAngleSr() { return 2.0 * std::numbers::pi * (1.0 - std::cos(kSunDiscAngularRadiusDeg * kDegToRad)); }

SunDiscEstimate extractSunDisc(ImageRGBA& sky_in_out, double north_azimuth_in_image_deg) {
    const int width = sky_in_out.width;
    const int height = sky_in_out.height;
    if (width <= 0 || height <= 0)
        throw InputError("sky map", "size", "empty image (" + std::to_string(width) + " x " +
                                                std::to_string(height) + ")");
    if (sky_in_out.texels.size() != size_t(width) * size_t(height) * 4)
        throw InputError("sky map", "texels", "texel count does not match width * height * 4");
    if (!std::isfinite(north_azimuth_in_image_deg))
        throw InputError("sky map", "north_azimuth_in_image_deg", "not finite");

    const MapGeometry geometry{width, height, north_azimuth_in_image_deg, 180.0 / height};
    auto luminanceAt = [&](int x, int y) { return luminanceRec709(radianceOf(sky_in_out, x, y)); };

    SunDiscEstimate estimate;
    int peak_x = 0, peak_y = 0;
    double peak = -1.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double lum = luminanceAt(x, y);
            if (lum > peak) {
                peak = lum;
                peak_x = x;
                peak_y = y;
            }
        }
    estimate.peak_luminance = std::max(peak, 0.0);
    if (!(peak > 0.0)) return estimate;  // a black map has no sun
    const glm::dvec3 peak_direction = geometry.direction(peak_x, peak_y);

    // 1. The bright core places the ring; one wider than a sun's glare is no sun.
    bool core_escaped = false;
    const TexelSet core = growRegion(
        sky_in_out, geometry, peak_x, peak_y, peak_direction, kMaxCoreRadiusDeg,
        [&](int x, int y) { return luminanceAt(x, y) >= 0.5 * peak; }, &core_escaped);
    if (core_escaped) return estimate;
    double core_radius_deg = 0.0;
    for (const auto& [x, y] : core.members())
        core_radius_deg = std::max(core_radius_deg, angleDeg(geometry.direction(x, y), peak_direction));
    core_radius_deg += 0.71 * geometry.texel_deg;  // half a texel's diagonal: the core's far edge

    // 2. The ring around it: the background to compare with and to fill with.
    const double ring_step_deg = std::max(2.0, 3.0 * geometry.texel_deg);
    const double ring_inner_deg = core_radius_deg + ring_step_deg;
    const RingStatistics ring =
        ringStatistics(sky_in_out, geometry, peak_direction, ring_inner_deg, ring_inner_deg + ring_step_deg);
    if (ring.empty) return estimate;
    const double ring_median = ring.median_luminance;
    estimate.ring_median_luminance = ring_median;

    // 3. Flat top: texels at the maximum covering more than a whole sun disc.
    const TexelSet flat = growRegion(sky_in_out, geometry, peak_x, peak_y, peak_direction, kMaxCoreRadiusDeg,
                                     [&](int x, int y) {
                                         return luminanceAt(x, y) >= peak * (1.0 - kFlatTopRelativeTolerance);
                                     });
    double flat_solid_angle = 0.0;
    for (const auto& [x, y] : flat.members()) flat_solid_angle += geometry.solidAngle(y);
    const bool flat_top = flat.members().size() >= kFlatTopMinTexels && flat_solid_angle > sunDiscSolidAngleSr();

    const bool found = peak > kHdrPeakToRingRatio * ring_median ||
                       (flat_top && peak > kClippedPeakToRingRatio * ring_median);
    if (!found) return estimate;

    // 4. The region to remove: everything clearly above the background, inside the ring, plus a margin.
    const double threshold = ring_median + std::min(ring_median, 0.5 * (peak - ring_median));
    const TexelSet bright = growRegion(sky_in_out, geometry, peak_x, peak_y, peak_direction, ring_inner_deg,
                                       [&](int x, int y) { return luminanceAt(x, y) > threshold; });
    const TexelSet removed = dilate(bright, geometry, kMarginTexels, peak_direction, ring_inner_deg);

    // 5. Measure before overwriting: centroid of the excess luminance, then the excess irradiance.
    const glm::dvec3 fill = ring.mean_radiance;
    const double fill_luminance = luminanceRec709(fill);
    glm::dvec3 weighted_direction(0.0);
    for (const auto& [x, y] : removed.members()) {
        const double excess = std::max(0.0, luminanceAt(x, y) - fill_luminance);
        weighted_direction += excess * geometry.solidAngle(y) * geometry.direction(x, y);
    }
    const double weight_length = glm::length(weighted_direction);
    const glm::dvec3 centroid = weight_length > 0.0 ? weighted_direction / weight_length : peak_direction;

    glm::dvec3 irradiance(0.0);
    double radius_deg = 0.0;
    for (const auto& [x, y] : removed.members()) {
        const glm::dvec3 direction = geometry.direction(x, y);
        const double cosine = std::max(0.0, glm::dot(direction, centroid));
        irradiance += (radianceOf(sky_in_out, x, y) - fill) * geometry.solidAngle(y) * cosine;
        radius_deg = std::max(radius_deg, angleDeg(direction, centroid));
    }
    irradiance = glm::max(irradiance, glm::dvec3(0.0));

    for (const auto& [x, y] : removed.members()) {
        float* texel = sky_in_out.texel(x, y);
        texel[0] = float(fill.x);
        texel[1] = float(fill.y);
        texel[2] = float(fill.z);
    }

    estimate.found = true;
    estimate.direction_enu = centroid;
    estimate.irradiance_rgb = irradiance;
    estimate.clipped =
        flat_top || luminanceRec709(irradiance) < kFaintIrradianceFraction * std::numbers::pi * ring_median;
    estimate.texel_count = int(removed.members().size());
    estimate.angular_radius_deg = radius_deg;
    estimate.fill_radiance_rgb = fill;
    return estimate;
}

}  // namespace gusuku::bake
