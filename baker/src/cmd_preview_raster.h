#pragma once
// The preview's pictures (gusuku-bake preview): a small z-buffered rasteriser on the CPU, flat-shaded by the sun, so
// a placement can be seen in seconds on any machine, with or without a GPU.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "gusuku/maths/image_rgba.h"
#include "gusuku/maths/mesh.h"

namespace gusuku::bake_cli {

/// A camera in the site's ENU frame: orthographic (pixels per metre) or perspective (focal length in pixels).
struct PreviewCamera {
    glm::dvec3 eye{0.0};
    glm::dvec3 right{1, 0, 0}, up{0, 0, 1}, forward{0, 1, 0};  ///< unit, orthogonal
    bool perspective = true;
    double pixels = 500.0;  ///< focal length (perspective) or pixels per metre (orthographic)
    /// Looking from `eye` at `target`, the picture's up as near world up as it can be.
    static PreviewCamera lookingAt(const glm::dvec3& eye, const glm::dvec3& target, double focal_pixels);
    /// Straight down on `centre`, north up, `pixels_per_metre`.
    static PreviewCamera topDown(const glm::dvec3& centre, double pixels_per_metre);
};

class PreviewCanvas {
public:
    PreviewCanvas(int width, int height, const glm::vec3& background_linear);
    int width() const { return width_; }
    int height() const { return height_; }
    /// Each background pixel (nothing drawn yet) from the sky map in its direction, tone-mapped (perspective only).
    void drawSky(const PreviewCamera& camera, const ImageRGBA& sky, double north_azimuth_in_image_deg);
    /// The mesh's triangles, depth-tested, each flat-shaded: tint * its material's colour * (ambient + direct
    /// from `sun_enu`), both sides lit alike.
    void drawMesh(const PreviewCamera& camera, const TriangleMesh& mesh, const glm::vec3& tint,
                  const glm::dvec3& sun_enu);
    /// A line over everything drawn (not depth-tested), `thickness` pixels wide; parts behind the camera are cut.
    void drawLine(const PreviewCamera& camera, const glm::dvec3& a, const glm::dvec3& b, const glm::vec3& colour,
                  int thickness = 2);
    /// A line in pixel coordinates (overlays: the north arrow).
    void drawPixelLine(double x0, double y0, double x1, double y1, const glm::vec3& colour, int thickness = 2);
    /// sRGB-encoded RGBA8, row 0 at the top.
    std::vector<uint8_t> rgba8() const;

private:
    bool project(const PreviewCamera& camera, const glm::dvec3& p, glm::dvec3& pixel) const;
    void fillTriangle(const glm::dvec3 (&pixels)[3], const glm::vec3& colour);
    void plot(int x, int y, const glm::vec3& colour, int thickness);
    int width_, height_;
    std::vector<glm::vec3> colour_;
    std::vector<double> nearness_;  ///< larger is nearer: 1/depth (perspective) or -depth (orthographic)
    std::vector<uint8_t> drawn_;
};

}  // namespace gusuku::bake_cli
