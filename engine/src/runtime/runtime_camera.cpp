// The camera convention of runtime.h (projection of ENU points to pixels, the matching Vulkan clip matrix, the
// placement helpers), the frame input's checks, and the weather read off a camera frame.

#include "runtime_camera.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include <glm/matrix.hpp>

#include "gusuku/runtime/runtime.h"
#include "gusuku/maths/weather_estimate.h"

namespace gusuku {
namespace {

// lookingAt: a target nearer than this to the position gives no direction to look in.
constexpr double kMinLookDistanceM = 1e-6;
// lookingAt: a view this close to straight up or down (|forward . up| above it) takes north as its up instead, so
// the right axis, forward x up, stays well defined.
constexpr double kNearlyVertical = 0.999;
// A pose's rotation counts as orthonormal when R^T R is this close to the identity, element by element: loose
// enough for a rotation built in float from sensor quaternions.
constexpr double kRotationTolerance = 1e-3;
// A GPS fix's height above the ellipsoid is refused beyond 100 km either way (no site on the ground lies there).
constexpr double kMaxFixHeightM = 1e5;

// `offset` scaled by a power of two so that its largest component lies in [1, 2): exact (barring underflow of
// components far smaller than the largest), so directions and ratios such as X / Z are unchanged, while lengths
// and products of it stay far from a double's overflow (a finite offset of 1e308 has a length of inf).
glm::dvec3 scaledByPowerOfTwo(const glm::dvec3& offset) {
    const double largest = std::max({std::abs(offset.x), std::abs(offset.y), std::abs(offset.z)});
    if (!(largest > 0.0) || !std::isfinite(largest)) return offset;
    const int exponent = std::ilogb(largest);
    return {std::scalbn(offset.x, -exponent), std::scalbn(offset.y, -exponent), std::scalbn(offset.z, -exponent)};
}

}  // namespace

Weather Weather::estimatedFrom(const uint8_t* camera_rgba8, uint32_t width, uint32_t height) {
    try {
        return {estimateCloudCover(camera_rgba8, width, height).cloud_cover};
    } catch (const RuntimeError&) {
        throw;
    } catch (const std::bad_alloc&) {  // its two frame-sized arrays: host memory, not the frame, is short
        throw RuntimeError(RuntimeErrorCode::kOutOfMemory, "Weather::estimatedFrom: out of host memory");
    } catch (const std::exception& error) {  // the runtime's one error family (runtime.h)
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, std::string("Weather::estimatedFrom: ") + error.what());
    }
}

CameraIntrinsics CameraIntrinsics::fromFieldOfView(uint32_t width, uint32_t height, double horizontal_fov_deg) {
    if (width == 0 || height == 0 || !(horizontal_fov_deg > 0.0 && horizontal_fov_deg < 180.0))
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame,
                           "CameraIntrinsics::fromFieldOfView: needs a non-empty frame and a field of view in (0, "
                           "180) degrees, got " + std::to_string(width) + " x " + std::to_string(height) + " and " +
                               std::to_string(horizontal_fov_deg));
    const double focal = 0.5 * double(width) / std::tan(0.5 * horizontal_fov_deg * std::numbers::pi / 180.0);
    return {focal, focal, 0.5 * width, 0.5 * height, width, height};
}

CameraPose CameraPose::lookingAt(const glm::dvec3& position_enu, const glm::dvec3& target_enu) {
    const glm::dvec3 offset = target_enu - position_enu;
    if (!(glm::length(offset) > kMinLookDistanceM))
        throw RuntimeError(RuntimeErrorCode::kInvalidFrame, "CameraPose::lookingAt: the target is the position");
    const glm::dvec3 forward = glm::normalize(scaledByPowerOfTwo(offset));  // no overflow of its length
    const glm::dvec3 world_up = std::abs(forward.z) > kNearlyVertical ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, world_up));
    CameraPose pose;
    pose.position_enu = position_enu;
    pose.camera_to_enu = glm::dmat3(right, glm::cross(forward, right), forward);  // right, down, forward
    return pose;
}

std::optional<glm::dvec2> Runtime::projectToPixel(const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                                  const glm::dvec3& point_enu) {
    // camera_to_enu is orthonormal, so its transpose takes ENU offsets into the camera frame. The pixel depends on
    // the offset's direction only, so it is scaled first: a far point's rotated offset cannot overflow.
    const glm::dvec3 camera = glm::transpose(pose.camera_to_enu) * scaledByPowerOfTwo(point_enu - pose.position_enu);
    if (!(camera.z > 0.0)) return std::nullopt;
    return glm::dvec2(intrinsics.fx * camera.x / camera.z + intrinsics.cx,
                      intrinsics.fy * camera.y / camera.z + intrinsics.cy);
}

