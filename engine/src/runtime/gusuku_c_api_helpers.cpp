// The C API's camera and weather helpers (gusuku.h): CameraPose::lookingAt, CameraIntrinsics::fromFieldOfView,
// Runtime::projectToPixel and Weather::estimatedFrom, each with its input checked here first so that bad input is
// a code and a one-line message naming the argument, and no exception crosses the boundary.
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "gusuku/runtime/gusuku.h"
#include "gusuku/runtime/runtime.h"
#include "gusuku_c_api_detail.h"
#include "gusuku_c_api_structs.h"
#include "runtime_camera.h"

namespace {

using gusuku::c_api_detail::fail;
using gusuku::c_api_detail::failFromCurrentException;

/// The runtime's own limit for a target this close to the position (runtime_camera.cpp's kMinLookDistanceM).
constexpr double kMinLookDistanceM = 1e-6;
/// Frame sides the helpers take: the largest image side any Vulkan device offers.
constexpr uint32_t kMaxSide = 65536;
/// Pixels the weather estimate takes (2^28: a 1 GiB RGBA8 frame); its two frame-sized arrays stay bounded.
constexpr uint64_t kMaxEstimatePixels = uint64_t(1) << 28;

gusuku_result failArgument(const char* function, const std::string& problem) noexcept {
    char text[GUSUKU_MESSAGE_CAPACITY];
    std::snprintf(text, sizeof text, "%s: %s", function, problem.c_str());
    return fail(GUSUKU_ERROR_INVALID_ARGUMENT, text);
}

/// "" or "NAME: not finite" / "NAME: is NULL" for a 3-vector argument.
std::string findVectorProblem(const double* vector, const char* name) {
    if (vector == nullptr) return std::string(name) + ": is NULL";
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(vector[i])) return std::string(name) + "[" + std::to_string(i) + "]: not finite";
    return {};
}

}  // namespace

extern "C" {

gusuku_result gusuku_pose_looking_at(const double position_enu[3], const double target_enu[3],
                                     gusuku_pose* out_pose) {
    const char* function = "gusuku_pose_looking_at";
    try {
        if (out_pose == nullptr) return failArgument(function, "out_pose: is NULL");
        std::string problem = findVectorProblem(position_enu, "position_enu");
        if (problem.empty()) problem = findVectorProblem(target_enu, "target_enu");
        if (!problem.empty()) return failArgument(function, problem);
        const glm::dvec3 position(position_enu[0], position_enu[1], position_enu[2]);
        const glm::dvec3 target(target_enu[0], target_enu[1], target_enu[2]);
        if (!(glm::length(target - position) > kMinLookDistanceM))
            return failArgument(function, "target_enu: within 1 um of position_enu, no direction to look in");
        *out_pose = gusuku::c_api_detail::convertPose(gusuku::CameraPose::lookingAt(position, target));
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

gusuku_result gusuku_intrinsics_from_field_of_view(uint32_t width, uint32_t height, double horizontal_fov_deg,
                                                   gusuku_intrinsics* out_intrinsics) {
    const char* function = "gusuku_intrinsics_from_field_of_view";
    try {
        if (out_intrinsics == nullptr) return failArgument(function, "out_intrinsics: is NULL");
        if (width == 0 || width > kMaxSide || height == 0 || height > kMaxSide)
            return failArgument(function, "width, height: " + std::to_string(width) + " x " +
                                              std::to_string(height) + " is outside [1, 65536] per side");
        if (!(horizontal_fov_deg > 0.0 && horizontal_fov_deg < 180.0))
            return failArgument(function, "horizontal_fov_deg: " + std::to_string(horizontal_fov_deg) +
                                              " is outside (0, 180)");
        const gusuku::CameraIntrinsics k = gusuku::CameraIntrinsics::fromFieldOfView(width, height, horizontal_fov_deg);
        *out_intrinsics = gusuku_intrinsics{k.fx, k.fy, k.cx, k.cy, k.width, k.height};
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

gusuku_result gusuku_project_to_pixel(const gusuku_intrinsics* intrinsics, const gusuku_pose* pose,
                                      const double point_enu[3], double out_pixel[2], int32_t* out_in_front) {
    const char* function = "gusuku_project_to_pixel";
    try {
        if (intrinsics == nullptr) return failArgument(function, "intrinsics: is NULL");
        if (pose == nullptr) return failArgument(function, "pose: is NULL");
        if (out_pixel == nullptr) return failArgument(function, "out_pixel: is NULL");
        if (out_in_front == nullptr) return failArgument(function, "out_in_front: is NULL");
        if (std::string problem = findVectorProblem(point_enu, "point_enu"); !problem.empty())
            return failArgument(function, problem);
        // The frame's own checks of intrinsics and pose; the rest of this stand-in frame is valid by construction.
        gusuku::FrameInput frame;
        frame.intrinsics = gusuku::c_api_detail::convertIntrinsics(*intrinsics);
        frame.pose = gusuku::c_api_detail::convertPose(*pose);
        const uint8_t any_pixel = 0;
        frame.camera_rgba8 = &any_pixel;
        if (std::optional<std::string> problem = gusuku::runtime_detail::findFrameProblem(
                frame, frame.intrinsics.width, frame.intrinsics.height))
            return failArgument(function, *problem);
        const std::optional<glm::dvec2> pixel = gusuku::Runtime::projectToPixel(
            frame.intrinsics, frame.pose, glm::dvec3(point_enu[0], point_enu[1], point_enu[2]));
        const double nan = std::numeric_limits<double>::quiet_NaN();
        out_pixel[0] = pixel ? pixel->x : nan;
        out_pixel[1] = pixel ? pixel->y : nan;
        *out_in_front = pixel ? 1 : 0;
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

gusuku_result gusuku_weather_estimate(const uint8_t* camera_rgba8, uint32_t width, uint32_t height,
                                      gusuku_weather* out_weather) {
    const char* function = "gusuku_weather_estimate";
    try {
        if (out_weather == nullptr) return failArgument(function, "out_weather: is NULL");
        if (camera_rgba8 == nullptr) return failArgument(function, "camera_rgba8: is NULL");
        if (width == 0 || height == 0 || uint64_t(width) * height > kMaxEstimatePixels)
            return failArgument(function, "width, height: " + std::to_string(width) + " x " +
                                              std::to_string(height) + ": must be non-zero, at most 2^28 pixels");
        out_weather->cloud_cover = gusuku::Weather::estimatedFrom(camera_rgba8, width, height).cloud_cover;
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

}  // extern "C"
