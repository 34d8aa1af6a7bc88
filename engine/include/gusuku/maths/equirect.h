#pragma once
// The equirectangular convention for sky maps (docs/design.md 2): row 0 is the zenith, the bottom row the nadir.
// u in [0, 1) runs from the left edge; the column at 360 * u = north_azimuth_in_image_deg faces north, and
// azimuth (east of north) grows with u: azimuth = 360 * u - north_azimuth_in_image_deg.
// v in [0, 1] runs from the top: elevation = 90 - 180 * v degrees.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace gusuku {

/// Unit ENU direction of image coordinates (u, v), both in [0, 1] (texel centres at (x + 0.5) / width).
glm::dvec3 equirectDirection(double u, double v, double north_azimuth_in_image_deg);

/// Image coordinates (u in [0, 1), v in [0, 1]) of a unit ENU direction.
glm::dvec2 equirectCoordinates(const glm::dvec3& direction_enu, double north_azimuth_in_image_deg);

/// Solid angle of texel row y of an equirect map of the given size: (2 pi / w) * (pi / h) * sin(theta_y),
/// theta_y the polar angle of the row centre. Sums to 4 pi over the whole map.
double equirectTexelSolidAngle(int y, int width, int height);

}  // namespace gusuku
