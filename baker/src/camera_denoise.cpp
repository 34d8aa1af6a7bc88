#include "gusuku_bake/camera_denoise.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>

#include "gusuku/maths/colour.h"

namespace gusuku::bake {

namespace {

// Edge-stop width: kNoiseMultiple / sqrt(samples). A camera frame's filter reaches across pixels, not texels:
// its blur shows sooner than a lightmap's, so it is narrower than lightmap_denoise.cpp's and runs two passes at
// most. Measured on the sunlit box of tests/test_camera_tracer.cpp (4 spp against 128 spp, RMS): raw 0.0291;
// relative sigma 0.1 / 0.25 / 0.5 with 2 passes 0.0173 / 0.0180 / 0.0191, with 3 passes 0.0176 / 0.0200 /
// 0.0209 (the lightmap's choice, 0.5 and 3 passes, was the worst).
constexpr float kNoiseMultiple = 0.4f;
// Below this albedo luminance the irradiance cannot be recovered from the radiance: the pixel is left raw.
constexpr float kMinAlbedoLuminance = 0.01f;

// What the filter works on, per pixel.
struct FilterPixel {
    bool filtered = false;     // a lit surface of usable albedo
    glm::vec3 irradiance{0.0f};  // (radiance - emission) / albedo: irradiance / pi
    glm::vec3 position{0.0f};  // first hit, ENU
    glm::vec3 normal{0.0f};
    float footprint_m = 0.0f;  // a pixel's width at the hit's distance
    float sun_share = 0.0f;    // max(0, n . s) where the sun is visible, else 0
};

float powerOfCosine(float cosine, float power) { return std::pow(std::max(0.0f, cosine), power); }

}  // namespace

CameraDenoiseOptions cameraDenoiseOptionsForSamples(uint32_t samples_per_pixel) {
    CameraDenoiseOptions options;
    const float noise_scale = 1.0f / std::sqrt(float(std::max(samples_per_pixel, 1u)));
    options.relative_luminance_sigma = std::clamp(kNoiseMultiple * noise_scale, 0.01f, 0.25f);
    options.iterations = samples_per_pixel <= 64 ? 2 : 1;
    return options;
}

ImageRGBA denoiseCameraFrame(const CameraRender& render, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                             const CameraDenoiseOptions& options) {
    const int width = render.radiance.width;
    const int height = render.radiance.height;
    if (render.guides.width != width || render.guides.height != height ||
        render.guides.texels.size() != size_t(width) * size_t(height) * 3 || width != int(intrinsics.width) ||
        height != int(intrinsics.height))
        throw std::invalid_argument("denoiseCameraFrame: radiance, guides and intrinsics differ in size");
    const size_t pixel_count = size_t(width) * size_t(height);
    const glm::dmat3 rotation = pose.camera_to_enu;
    const double focal = std::max(intrinsics.fx, intrinsics.fy);

    std::vector<FilterPixel> pixels(pixel_count);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t index = size_t(y) * size_t(width) + size_t(x);
            const glm::vec4& normal_distance = render.guides.normalDistance(x, y);
            const glm::vec4& albedo_lit = render.guides.albedoLit(x, y);
            const glm::vec3 albedo(albedo_lit);
            FilterPixel& pixel = pixels[index];
            pixel.filtered = normal_distance.w > 0.0f && albedo_lit.w > 0.0f &&
                             luminanceRec709(albedo) >= kMinAlbedoLuminance;
            if (!pixel.filtered) continue;
            const glm::dvec3 camera_direction((x + 0.5 - intrinsics.cx) / intrinsics.fx,
                                              (y + 0.5 - intrinsics.cy) / intrinsics.fy, 1.0);
            const double distance = normal_distance.w;
            pixel.position = glm::vec3(pose.position_enu + rotation * glm::normalize(camera_direction) * distance);
            pixel.normal = glm::vec3(normal_distance);
            // The centre ray's footprint: distance / focal at the image centre, a little more off axis (ignored).
            pixel.footprint_m = float(distance / focal);
            pixel.sun_share = render.guides.emissionSunShare(x, y).w;
            const glm::vec3 radiance(render.radiance.texel(x, y)[0], render.radiance.texel(x, y)[1],
                                     render.radiance.texel(x, y)[2]);
            const glm::vec3 emission(render.guides.emissionSunShare(x, y));
            pixel.irradiance = (radiance - emission) / glm::max(albedo, glm::vec3(1e-4f));
        }

    constexpr float kTap[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};
    const float inverse_sun_variance = 1.0f / (2.0f * options.sun_share_sigma * options.sun_share_sigma);
    const float inverse_colour_variance =
        1.0f / (2.0f * options.relative_luminance_sigma * options.relative_luminance_sigma);
    std::vector<glm::vec3> source(pixel_count), filtered(pixel_count);
    for (size_t i = 0; i < pixel_count; ++i) source[i] = pixels[i].irradiance;
    for (int iteration = 0; iteration < options.iterations; ++iteration) {
        const int step = 1 << iteration;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const size_t centre = size_t(y) * size_t(width) + size_t(x);
                const FilterPixel& p = pixels[centre];
                if (!p.filtered) continue;
                const float centre_luminance = luminanceRec709(source[centre]);
                const float plane_sigma = options.plane_distance_sigma_pixels * p.footprint_m * float(step);
                const float inverse_plane_variance = 1.0f / (2.0f * plane_sigma * plane_sigma);
                glm::vec3 weighted_sum(0.0f);
                float weight_sum = 0.0f;
                for (int j = 0; j < 5; ++j) {
                    const int qy = y + (j - 2) * step;
                    if (qy < 0 || qy >= height) continue;
                    for (int i = 0; i < 5; ++i) {
                        const int qx = x + (i - 2) * step;
                        if (qx < 0 || qx >= width) continue;
                        const size_t q_index = size_t(qy) * size_t(width) + size_t(qx);
                        const FilterPixel& q = pixels[q_index];
                        if (!q.filtered) continue;
                        const float off_plane = glm::dot(p.normal, q.position - p.position);
                        const float plane_weight = std::exp(-off_plane * off_plane * inverse_plane_variance);
                        const float normal_weight = powerOfCosine(glm::dot(p.normal, q.normal), options.normal_power);
                        const float luminance = luminanceRec709(source[q_index]);
                        const float relative = std::fabs(luminance - centre_luminance) /
                                               std::max(luminance + centre_luminance, 1e-12f);
                        const float colour_weight = std::exp(-relative * relative * inverse_colour_variance);
                        const float sun_difference = q.sun_share - p.sun_share;
                        const float sun_weight = std::exp(-sun_difference * sun_difference * inverse_sun_variance);
                        const float weight =
                            kTap[i] * kTap[j] * plane_weight * normal_weight * colour_weight * sun_weight;
                        weighted_sum += weight * source[q_index];
                        weight_sum += weight;
                    }
                }
                // The centre tap always contributes (weight 9/64), so weight_sum > 0.
                filtered[centre] = weighted_sum / weight_sum;
            }
        for (size_t i = 0; i < pixel_count; ++i)
            if (pixels[i].filtered) source[i] = filtered[i];
    }

    ImageRGBA result = render.radiance;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t index = size_t(y) * size_t(width) + size_t(x);
            if (!pixels[index].filtered) continue;
            const glm::vec3 radiance = glm::vec3(render.guides.albedoLit(x, y)) * source[index] +
                                       glm::vec3(render.guides.emissionSunShare(x, y));
            for (int channel = 0; channel < 3; ++channel) result.texel(x, y)[channel] = radiance[channel];
        }
    return result;
}

}  // namespace gusuku::bake
