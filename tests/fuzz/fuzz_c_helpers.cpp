// libFuzzer target: the C API's camera and weather helpers (gusuku.h, "Cameras and weather") on fuzzed numbers.
// Each helper must answer GUSUKU_OK with every output finite (out_pixel's documented NaN behind the camera
// excepted), or refuse with GUSUKU_ERROR_INVALID_ARGUMENT and a message naming its function. Anything else (an OK
// with a NaN or an inf, another code, an empty message) aborts: a finding.
//
// Input: a stream of numbers, each a selector byte then its bytes. Selector % 4: 0 a raw little-endian double
// (8 bytes: NaN payloads, infinities, 1e308 and denormals arise naturally), 1 a raw float widened (4 bytes), 2 an
// edge value from kEdges (1 byte), 3 a small integer (1 byte, -128..127). Past the end every number is 0. The
// rest of the input after the numbers is the weather estimate's frame.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "gusuku/runtime/gusuku.h"

namespace {

constexpr double kEdges[] = {std::numeric_limits<double>::quiet_NaN(),
                             std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(),
                             1e308,
                             -1e308,
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min(),
                             1e-320,
                             0.0,
                             -0.0,
                             1e-6,
                             179.99999999999997,
                             180.0,
                             1.0};

class NumberStream {
public:
    NumberStream(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    double next() {
        const uint8_t selector = byte();
        switch (selector % 4) {
        case 0: {
            double value;
            copy(&value, sizeof value);
            return value;
        }
        case 1: {
            float value;
            copy(&value, sizeof value);
            return double(value);
        }
        case 2: return kEdges[byte() % (sizeof kEdges / sizeof kEdges[0])];
        default: return double(int8_t(byte()));
        }
    }
    uint32_t nextSide() {  // a frame side: mostly small, sometimes at or past the helpers' 65536
        uint32_t value = 0;
        copy(&value, sizeof value);
        return value % 4 == 0 ? value : value % 70000;
    }
    uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
    const uint8_t* rest() const { return data_ + offset_; }
    size_t restSize() const { return size_ - offset_; }

private:
    void copy(void* out, size_t bytes) {
        std::memset(out, 0, bytes);
        const size_t available = offset_ < size_ ? size_ - offset_ : 0;
        const size_t taken = bytes < available ? bytes : available;
        std::memcpy(out, data_ + offset_, taken);
        offset_ += taken;
    }

    const uint8_t* data_;
    size_t size_, offset_ = 0;
};

[[noreturn]] void finding(const char* function, const std::string& what) {
    std::fprintf(stderr, "fuzz_c_helpers: %s: %s (last message: \"%s\")\n", function, what.c_str(),
                 gusuku_last_error_message());
    std::abort();
}

bool allFinite(const double* values, int count) {
    for (int i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) return false;
    return true;
}

/// A refusal must be INVALID_ARGUMENT with a message "FUNCTION: ...".
void checkRefusal(const char* function, gusuku_result result) {
    if (result != GUSUKU_ERROR_INVALID_ARGUMENT)
        finding(function, std::string("returned ") + gusuku_result_name(result));
    const std::string message = gusuku_last_error_message();
    if (message.rfind(std::string(function) + ": ", 0) != 0) finding(function, "message does not name it");
}

gusuku_pose lookingAt(NumberStream& numbers, bool& made) {
    double position[3], target[3];
    for (double& value : position) value = numbers.next();
    for (double& value : target) value = numbers.next();
    gusuku_pose pose{};
    const gusuku_result result = gusuku_pose_looking_at(position, target, &pose);
    made = result == GUSUKU_OK;
    if (result != GUSUKU_OK) {
        checkRefusal("gusuku_pose_looking_at", result);
        return pose;
    }
    if (!allFinite(pose.camera_to_enu, 9) || !allFinite(pose.position_enu, 3))
        finding("gusuku_pose_looking_at", "GUSUKU_OK with a non-finite pose");
    // The rotation's columns are unit: what project_to_pixel's rotation check will take.
    for (int column = 0; column < 3; ++column) {
        double length_squared = 0.0;
        for (int row = 0; row < 3; ++row) {
            const double element = pose.camera_to_enu[3 * row + column];
            length_squared += element * element;
        }
        if (!(std::abs(length_squared - 1.0) < 1e-9))
            finding("gusuku_pose_looking_at", "GUSUKU_OK with a non-unit axis");
    }
    return pose;
}

gusuku_intrinsics fromFieldOfView(NumberStream& numbers) {
    const uint32_t width = numbers.nextSide(), height = numbers.nextSide();
    const double fov = numbers.next();
    gusuku_intrinsics intrinsics{};
    const gusuku_result result = gusuku_intrinsics_from_field_of_view(width, height, fov, &intrinsics);
    if (result != GUSUKU_OK) {
        checkRefusal("gusuku_intrinsics_from_field_of_view", result);
        return intrinsics;
    }
    const double values[4] = {intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy};
    if (!allFinite(values, 4) || !(intrinsics.fx > 0.0 && intrinsics.fy > 0.0))
        finding("gusuku_intrinsics_from_field_of_view", "GUSUKU_OK with a focal length not finite and positive");
    return intrinsics;
}

void projectToPixel(NumberStream& numbers) {
    // Intrinsics from the field of view or raw; a pose from lookingAt or raw (mostly refused as no rotation).
    const uint8_t choice = numbers.byte();
    gusuku_intrinsics intrinsics = fromFieldOfView(numbers);
    if (choice & 1) {
        intrinsics.fx = numbers.next();
        intrinsics.fy = numbers.next();
        intrinsics.cx = numbers.next();
        intrinsics.cy = numbers.next();
    }
    bool made = false;
    gusuku_pose pose = lookingAt(numbers, made);
    if (choice & 2)
        for (double& value : pose.camera_to_enu) value = numbers.next();
    if (choice & 4)
        for (double& value : pose.position_enu) value = numbers.next();
    double point[3];
    for (double& value : point) value = numbers.next();
    double pixel[2] = {0.0, 0.0};
    int32_t in_front = -1;
    const char* function = "gusuku_project_to_pixel";
    const gusuku_result result = gusuku_project_to_pixel(&intrinsics, &pose, point, pixel, &in_front);
    if (result != GUSUKU_OK) return checkRefusal(function, result);
    if (in_front == 1 && !allFinite(pixel, 2)) finding(function, "GUSUKU_OK in front with a non-finite pixel");
    if (in_front == 0 && !(std::isnan(pixel[0]) && std::isnan(pixel[1])))
        finding(function, "GUSUKU_OK behind the camera without the documented NaN pixel");
    if (in_front != 0 && in_front != 1) finding(function, "in_front neither 0 nor 1");
}

void weatherEstimate(NumberStream& numbers) {
    // A frame of the bytes left (sides at most 64, so a run stays fast).
    const uint32_t width = numbers.byte() % 65, height = numbers.byte() % 65;
    const size_t bytes = size_t(width) * height * 4;
    if (bytes > numbers.restSize() || bytes == 0) return;
    gusuku_weather weather{};
    const gusuku_result result = gusuku_weather_estimate(numbers.rest(), width, height, &weather);
    if (result != GUSUKU_OK) return checkRefusal("gusuku_weather_estimate", result);
    if (!(weather.cloud_cover >= 0.0f && weather.cloud_cover <= 1.0f))
        finding("gusuku_weather_estimate", "GUSUKU_OK with a cloud cover outside [0, 1]");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    NumberStream numbers(data, size);
    bool made = false;
    lookingAt(numbers, made);
    fromFieldOfView(numbers);
    projectToPixel(numbers);
    weatherEstimate(numbers);
    return 0;
}