namespace runtime_detail {

glm::dmat4 cameraEnuToClip(const CameraIntrinsics& intrinsics, const CameraPose& pose, double near_m, double far_m) {
    // ENU -> camera (x right, y down, z forward).
    const glm::dmat3 enu_to_camera = glm::transpose(pose.camera_to_enu);
    glm::dmat4 view(1.0);
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) view[column][row] = enu_to_camera[column][row];
    const glm::dvec3 translation = -(enu_to_camera * pose.position_enu);
    view[3] = glm::dvec4(translation, 1.0);

    // Camera -> clip: x_ndc = 2 u / W - 1 with u = fx X / Z + cx (Vulkan's y also points down, so rows map
    // straight), depth z_ndc = far (Z - near) / (Z (far - near)) in [0, 1], w = Z.
    const double width = double(intrinsics.width), height = double(intrinsics.height);
    glm::dmat4 projection(0.0);
    projection[0][0] = 2.0 * intrinsics.fx / width;
    projection[2][0] = 2.0 * intrinsics.cx / width - 1.0;
    projection[1][1] = 2.0 * intrinsics.fy / height;
    projection[2][1] = 2.0 * intrinsics.cy / height - 1.0;
    projection[2][2] = far_m / (far_m - near_m);
    projection[3][2] = -far_m * near_m / (far_m - near_m);
    projection[2][3] = 1.0;
    return projection * view;
}

std::optional<std::string> findFrameProblem(const FrameInput& frame, uint32_t width, uint32_t height) {
    const CameraIntrinsics& k = frame.intrinsics;
    auto finite = [](double value) { return std::isfinite(value); };
    if (k.width != width || k.height != height)
        return "intrinsics: the frame is " + std::to_string(k.width) + " x " + std::to_string(k.height) +
               ", the runtime was opened for " + std::to_string(width) + " x " + std::to_string(height);
    if (!(finite(k.fx) && finite(k.fy) && k.fx > 0.0 && k.fy > 0.0))
        return "intrinsics: focal lengths must be finite and positive, got fx " + std::to_string(k.fx) + ", fy " +
               std::to_string(k.fy);
    if (!(finite(k.cx) && finite(k.cy))) return "intrinsics: the principal point is not finite";
    const glm::dvec3& position = frame.pose.position_enu;
    if (!(finite(position.x) && finite(position.y) && finite(position.z)))
        return "pose.position_enu: not finite";
    const glm::dmat3& rotation = frame.pose.camera_to_enu;
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            if (!finite(rotation[column][row])) return "pose.camera_to_enu: not finite";
    // Orthonormal within kRotationTolerance.
    const glm::dmat3 should_be_identity = glm::transpose(rotation) * rotation;
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            if (std::abs(should_be_identity[column][row] - (column == row ? 1.0 : 0.0)) > kRotationTolerance)
                return "pose.camera_to_enu: not a rotation (its columns are not orthonormal)";
    if (glm::determinant(rotation) < 0.0) return "pose.camera_to_enu: a reflection, not a rotation";
    if (!finite(frame.utc_unix_seconds)) return "utc_unix_seconds: not finite";
    if (!std::isfinite(frame.weather.cloud_cover) || frame.weather.cloud_cover < 0.0f ||
        frame.weather.cloud_cover > 1.0f)
        return "weather.cloud_cover: must be in [0, 1], got " + std::to_string(frame.weather.cloud_cover);
    if (!std::isfinite(frame.weather.sun_scale) || frame.weather.sun_scale > Weather::kMaxSunScale)
        return "weather.sun_scale: must be finite and at most " + std::to_string(Weather::kMaxSunScale) +
               " (negative: 1 - cloud_cover), got " + std::to_string(frame.weather.sun_scale);
    if (!std::isfinite(frame.exposure) || !(frame.exposure > 0.0f))
        return "exposure: must be finite and positive, got " + std::to_string(frame.exposure);
    if (frame.colour_match != ColourMatch::kOff && frame.colour_match != ColourMatch::kReinhard &&
        frame.colour_match != ColourMatch::kPreserve && frame.colour_match != ColourMatch::kGround &&
        frame.colour_match != ColourMatch::kAuto)
        return "colour_match: " + std::to_string(uint32_t(frame.colour_match)) +
               " is not off, paper, preserve, ground or auto";
    if (frame.mode != RenderMode::kBakedLight && frame.mode != RenderMode::kDirectOnly)
        return "mode: " + std::to_string(int(frame.mode)) + " is not proposed or direct-only";
    if (frame.position) {
        const GeoPosition& fix = *frame.position;
        if (!(std::abs(fix.latitude_deg) <= 90.0)) return "position.latitude_deg: must be in [-90, 90]";
        if (!(std::abs(fix.longitude_deg) <= 180.0)) return "position.longitude_deg: must be in [-180, 180]";
        if (!(std::abs(fix.height_m) <= kMaxFixHeightM)) return "position.height_m: must be in [-100000, 100000]";
    }
    return std::nullopt;
}

