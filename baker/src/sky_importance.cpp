// Sky importance-sampling tables and their CPU twins of shaders/include/sky_sampling.glsl.
// Every step here is mirrored line for line in the GLSL (same clamps, same search, same sin theta), so that a
// test can hold the two to each other; see the layout contract in gusuku_bake/sky_light.h.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"
#include "gusuku/formats/input_error.h"
#include "gusuku_bake/sky_light.h"

namespace gusuku::bake {

namespace {

using std::numbers::pi;
// The largest float below 1: xi == 1 would pick the last entry even when it has no mass.
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
// sin theta floor: keeps the pdf finite at the poles (a sample lands there with probability ~0).
constexpr double kMinSinTheta = 1e-7;

double sanitizedChannel(float value) { return (std::isfinite(value) && value > 0.0f) ? double(value) : 0.0; }

double luminanceOf(const float* rgba) {
    return luminanceRec709(glm::dvec3(sanitizedChannel(rgba[0]), sanitizedChannel(rgba[1]), sanitizedChannel(rgba[2])));
}

size_t marginalOffset() { return kSkyTableHeaderFloats; }
size_t conditionalOffset(const SkySamplingTables& tables, int row) {
    return kSkyTableHeaderFloats + size_t(tables.height) + 1 + size_t(row) * (size_t(tables.width) + 1);
}
// The guide tables follow the last row's conditional CDF (layout in sky_light.h).
size_t marginalGuideOffset(const SkySamplingTables& tables) { return conditionalOffset(tables, tables.height); }
size_t conditionalGuideOffset(const SkySamplingTables& tables, int row) {
    return marginalGuideOffset(tables) + size_t(skyGuideCells(tables.height)) + 1 +
           size_t(row) * (size_t(skyGuideCells(tables.width)) + 1);
}
size_t tableFloats(const SkySamplingTables& tables) { return conditionalGuideOffset(tables, tables.height); }

/// Largest i in [0, n-1] with cdf[i] <= xi (cdf has n + 1 entries), searched in [guide[k], guide[k + 1]] for
/// k = floor(xi * cells): the guide's entries are that same answer at k / cells and (k + 1) / cells, and the
/// answer grows with xi, so it lies between them. Same loop as skyFindInterval() in GLSL.
int findInterval(const float* cdf, const float* guide, int cells, float xi) {
    const int cell = std::min(int(xi * float(cells)), cells - 1);
    int lo = int(guide[cell]);
    int hi = int(guide[cell + 1]);
    while (lo < hi) {
        const int mid = (lo + hi + 1) / 2;
        if (cdf[mid] <= xi)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

void checkTables(const SkySamplingTables& tables) {
    if (tables.width <= 0 || tables.height <= 0 ||
        tables.table.size() != tableFloats(tables) ||
        tables.radiance_rgba.size() != size_t(tables.width) * size_t(tables.height) * 4)
        throw std::invalid_argument("SkySamplingTables: sizes do not match width and height");
}

struct TexelIndex {
    int x;
    int y;
    double sin_theta;
};

/// Texel containing a direction, as skyTexelOf() in GLSL.
TexelIndex texelOf(const SkySamplingTables& tables, const glm::dvec3& direction_enu) {
    const double horizontal = std::hypot(direction_enu.x, direction_enu.y);
    const double length = std::sqrt(horizontal * horizontal + direction_enu.z * direction_enu.z);
    const double theta = length > 0.0 ? std::atan2(horizontal, direction_enu.z) : 0.0;
    const double azimuth_rad = horizontal > 0.0 ? std::atan2(direction_enu.x, direction_enu.y) : 0.0;
    double u = (azimuth_rad * 180.0 / pi + double(tables.north_azimuth_in_image_deg)) / 360.0;
    u -= std::floor(u);
    const double v = theta / pi;
    TexelIndex index;
    index.x = std::clamp(int(u * tables.width), 0, tables.width - 1);
    index.y = std::clamp(int(v * tables.height), 0, tables.height - 1);
    index.sin_theta = length > 0.0 ? horizontal / length : 0.0;
    return index;
}

/// p(u, v) over the unit square for texel (x, y), from the CDFs alone.
double unitSquareDensity(const SkySamplingTables& tables, int x, int y) {
    const float* marginal = tables.table.data() + marginalOffset();
    const float* conditional = tables.table.data() + conditionalOffset(tables, y);
    const double row_probability = double(marginal[y + 1]) - double(marginal[y]);
    const double column_probability = double(conditional[x + 1]) - double(conditional[x]);
    return row_probability * tables.height * column_probability * tables.width;
}

double solidAnglePdf(double unit_square_density, double sin_theta) {
    return unit_square_density / (2.0 * pi * pi * std::max(sin_theta, kMinSinTheta));
}

/// Writes a CDF of n + 1 entries from n non-negative weights; uniform when they sum to 0. Sums in double, then
/// rounds to float (rounding keeps it non-decreasing); the last entry is exactly 1.
void writeCdf(const std::vector<double>& weights, float* cdf) {
    const int n = int(weights.size());
    double total = 0.0;
    for (double w : weights) total += w;
    cdf[0] = 0.0f;
    if (!(total > 0.0) || !std::isfinite(total)) {
        for (int i = 1; i <= n; ++i) cdf[i] = float(double(i) / double(n));
    } else {
        double running = 0.0;
        for (int i = 1; i <= n; ++i) {
            running += weights[size_t(i - 1)];
            cdf[i] = float(std::min(1.0, running / total));
        }
    }
    cdf[n] = 1.0f;
}

/// Writes the guide of a CDF of n intervals: cells + 1 entries, entry k the largest i in [0, n-1] with
/// cdf[i] <= k / cells (compared in float: k / cells is exact for a power-of-two cells below 2^24).
void writeGuide(const float* cdf, int n, int cells, float* guide) {
    int interval = 0;
    for (int k = 0; k <= cells; ++k) {
        const float xi = float(k) / float(cells);
        while (interval + 1 <= n - 1 && cdf[interval + 1] <= xi) ++interval;
        guide[k] = float(interval);
    }
}

}  // namespace

int skyGuideCells(int intervals) {
    int cells = 1;
    while (cells < intervals) cells *= 2;
    return cells;
}

SkySamplingTables buildSkySamplingTables(const ImageRGBA& sky_without_sun, double north_azimuth_in_image_deg) {
    const int width = sky_without_sun.width;
    const int height = sky_without_sun.height;
    if (width <= 0 || height <= 0)
        throw InputError("sky map", "size", "empty image (" + std::to_string(width) + " x " +
                                                std::to_string(height) + ")");
    if (width > (1 << 24) || height > (1 << 24))
        throw InputError("sky map", "size", "more than 2^24 texels per side");
    if (sky_without_sun.texels.size() != size_t(width) * size_t(height) * 4)
        throw InputError("sky map", "texels", "texel count does not match width * height * 4");
    if (!std::isfinite(north_azimuth_in_image_deg))
        throw InputError("sky map", "north_azimuth_in_image_deg", "not finite");

    SkySamplingTables tables;
    tables.width = width;
    tables.height = height;
    tables.north_azimuth_in_image_deg = float(north_azimuth_in_image_deg);
    tables.radiance_rgba.resize(sky_without_sun.texels.size());
    for (size_t i = 0; i < sky_without_sun.texels.size(); ++i)
        tables.radiance_rgba[i] = float(sanitizedChannel(sky_without_sun.texels[i]));

    std::vector<double> luminance(static_cast<size_t>(width) * static_cast<size_t>(height));
    double integral = 0.0;
    double any_luminance = 0.0;
    for (int y = 0; y < height; ++y) {
        const double texel_solid_angle = equirectTexelSolidAngle(y, width, height);
        for (int x = 0; x < width; ++x) {
            const double lum = luminanceOf(sky_without_sun.texel(x, y));
            luminance[size_t(y) * size_t(width) + size_t(x)] = lum;
            integral += lum * texel_solid_angle;
            any_luminance += lum;
        }
    }
    // A black (or all-invalid) map: sample uniformly over the sphere rather than divide by zero.
    const bool uniform_fallback = !(any_luminance > 0.0) || !std::isfinite(any_luminance);
    if (uniform_fallback) std::fill(luminance.begin(), luminance.end(), 1.0);

    tables.table.assign(tableFloats(tables), 0.0f);
    tables.table[0] = float(width);
    tables.table[1] = float(height);
    tables.table[2] = float(north_azimuth_in_image_deg);
    tables.table[3] = uniform_fallback ? 0.0f : float(integral);

    std::vector<double> row_weights(static_cast<size_t>(height));
    std::vector<double> column_weights(static_cast<size_t>(width));
    for (int y = 0; y < height; ++y) {
        const double sin_theta = std::sin((double(y) + 0.5) / double(height) * pi);
        double row_sum = 0.0;
        for (int x = 0; x < width; ++x) {
            column_weights[size_t(x)] = luminance[size_t(y) * size_t(width) + size_t(x)];
            row_sum += column_weights[size_t(x)];
        }
        row_weights[size_t(y)] = row_sum * sin_theta;
        writeCdf(column_weights, tables.table.data() + conditionalOffset(tables, y));
    }
    writeCdf(row_weights, tables.table.data() + marginalOffset());

    const int row_cells = skyGuideCells(height);
    const int column_cells = skyGuideCells(width);
    const float* marginal = tables.table.data() + marginalOffset();
    writeGuide(marginal, height, row_cells, tables.table.data() + marginalGuideOffset(tables));
    for (int y = 0; y < height; ++y) {
        const float* conditional = tables.table.data() + conditionalOffset(tables, y);
        writeGuide(conditional, width, column_cells, tables.table.data() + conditionalGuideOffset(tables, y));
        // The texel's density in its fourth float, in float and in the GPU's order of operations (sky_light.h).
        const float row_probability = marginal[y + 1] - marginal[y];
        for (int x = 0; x < width; ++x) {
            const float column_probability = conditional[x + 1] - conditional[x];
            tables.radiance_rgba[(size_t(y) * size_t(width) + size_t(x)) * 4 + 3] =
                row_probability * float(height) * column_probability * float(width);
        }
    }
    tables.cosine_relative_variance = skyCosineRelativeVariance(sky_without_sun, north_azimuth_in_image_deg);
    return tables;
}

double skyCosineRelativeVariance(const ImageRGBA& sky_without_sun, double north_azimuth_in_image_deg) {
    const int width = sky_without_sun.width, height = sky_without_sun.height;
    if (width <= 0 || height <= 0 || sky_without_sun.texels.size() != size_t(width) * size_t(height) * 4) return 0.0;
    constexpr int kPlanes = 5;
    const glm::dvec3 normals[kPlanes] = {{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, -1.0, 0.0},
                                         {-1.0, 0.0, 0.0}};
    // The texel directions are separable: (cos(elevation) * horizontal(column), sin(elevation)(row)), so the
    // trigonometry is done once per column and once per row, not per texel.
    std::vector<glm::dvec3> column_horizontal(static_cast<size_t>(width));
    for (int x = 0; x < width; ++x)
        column_horizontal[size_t(x)] = equirectDirection((x + 0.5) / width, 0.5, north_azimuth_in_image_deg);
    // Per plane, the integrals of L cos and L^2 cos over its hemisphere.
    double first_moment[kPlanes] = {}, second_moment[kPlanes] = {};
    for (int y = 0; y < height; ++y) {
        const double texel_solid_angle = equirectTexelSolidAngle(y, width, height);
        const double sin_elevation = equirectDirection(0.0, (y + 0.5) / height, 0.0).z;
        const double cos_elevation = std::sqrt(std::max(0.0, 1.0 - sin_elevation * sin_elevation));
        for (int x = 0; x < width; ++x) {
            const double luminance = luminanceOf(sky_without_sun.texel(x, y));
            if (luminance <= 0.0) continue;
            const glm::dvec3 direction(cos_elevation * column_horizontal[size_t(x)].x,
                                       cos_elevation * column_horizontal[size_t(x)].y, sin_elevation);
            for (int plane = 0; plane < kPlanes; ++plane) {
                const double cosine = glm::dot(normals[plane], direction);
                if (cosine <= 0.0) continue;
                first_moment[plane] += luminance * cosine * texel_solid_angle;
                second_moment[plane] += luminance * luminance * cosine * texel_solid_angle;
            }
        }
    }
    double largest = 0.0;
    for (int plane = 0; plane < kPlanes; ++plane)
        if (first_moment[plane] > 0.0)
            largest = std::max(largest, pi * second_moment[plane] / (first_moment[plane] * first_moment[plane]) - 1.0);
    return largest;
}

SkySample sampleSkyCpu(const SkySamplingTables& tables, float xi1, float xi2) {
    checkTables(tables);
    xi1 = std::clamp(xi1, 0.0f, kOneMinusEpsilon);
    xi2 = std::clamp(xi2, 0.0f, kOneMinusEpsilon);
    const float* marginal = tables.table.data() + marginalOffset();
    const int y = findInterval(marginal, tables.table.data() + marginalGuideOffset(tables),
                               skyGuideCells(tables.height), xi1);
    const float* conditional = tables.table.data() + conditionalOffset(tables, y);
    const int x = findInterval(conditional, tables.table.data() + conditionalGuideOffset(tables, y),
                               skyGuideCells(tables.width), xi2);

    const double row_fraction = (double(xi1) - double(marginal[y])) / (double(marginal[y + 1]) - double(marginal[y]));
    const double column_fraction =
        (double(xi2) - double(conditional[x])) / (double(conditional[x + 1]) - double(conditional[x]));
    const double u = (double(x) + column_fraction) / double(tables.width);
    const double v = (double(y) + row_fraction) / double(tables.height);

    SkySample sample;
    sample.direction_enu = equirectDirection(u, v, double(tables.north_azimuth_in_image_deg));
    // sin theta from the distance to the nearer pole, measured as the GLSL does (float precision at the poles).
    const double v_from_pole =
        (2 * y + 1 < tables.height)
            ? v
            : (double(tables.height - 1 - y) + (double(marginal[y + 1]) - double(xi1)) /
                                                    (double(marginal[y + 1]) - double(marginal[y]))) /
                  double(tables.height);
    const double sin_theta = std::sin(pi * v_from_pole);
    sample.pdf_solid_angle = solidAnglePdf(unitSquareDensity(tables, x, y), sin_theta);
    return sample;
}

SkyRows skyRowsFacingCpu(const SkySamplingTables& tables, const glm::dvec3& unit_normal) {
    checkTables(tables);
    const double v_normal = std::acos(std::clamp(unit_normal.z, -1.0, 1.0)) / pi;
    const int first = int(std::floor((v_normal - 0.5) * tables.height)) - 1;
    const int last = int(std::floor((v_normal + 0.5) * tables.height)) + 1;
    return {std::clamp(first, 0, tables.height - 1), std::clamp(last, 0, tables.height - 1)};
}

float skyRowsProbabilityCpu(const SkySamplingTables& tables, SkyRows rows) {
    checkTables(tables);
    if (rows.first > rows.last) return 0.0f;
    if (rows.first < 0 || rows.last >= tables.height)
        throw std::invalid_argument("skyRowsProbabilityCpu: rows outside the map");
    const float* marginal = tables.table.data() + marginalOffset();
    return marginal[rows.last + 1] - marginal[rows.first];
}

SkySample sampleSkyInRowsCpu(const SkySamplingTables& tables, SkyRows rows, float xi1, float xi2) {
    const float probability = skyRowsProbabilityCpu(tables, rows);
    if (!(probability > 0.0f)) return SkySample{{0.0, 0.0, 1.0}, 0.0};
    const float* marginal = tables.table.data() + marginalOffset();
    const float low = marginal[rows.first];
    const float high = marginal[rows.last + 1];
    const float row_xi = std::min(low + std::clamp(xi1, 0.0f, 1.0f) * probability, std::nextafter(high, 0.0f));
    SkySample sample = sampleSkyCpu(tables, row_xi, xi2);
    sample.pdf_solid_angle /= double(probability);
    return sample;
}

double skyPdfCpu(const SkySamplingTables& tables, const glm::dvec3& direction_enu) {
    checkTables(tables);
    const TexelIndex index = texelOf(tables, direction_enu);
    return solidAnglePdf(unitSquareDensity(tables, index.x, index.y), index.sin_theta);
}

glm::dvec3 skyRadianceCpu(const SkySamplingTables& tables, const glm::dvec3& direction_enu) {
    checkTables(tables);
    const TexelIndex index = texelOf(tables, direction_enu);
    const float* rgba = tables.radiance_rgba.data() + (size_t(index.y) * size_t(tables.width) + size_t(index.x)) * 4;
    return {rgba[0], rgba[1], rgba[2]};
}

}  // namespace gusuku::bake
