// The C API's camera and weather helpers (gusuku.h): CameraPose::lookingAt, CameraIntrinsics::fromFieldOfView,
// Runtime::projectToPixel and Weather::estimatedFrom, each with its input checked here first so that bad input is
// a code and a one-line message naming the argument, and no exception crosses the boundary. Each result is checked
// too: finite input can still overflow a double on the way (a focal length of inf from a denormal field of view,
// a pixel of inf for a point just beside the camera's plane), and GUSUKU_OK never comes with a NaN or an inf.
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

/// A number for a message: %g shows 1e-320 and 1e308 as they are (std::to_string writes "0.000000").
std::string formatNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

bool allFinite(const double* values, int count) {
    for (int i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) return false;
    return true;
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
        const glm::dvec3 offset = target - position;
        if (!(std::isfinite(offset.x) && std::isfinite(offset.y) && std::isfinite(offset.z)))
            return failArgument(function, "target_enu: its offset from position_enu overflows a double "
                                          "(coordinates of opposite sign near 1.8e308)");
        if (!(glm::length(offset) > kMinLookDistanceM))
            return failArgument(function, "target_enu: within 1 um of position_enu, no direction to look in");
        const gusuku_pose pose = gusuku::c_api_detail::convertPose(gusuku::CameraPose::lookingAt(position, target));
        if (!allFinite(pose.camera_to_enu, 9) || !allFinite(pose.position_enu, 3))
            return failArgument(function, "target_enu: gives a rotation that is not finite");
        *out_pose = pose;
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
            return failArgument(function, "horizontal_fov_deg: " + formatNumber(horizontal_fov_deg) +
                                              " is outside (0, 180)");
        const gusuku::CameraIntrinsics k = gusuku::CameraIntrinsics::fromFieldOfView(width, height, horizontal_fov_deg);
        // A field of view of a denormal's size has a tangent so small that the focal length overflows.
        if (!(std::isfinite(k.fx) && std::isfinite(k.fy) && k.fx > 0.0 && k.fy > 0.0))
            return failArgument(function, "horizontal_fov_deg: " + formatNumber(horizontal_fov_deg) +
                                              " gives a focal length of " + formatNumber(k.fx) +
                                              " pixels, not a finite positive number");
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
        const glm::dvec3 point(point_enu[0], point_enu[1], point_enu[2]);
        const glm::dvec3 offset = point - frame.pose.position_enu;
        if (!(std::isfinite(offset.x) && std::isfinite(offset.y) && std::isfinite(offset.z)))
            return failArgument(function, "point_enu: its offset from pose.position_enu overflows a double "
                                          "(coordinates of opposite sign near 1.8e308)");
        const std::optional<glm::dvec2> pixel = gusuku::Runtime::projectToPixel(frame.intrinsics, frame.pose, point);
        // A point in front but nearly in the camera's plane (camera z tiny beside x or y) lands beyond any double.
        if (pixel && !(std::isfinite(pixel->x) && std::isfinite(pixel->y)))
            return failArgument(function, "point_enu: lands at pixel (" + formatNumber(pixel->x) + ", " +
                                              formatNumber(pixel->y) + "), beyond a double (a point nearly in the "
                                              "camera's plane, or intrinsics near 1e308)");
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
        const float cloud_cover = gusuku::Weather::estimatedFrom(camera_rgba8, width, height).cloud_cover;
        // Bytes in cannot make a NaN, but GUSUKU_OK promises a cover in [0, 1]: held to it here.
        if (!(cloud_cover >= 0.0f && cloud_cover <= 1.0f))
            return failArgument(function, "camera_rgba8: gives a cloud cover of " + formatNumber(cloud_cover) +
                                              ", outside [0, 1]");
        out_weather->cloud_cover = cloud_cover;
        return GUSUKU_OK;
    } catch (...) {
        return failFromCurrentException(function);
    }
}

}  // extern "C"
