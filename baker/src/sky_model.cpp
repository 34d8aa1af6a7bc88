#include "gusuku_bake/sky_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"
#include "gusuku/maths/equirect.h"

namespace gusuku::bake {

namespace {

using std::numbers::pi;

// ISO 15469:2004 / CIE S 011/E:2003, the six gradation groups (a, b) and six indicatrix groups (c, d, e), and
// which pair each of the 15 sky types uses (Darula and Kittler 2002, Table 1).
constexpr std::array<std::array<double, 2>, 6> kGradationGroups{{
    {4.0, -0.70}, {1.1, -0.80}, {0.0, -1.00}, {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}}};
constexpr std::array<std::array<double, 3>, 6> kIndicatrixGroups{{
    {0.0, -1.0, 0.00}, {2.0, -1.5, 0.15}, {5.0, -2.5, 0.30}, {10.0, -3.0, 0.45}, {16.0, -3.0, 0.30},
    {24.0, -2.8, 0.15}}};
// (gradation group, indicatrix group), 1-based, for types 1..15.
constexpr std::array<std::array<int, 2>, 15> kTypeGroups{{
    {1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 1}, {3, 2}, {3, 3}, {3, 4}, {4, 2}, {4, 3}, {4, 4}, {5, 4}, {5, 5},
    {6, 5}, {6, 6}}};

double gradation(const CieSkyCoefficients& k, double cos_zenith) {
    // phi(90 deg) = 1: exp(b / cos Z) -> 0 as cos Z -> 0+ (b < 0 in every group).
    if (cos_zenith <= 0.0) return 1.0;
    return 1.0 + k.a * std::exp(k.b / cos_zenith);
}

double indicatrix(const CieSkyCoefficients& k, double scattering_angle) {
    const double cos_chi = std::cos(scattering_angle);
    return 1.0 + k.c * (std::exp(k.d * scattering_angle) - std::exp(k.d * pi / 2.0)) + k.e * cos_chi * cos_chi;
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
}

glm::dvec3 normalisedToUnitLuminance(const glm::dvec3& rgb) {
    const double luminance = luminanceRec709(rgb);
    if (!(luminance > 0.0)) throw std::invalid_argument("sky colour has no positive luminance");
    return rgb / luminance;
}

// Midpoint quadrature of relative_luminance(direction) * cos Z over the upper hemisphere.
template <typename RelativeLuminance>
double hemisphereCosineIntegral(const RelativeLuminance& relative_luminance, int zenith_steps) {
    const int azimuth_steps = 2 * zenith_steps;
    const double zenith_step = (pi / 2.0) / zenith_steps;
    const double azimuth_step = (2.0 * pi) / azimuth_steps;
    double integral = 0.0;
    for (int i = 0; i < zenith_steps; ++i) {
        const double zenith = (i + 0.5) * zenith_step;
        const double sin_z = std::sin(zenith), cos_z = std::cos(zenith);
        double ring = 0.0;
        for (int j = 0; j < azimuth_steps; ++j) {
            const double azimuth = (j + 0.5) * azimuth_step;
            ring += relative_luminance(glm::dvec3(sin_z * std::sin(azimuth), sin_z * std::cos(azimuth), cos_z));
        }
        integral += ring * cos_z * sin_z * zenith_step * azimuth_step;
    }
    return integral;
}

void setTexel(ImageRGBA& image, int x, int y, const glm::dvec3& rgb) {
    float* texel = image.texel(x, y);
    texel[0] = float(rgb.x);
    texel[1] = float(rgb.y);
    texel[2] = float(rgb.z);
    texel[3] = 1.0f;
}

void checkImageSize(int width, int height) {
    if (width < 8 || height < 4) throw std::invalid_argument("sky image size too small");
}

}  // namespace

CieSkyCoefficients cieSkyCoefficients(int sky_type) {
    if (sky_type < 1 || sky_type > 15)
        throw std::invalid_argument("CIE general sky type must be 1..15, got " + std::to_string(sky_type));
    const auto [gradation_group, indicatrix_group] = kTypeGroups[size_t(sky_type - 1)];
    const auto& ab = kGradationGroups[size_t(gradation_group - 1)];
    const auto& cde = kIndicatrixGroups[size_t(indicatrix_group - 1)];
    return {ab[0], ab[1], cde[0], cde[1], cde[2]};
}

double cieRelativeLuminance(const glm::dvec3& direction, const glm::dvec3& sun_direction, int sky_type) {
    if (direction.z <= 0.0) return 0.0;
    const CieSkyCoefficients k = cieSkyCoefficients(sky_type);
    const double sun_zenith = std::acos(std::clamp(sun_direction.z, -1.0, 1.0));
    const double numerator = indicatrix(k, angleBetween(direction, sun_direction)) * gradation(k, direction.z);
    const double denominator = indicatrix(k, sun_zenith) * gradation(k, 1.0);
    return numerator / denominator;
}

double overcastRelativeLuminance(const glm::dvec3& direction) {
    if (direction.z <= 0.0) return 0.0;
    return (1.0 + 2.0 * direction.z) / 3.0;
}

double cieDiffuseHorizontalPerZenith(const glm::dvec3& sun_direction, int sky_type, int zenith_steps) {
    cieSkyCoefficients(sky_type);  // validates the type once, before the loop
    return hemisphereCosineIntegral(
        [&](const glm::dvec3& d) { return cieRelativeLuminance(d, sun_direction, sky_type); }, zenith_steps);
}

double overcastDiffuseHorizontalPerZenith(int zenith_steps) {
    return hemisphereCosineIntegral([](const glm::dvec3& d) { return overcastRelativeLuminance(d); },
                                    zenith_steps);
}

ClearSkyModel::ClearSkyModel(const ClearSkySpec& spec) : spec_(spec) {
    const double length = glm::length(spec.sun_direction);
    if (!(length > 0.0)) throw std::invalid_argument("clear sky: sun direction is zero");
    spec_.sun_direction = spec.sun_direction / length;
    if (spec_.sun_direction.z < 0.0) throw std::invalid_argument("clear sky: the sun is below the horizon");
    if (!(spec.diffuse_horizontal_irradiance > 0.0) || !(spec.direct_normal_to_diffuse_horizontal >= 0.0))
        throw std::invalid_argument("clear sky: irradiances must be positive");
    spec_.zenith_colour = normalisedToUnitLuminance(spec.zenith_colour);
    spec_.horizon_colour = normalisedToUnitLuminance(spec.horizon_colour);
    spec_.sun_colour = normalisedToUnitLuminance(spec.sun_colour);
    spec_.ground_colour = normalisedToUnitLuminance(spec.ground_colour);
    zenith_luminance_ = spec.diffuse_horizontal_irradiance /
                        cieDiffuseHorizontalPerZenith(spec_.sun_direction, spec.cie_sky_type);
}

double ClearSkyModel::directNormalIrradiance() const {
    return spec_.diffuse_horizontal_irradiance * spec_.direct_normal_to_diffuse_horizontal;
}

double ClearSkyModel::sunDiscLuminance() const {
    const double disc_solid_angle = 2.0 * pi * (1.0 - std::cos(kSunAngularRadiusDeg * pi / 180.0));
    return directNormalIrradiance() / disc_solid_angle;
}

double ClearSkyModel::globalHorizontalIrradiance() const {
    return spec_.diffuse_horizontal_irradiance + directNormalIrradiance() * std::max(0.0, spec_.sun_direction.z);
}

double ClearSkyModel::groundLuminance() const {
    return spec_.ground_albedo * globalHorizontalIrradiance() / pi;
}

glm::dvec3 ClearSkyModel::radiance(const glm::dvec3& direction) const {
    if (direction.z <= 0.0) return spec_.ground_colour * groundLuminance();
    const double luminance =
        zenith_luminance_ * cieRelativeLuminance(direction, spec_.sun_direction, spec_.cie_sky_type);
    // Paler near the horizon, where the light has crossed more air; both colours have Y = 1, so the blend does
    // not change the luminance that the CIE distribution sets.
    const double towards_zenith = std::sqrt(direction.z);
    const glm::dvec3 colour = spec_.horizon_colour + (spec_.zenith_colour - spec_.horizon_colour) * towards_zenith;
    return colour * luminance;
}

ImageRGBA renderClearSky(const ClearSkySpec& spec, int width, int height, double north_azimuth_in_image_deg,
                         int sun_subsamples) {
    checkImageSize(width, height);
    if (sun_subsamples < 1) throw std::invalid_argument("sun_subsamples must be >= 1");
    const ClearSkyModel model(spec);
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 direction =
                equirectDirection((x + 0.5) / width, (y + 0.5) / height, north_azimuth_in_image_deg);
            setTexel(image, x, y, model.radiance(direction));
        }

