// The preview's CPU rasteriser (cmd_preview_raster.h).
#include "cmd_preview_raster.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "gusuku/maths/equirect.h"

namespace gusuku::bake_cli {

namespace {

// Nearer than this (metres) a perspective camera cuts a triangle (its projection would blow up).
constexpr double kNearPlaneM = 0.05;
// Light from the sky on a face the sun does not reach, as a fraction of full sun: enough to read its shape.
constexpr double kAmbient = 0.3;

glm::dvec3 toCamera(const PreviewCamera& camera, const glm::dvec3& p) {
    const glm::dvec3 d = p - camera.eye;
    return {glm::dot(d, camera.right), glm::dot(d, camera.up), glm::dot(d, camera.forward)};
}

double srgbEncode(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double luminance(const float* texel) {
    const auto channel = [](float value) { return std::isfinite(value) && value > 0.0f ? double(value) : 0.0; };
    return 0.2126 * channel(texel[0]) + 0.7152 * channel(texel[1]) + 0.0722 * channel(texel[2]);
}

}  // namespace

PreviewCamera PreviewCamera::lookingAt(const glm::dvec3& eye, const glm::dvec3& target, double focal_pixels) {
    PreviewCamera camera;
    camera.eye = eye;
    camera.forward = glm::normalize(target - eye);
    glm::dvec3 right = glm::cross(camera.forward, glm::dvec3(0, 0, 1));
    if (glm::length(right) < 1e-6) right = {1, 0, 0};  // looking straight up or down
    camera.right = glm::normalize(right);
    camera.up = glm::cross(camera.right, camera.forward);
    camera.perspective = true;
    camera.pixels = focal_pixels;
    return camera;
}

PreviewCamera PreviewCamera::topDown(const glm::dvec3& centre, double pixels_per_metre) {
    PreviewCamera camera;
    camera.eye = centre;
    camera.right = {1, 0, 0};
    camera.up = {0, 1, 0};
    camera.forward = {0, 0, -1};
    camera.perspective = false;
    camera.pixels = pixels_per_metre;
    return camera;
}

PreviewCanvas::PreviewCanvas(int width, int height, const glm::vec3& background_linear)
    : width_(width), height_(height), colour_(size_t(width) * height, background_linear),
      nearness_(size_t(width) * height, -HUGE_VAL), drawn_(size_t(width) * height, 0) {}

bool PreviewCanvas::project(const PreviewCamera& camera, const glm::dvec3& p, glm::dvec3& pixel) const {
    const glm::dvec3 c = toCamera(camera, p);
    if (camera.perspective) {
        if (c.z < kNearPlaneM) return false;
        pixel = {0.5 * width_ + camera.pixels * c.x / c.z, 0.5 * height_ - camera.pixels * c.y / c.z, 1.0 / c.z};
    } else {
        pixel = {0.5 * width_ + camera.pixels * c.x, 0.5 * height_ - camera.pixels * c.y, -c.z};
    }
    return true;
}

void PreviewCanvas::drawSky(const PreviewCamera& camera, const ImageRGBA& sky, double north_azimuth_in_image_deg) {
    if (!camera.perspective || sky.width <= 0 || sky.height <= 0) return;
    // Exposure: the median luminance of the sky above the horizon at 0.35 of white, so the sun is one white spot.
    std::vector<double> upper;
    for (int y = 0; y < sky.height / 2; y += std::max(1, sky.height / 128))
        for (int x = 0; x < sky.width; x += std::max(1, sky.width / 256)) upper.push_back(luminance(sky.texel(x, y)));
    std::nth_element(upper.begin(), upper.begin() + upper.size() / 2, upper.end());
    const double median = upper[upper.size() / 2];
    const double exposure = median > 0.0 ? 0.35 / median : 1.0;
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t i = size_t(y) * width_ + x;
            if (drawn_[i]) continue;
            const glm::dvec3 direction = glm::normalize(camera.right * (x + 0.5 - 0.5 * width_) -
                                                        camera.up * (y + 0.5 - 0.5 * height_) +
                                                        camera.forward * camera.pixels);
            const glm::dvec2 uv = equirectCoordinates(direction, north_azimuth_in_image_deg);
            const int sx = std::clamp(int(uv.x * sky.width), 0, sky.width - 1);
            const int sy = std::clamp(int(uv.y * sky.height), 0, sky.height - 1);
            const float* texel = sky.texel(sx, sy);
            glm::vec3 colour;
            for (int c = 0; c < 3; ++c) {
                const double value = std::isfinite(texel[c]) ? std::max(0.0, double(texel[c]) * exposure) : 0.0;
                colour[c] = float(value / (1.0 + value));  // Reinhard: the sun stays white, the sky keeps its colour
            }
            colour_[i] = colour;
        }
}

void PreviewCanvas::fillTriangle(const glm::dvec3 (&p)[3], const glm::vec3& colour) {
    const double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    if (std::abs(area) < 1e-12) return;
    const int x0 = std::max(0, int(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
    const int x1 = std::min(width_ - 1, int(std::ceil(std::max({p[0].x, p[1].x, p[2].x}))));
    const int y0 = std::max(0, int(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
    const int y1 = std::min(height_ - 1, int(std::ceil(std::max({p[0].y, p[1].y, p[2].y}))));
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const double w0 = ((p[1].x - px) * (p[2].y - py) - (p[2].x - px) * (p[1].y - py)) / area;
            const double w1 = ((p[2].x - px) * (p[0].y - py) - (p[0].x - px) * (p[2].y - py)) / area;
            const double w2 = 1.0 - w0 - w1;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            const double nearness = w0 * p[0].z + w1 * p[1].z + w2 * p[2].z;
            const size_t i = size_t(y) * width_ + x;
            if (nearness <= nearness_[i]) continue;
            nearness_[i] = nearness;
            colour_[i] = colour;
            drawn_[i] = 1;
        }
}

void PreviewCanvas::drawMesh(const PreviewCamera& camera, const TriangleMesh& mesh, const glm::vec3& tint,
                             const glm::dvec3& sun_enu) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 corners[3] = {glm::dvec3(mesh.positions[mesh.indices[t]]),
                                       glm::dvec3(mesh.positions[mesh.indices[t + 1]]),
                                       glm::dvec3(mesh.positions[mesh.indices[t + 2]])};
        glm::dvec3 normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
        if (glm::length(normal) <= 0.0) continue;
        normal = glm::normalize(normal);
        const glm::dvec3 to_eye = camera.perspective ? camera.eye - corners[0] : -camera.forward;
        if (glm::dot(normal, to_eye) < 0.0) normal = -normal;
        const size_t material = t / 3 < mesh.triangle_material.size() ? mesh.triangle_material[t / 3] : 0;
        const glm::vec3 base = material < mesh.materials.size()
                                   ? glm::vec3(mesh.materials[material].base_color_factor)
                                   : glm::vec3(0.8f);
        const double light = kAmbient + (1.0 - kAmbient) * std::max(0.0, glm::dot(normal, sun_enu));
        const glm::vec3 colour = tint * base * float(light);
        // Cut by the near plane (perspective): the corners in front, with the crossings of the plane between.
        glm::dvec3 in_camera[3];
        for (int k = 0; k < 3; ++k) in_camera[k] = toCamera(camera, corners[k]);
        std::vector<glm::dvec3> polygon;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& a = in_camera[k];
            const glm::dvec3& b = in_camera[(k + 1) % 3];
            const bool a_in = !camera.perspective || a.z >= kNearPlaneM;
            const bool b_in = !camera.perspective || b.z >= kNearPlaneM;
            if (a_in) polygon.push_back(corners[k]);
            if (a_in != b_in) {
                const double s = (kNearPlaneM - a.z) / (b.z - a.z);
                polygon.push_back(corners[k] + s * (corners[(k + 1) % 3] - corners[k]));
            }
        }
        if (polygon.size() < 3) continue;
        glm::dvec3 pixels[8];
        bool visible = true;
        for (size_t k = 0; k < polygon.size(); ++k) visible = visible && project(camera, polygon[k], pixels[k]);
        if (!visible) continue;
        for (size_t k = 1; k + 1 < polygon.size(); ++k) {
            const glm::dvec3 fan[3] = {pixels[0], pixels[k], pixels[k + 1]};
            fillTriangle(fan, colour);
        }
    }
}

void PreviewCanvas::plot(int x, int y, const glm::vec3& colour, int thickness) {
    for (int dy = 0; dy < thickness; ++dy)
        for (int dx = 0; dx < thickness; ++dx) {
            const int px = x + dx - thickness / 2, py = y + dy - thickness / 2;
            if (px < 0 || py < 0 || px >= width_ || py >= height_) continue;
            colour_[size_t(py) * width_ + px] = colour;
        }
}

void PreviewCanvas::drawPixelLine(double x0, double y0, double x1, double y1, const glm::vec3& colour,
                                  int thickness) {
    const int steps = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    if (steps > 4 * (width_ + height_)) return;  // far off the picture: nothing of it to see worth the loop
    for (int s = 0; s <= steps; ++s) {
        const double t = double(s) / steps;
        plot(int(std::floor(x0 + t * (x1 - x0))), int(std::floor(y0 + t * (y1 - y0))), colour, thickness);
    }
}

void PreviewCanvas::drawLine(const PreviewCamera& camera, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::vec3& colour, int thickness) {
    glm::dvec3 from = a, to = b;
    if (camera.perspective) {
        const double za = toCamera(camera, a).z, zb = toCamera(camera, b).z;
        if (za < kNearPlaneM && zb < kNearPlaneM) return;
        if (za < kNearPlaneM) from = a + (kNearPlaneM - za) / (zb - za) * (b - a);
        if (zb < kNearPlaneM) to = b + (kNearPlaneM - zb) / (za - zb) * (a - b);
    }
    glm::dvec3 p, q;
    if (!project(camera, from, p) || !project(camera, to, q)) return;
    drawPixelLine(p.x, p.y, q.x, q.y, colour, thickness);
}

std::vector<uint8_t> PreviewCanvas::rgba8() const {
    std::vector<uint8_t> bytes(colour_.size() * 4);
    for (size_t i = 0; i < colour_.size(); ++i) {
        for (int c = 0; c < 3; ++c) bytes[4 * i + c] = uint8_t(std::lround(255.0 * srgbEncode(colour_[i][c])));
        bytes[4 * i + 3] = 255;
    }
    return bytes;
}

}  // namespace gusuku::bake_cli