std::optional<std::string> findCameraProblem(const FrameInput& frame, const RuntimeOptions& options) {
    const bool yuv = options.camera_format == CameraFormat::kNv12 || options.camera_format == CameraFormat::kNv21;
    const int sources = int(frame.camera_rgba8 != nullptr) + int(frame.camera_luma != nullptr) +
                        int(frame.camera_image != VK_NULL_HANDLE);
    if (sources != 1)
        return "camera: give exactly one of camera_rgba8, camera_luma (with camera_chroma) and camera_image";
    if (options.camera_ycbcr_image && frame.camera_image == VK_NULL_HANDLE)
        return "camera_image: null, but options.camera_ycbcr_image takes the camera as the app's "
               "G8_B8R8_2PLANE_420_UNORM image, not as host pixels";
    if (yuv && frame.camera_rgba8 != nullptr)
        return "camera_rgba8: the runtime was opened for a Y'CbCr camera (options.camera_format): give camera_luma "
               "and camera_chroma";
    if (!yuv && frame.camera_luma != nullptr)
        return "camera_luma: the runtime was opened for a four-byte camera (options.camera_format): give "
               "camera_rgba8";
    if (frame.camera_luma != nullptr && frame.camera_chroma == nullptr)
        return "camera_chroma: null, but camera_luma is set (a Y'CbCr frame needs both planes)";
    auto rowTooShort = [](uint32_t row_bytes, uint32_t packed) { return row_bytes != 0 && row_bytes < packed; };
    if (frame.camera_rgba8 != nullptr && rowTooShort(frame.camera_row_bytes, options.frame_width * 4))
        return "camera_row_bytes: " + std::to_string(frame.camera_row_bytes) + " is less than a row's " +
               std::to_string(options.frame_width * 4) + " bytes";
    if (frame.camera_luma != nullptr && rowTooShort(frame.camera_luma_row_bytes, options.frame_width))
        return "camera_luma_row_bytes: " + std::to_string(frame.camera_luma_row_bytes) + " is less than a row's " +
               std::to_string(options.frame_width) + " bytes";
    if (frame.camera_luma != nullptr && rowTooShort(frame.camera_chroma_row_bytes, options.frame_width))
        return "camera_chroma_row_bytes: " + std::to_string(frame.camera_chroma_row_bytes) +
               " is less than a row's " + std::to_string(options.frame_width) + " bytes";
    if (frame.camera_image != VK_NULL_HANDLE && frame.camera_image_layout != VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL &&
        frame.camera_image_layout != VK_IMAGE_LAYOUT_GENERAL &&
        frame.camera_image_layout != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)
        return "camera_image_layout: " + std::to_string(int(frame.camera_image_layout)) +
               " is not SHADER_READ_ONLY_OPTIMAL, GENERAL or TRANSFER_SRC_OPTIMAL";
    const FrameSync& sync = frame.sync;
    if (sync.wait_count > kMaxFrameSemaphores || sync.signal_count > kMaxFrameSemaphores)
        return "sync: at most " + std::to_string(kMaxFrameSemaphores) + " wait and " +
               std::to_string(kMaxFrameSemaphores) + " signal semaphores";
    if ((sync.wait_count > 0 && sync.wait_semaphores == nullptr) ||
        (sync.signal_count > 0 && sync.signal_semaphores == nullptr))
        return "sync: a semaphore count without its array";
    for (uint32_t index = 0; index < sync.wait_count; ++index)
        if (sync.wait_semaphores[index] == VK_NULL_HANDLE) return "sync.wait_semaphores: a null semaphore";
    for (uint32_t index = 0; index < sync.signal_count; ++index)
        if (sync.signal_semaphores[index] == VK_NULL_HANDLE) return "sync.signal_semaphores: a null semaphore";
    return std::nullopt;
}

}  // namespace runtime_detail
}  // namespace gusuku