    // The disc is 0.535 deg across, one or two texels: a texel's share of the direct irradiance is the solid
    // angle of the disc inside it, estimated with a grid of sub-texel points.
    const glm::dvec3 sun = model.spec().sun_direction;
    const double disc_radius = kSunAngularRadiusDeg * pi / 180.0;
    const double cos_disc_radius = std::cos(disc_radius);
    const double texel_height_angle = pi / height;
    const double candidate_angle = disc_radius + 2.0 * std::max(texel_height_angle, 2.0 * pi / width);
    const double sun_v = equirectCoordinates(sun, north_azimuth_in_image_deg).y;
    const int first_row = std::max(0, int(std::floor(sun_v * height - candidate_angle / texel_height_angle)) - 1);
    const int last_row =
        std::min(height - 1, int(std::ceil(sun_v * height + candidate_angle / texel_height_angle)) + 1);

    struct Covered {
        int x, y;
        double covered_solid_angle;
    };
    std::vector<Covered> covered;
    double total_covered = 0.0;
    for (int y = first_row; y <= last_row; ++y) {
        const double texel_solid_angle = equirectTexelSolidAngle(y, width, height);
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 centre =
                equirectDirection((x + 0.5) / width, (y + 0.5) / height, north_azimuth_in_image_deg);
            if (angleBetween(centre, sun) > candidate_angle) continue;
            int inside = 0;
            for (int sy = 0; sy < sun_subsamples; ++sy)
                for (int sx = 0; sx < sun_subsamples; ++sx) {
                    const glm::dvec3 point = equirectDirection((x + (sx + 0.5) / sun_subsamples) / width,
                                                               (y + (sy + 0.5) / sun_subsamples) / height,
                                                               north_azimuth_in_image_deg);
                    if (glm::dot(point, sun) >= cos_disc_radius) ++inside;
                }
            if (inside == 0) continue;
            const double fraction = double(inside) / double(sun_subsamples * sun_subsamples);
            covered.push_back({x, y, fraction * texel_solid_angle});
            total_covered += fraction * texel_solid_angle;
        }
    }
    if (covered.empty()) {
        // A disc smaller than the sub-sample spacing: give its energy to the texel holding its centre.
        const glm::dvec2 uv = equirectCoordinates(sun, north_azimuth_in_image_deg);
        const int x = std::min(width - 1, int(uv.x * width));
        const int y = std::min(height - 1, int(uv.y * height));
        const double solid_angle = equirectTexelSolidAngle(y, width, height);
        covered.push_back({x, y, solid_angle});
        total_covered = solid_angle;
    }
    // Extra radiance L_i with sum_i L_i * texel_solid_angle_i = DNI, each texel weighted by its covered part.
    const double direct_normal = model.directNormalIrradiance();
    for (const Covered& c : covered) {
        const double texel_solid_angle = equirectTexelSolidAngle(c.y, width, height);
        const double extra_luminance = direct_normal * (c.covered_solid_angle / total_covered) / texel_solid_angle;
        float* texel = image.texel(c.x, c.y);
        for (int channel = 0; channel < 3; ++channel)
            texel[channel] += float(model.spec().sun_colour[channel] * extra_luminance);
    }
    return image;
}

