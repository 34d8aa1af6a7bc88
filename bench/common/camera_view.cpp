// Camera placement for the tools (see camera_view.h).

#include "camera_view.h"

#include <stdexcept>

#include <glm/geometric.hpp>

namespace gusuku::bench_common {

CameraPose lookAtPose(const glm::dvec3& position, const glm::dvec3& target) {
    if (!(glm::length(target - position) > 1e-6)) throw std::invalid_argument("--look-at: the same point as --position");
    return CameraPose::lookingAt(position, target);
}

}  // namespace gusuku::bench_common