double overcastZenithLuminance(const OvercastSkySpec& spec) {
    // Integral of (1 + 2 cos Z) / 3 * cos Z over the hemisphere: 2 pi / 3 * (1/2 + 2/3) = 7 pi / 9.
    return spec.diffuse_horizontal_irradiance / (7.0 * pi / 9.0);
}

ImageRGBA renderOvercastSky(const OvercastSkySpec& spec, int width, int height,
                            double north_azimuth_in_image_deg) {
    checkImageSize(width, height);
    if (!(spec.diffuse_horizontal_irradiance > 0.0))
        throw std::invalid_argument("overcast sky: irradiance must be positive");
    const double zenith_luminance = overcastZenithLuminance(spec);
    const glm::dvec3 ground =
        normalisedToUnitLuminance(spec.ground_colour) * (spec.ground_albedo * spec.diffuse_horizontal_irradiance / pi);
    ImageRGBA image;
    image.width = width;
    image.height = height;
    image.texels.assign(size_t(width) * size_t(height) * 4, 0.0f);
    for (int y = 0; y < height; ++y) {
        // The overcast sky does not depend on azimuth: one value per row.
        const glm::dvec3 direction = equirectDirection(0.5 / width, (y + 0.5) / height, north_azimuth_in_image_deg);
        const glm::dvec3 rgb = direction.z > 0.0
                                   ? glm::dvec3(zenith_luminance * overcastRelativeLuminance(direction))
                                   : ground;
        for (int x = 0; x < width; ++x) setTexel(image, x, y, rgb);
    }
    return image;
}

}  // namespace gusuku::bake
