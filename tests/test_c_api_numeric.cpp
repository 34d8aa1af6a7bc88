// The C API's camera helpers (gusuku.h, "Cameras and weather") on numbers at a double's edges: NaN, +inf, 1e308
// and denormals in every numeric argument. Each either answers GUSUKU_OK with every output finite (and, where the
// geometry says what it must be, that value), or refuses with GUSUKU_ERROR_INVALID_ARGUMENT, the outputs
// untouched, and a one-line message naming the argument. Expected values come from the geometry: a camera
// looking along (1, 1, 0) has forward (1, 1, 0) / sqrt 2, right (1, -1, 0) / sqrt 2 and down (0, 0, -1).
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "gusuku/runtime/gusuku.h"

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kHuge = 1e308;
constexpr double kEdgeValues[] = {kNan, kInf, -kInf, kHuge, -kHuge};
const double kInvSqrt2 = 1.0 / std::sqrt(2.0);

bool allFinite(const double* values, int count) {
    for (int i = 0; i < count; ++i)
        if (!std::isfinite(values[i])) return false;
    return true;
}

// The message starts "FUNCTION: ARGUMENT" and is one line.
void expectMessageNames(const std::string& function, const std::string& argument) {
    const std::string message = gusuku_last_error_message();
    EXPECT_EQ(message.rfind(function + ": " + argument, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// A pose filled with a byte pattern, to show that a refusal leaves it untouched.
gusuku_pose sentinelPose() {
    gusuku_pose pose;
    std::memset(&pose, 0x5A, sizeof pose);
    return pose;
}

TEST(CApiNumeric, LookingAtAFarTargetGivesTheRotationTheDirectionSays) {
    // Today's (1e308, 1e308, 0) made the offset's length inf and the rotation NaN, with GUSUKU_OK.
    const double position[3] = {0.0, 0.0, 0.0};
    for (const double far : {1e300, 1e308, 1.7e308}) {
        SCOPED_TRACE(far);
        const double target[3] = {far, far, 0.0};
        gusuku_pose pose{};
        ASSERT_EQ(gusuku_pose_looking_at(position, target, &pose), GUSUKU_OK) << gusuku_last_error_message();
        const double expected[9] = {kInvSqrt2, 0.0, kInvSqrt2,    // row E: right, down, forward
                                    -kInvSqrt2, 0.0, kInvSqrt2,   // row N
                                    0.0, -1.0, 0.0};              // row U
        for (int i = 0; i < 9; ++i) EXPECT_NEAR(pose.camera_to_enu[i], expected[i], 1e-15) << i;
    }
}

TEST(CApiNumeric, LookingAtRefusesEveryNonFiniteCoordinateNamingIt) {
    for (const double value : {kNan, kInf, -kInf}) {
        for (int axis = 0; axis < 3; ++axis) {
            double position[3] = {0.0, 0.0, 0.0}, target[3] = {1.0, 2.0, 3.0};
            position[axis] = value;
            gusuku_pose pose = sentinelPose();
            const gusuku_pose before = pose;
            EXPECT_EQ(gusuku_pose_looking_at(position, target, &pose), GUSUKU_ERROR_INVALID_ARGUMENT);
            expectMessageNames("gusuku_pose_looking_at", "position_enu[" + std::to_string(axis) + "]");
            EXPECT_EQ(std::memcmp(&pose, &before, sizeof pose), 0);
            position[axis] = 0.0;
            target[axis] = value;
            EXPECT_EQ(gusuku_pose_looking_at(position, target, &pose), GUSUKU_ERROR_INVALID_ARGUMENT);
            expectMessageNames("gusuku_pose_looking_at", "target_enu[" + std::to_string(axis) + "]");
        }
    }
}

TEST(CApiNumeric, LookingAtAcrossMoreThanADoubleIsRefusedNamingTheTarget) {
    // Every coordinate finite, but target - position is -2e308: no direction a double can hold.
    const double position[3] = {kHuge, 0.0, 0.0}, target[3] = {-kHuge, 0.0, 0.0};
    gusuku_pose pose = sentinelPose();
    EXPECT_EQ(gusuku_pose_looking_at(position, target, &pose), GUSUKU_ERROR_INVALID_ARGUMENT);
    expectMessageNames("gusuku_pose_looking_at", "target_enu");
    // Any 1e308 coordinate elsewhere: a finite rotation or a refusal, never OK with NaN.
    for (int index = 0; index < 6; ++index) {
        for (const double value : kEdgeValues) {
            double points[6] = {0.0, 0.0, 0.0, 1.0, -2.0, 0.5};
            points[index] = value;
            gusuku_pose out{};
            const gusuku_result result = gusuku_pose_looking_at(points, points + 3, &out);
            if (result == GUSUKU_OK)
                EXPECT_TRUE(allFinite(out.camera_to_enu, 9) && allFinite(out.position_enu, 3)) << index << " " << value;
            else
                EXPECT_EQ(result, GUSUKU_ERROR_INVALID_ARGUMENT);
        }
    }
}

TEST(CApiNumeric, FieldOfViewOfADenormalIsRefusedInsteadOfAnInfiniteFocalLength) {
    // tan(denormal) is a denormal: 32 / 4.9e-324 overflowed to a focal length of inf, with GUSUKU_OK.
    for (const double fov : {std::numeric_limits<double>::denorm_min(), 1e-310, kNan, kInf, -kInf, kHuge, -kHuge}) {
        SCOPED_TRACE(fov);
        gusuku_intrinsics intrinsics;
        std::memset(&intrinsics, 0x5A, sizeof intrinsics);
        const gusuku_intrinsics before = intrinsics;
        EXPECT_EQ(gusuku_intrinsics_from_field_of_view(64, 48, fov, &intrinsics), GUSUKU_ERROR_INVALID_ARGUMENT);
        expectMessageNames("gusuku_intrinsics_from_field_of_view", "horizontal_fov_deg");
        EXPECT_EQ(std::memcmp(&intrinsics, &before, sizeof intrinsics), 0);
    }
    // The smallest normal angles still give a finite focal length: fx = 32 / tan(fov / 2).
    gusuku_intrinsics intrinsics{};
    ASSERT_EQ(gusuku_intrinsics_from_field_of_view(64, 48, 1e-300, &intrinsics), GUSUKU_OK);
    EXPECT_TRUE(std::isfinite(intrinsics.fx));
    EXPECT_NEAR(intrinsics.fx / (32.0 / (0.5e-300 * std::numbers::pi / 180.0)), 1.0, 1e-12);
}

class CApiProjectTest : public testing::Test {
protected:
    // 64 x 48, fx = fy = 50, the principal point at the centre; the camera at the origin looking up ENU +z
    // (camera_to_enu the identity: camera x = east, y = north, z = up).
    gusuku_intrinsics intrinsics{50.0, 50.0, 32.0, 24.0, 64, 48};
    gusuku_pose pose{{0.0, 0.0, 0.0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
    double pixel[2] = {-7.0, -7.0};
    int32_t in_front = -7;

    gusuku_result project(const double point[3]) {
        return gusuku_project_to_pixel(&intrinsics, &pose, point, pixel, &in_front);
    }
    void expectRefusedNaming(const double point[3], const std::string& argument) {
        pixel[0] = pixel[1] = -7.0;
        in_front = -7;
        EXPECT_EQ(project(point), GUSUKU_ERROR_INVALID_ARGUMENT);
        expectMessageNames("gusuku_project_to_pixel", argument);
        EXPECT_EQ(pixel[0], -7.0);  // untouched
        EXPECT_EQ(in_front, -7);
    }
};

TEST_F(CApiProjectTest, APointWhosePixelOverflowsIsRefusedNotInFrontAtInfinity) {
    // Camera (1e308, 1e308, 1): u = 50 * 1e308 / 1 + 32 is beyond a double; today (inf, inf) "in front".
    const double beside[3] = {kHuge, kHuge, 1.0};
    expectRefusedNaming(beside, "point_enu");
    // Just in front of the camera's plane: 1 / 1e-320 overflows likewise.
    const double grazing[3] = {1.0, 0.0, 1e-320};
    expectRefusedNaming(grazing, "point_enu");
    // Focal lengths near 1e308 times an ordinary point: refused, the point named.
    intrinsics.fx = kHuge;
    const double ordinary[3] = {2.0, 0.0, 1.0};
    expectRefusedNaming(ordinary, "point_enu");
}

TEST_F(CApiProjectTest, AFarPointLandsWhereItsDirectionSays) {
    // The camera looks along (1, 1, 0): a point at (1.7e308, 1.7e308, 1e308) is at camera (0, -1e308, 2.4e308),
    // a z past a double's 1.8e308: rotated unscaled it overflowed to inf and put the point on the principal point.
    // Its pixel is v = cy + fy * (-1e308) / (1.7e308 sqrt 2).
    const double position[3] = {0.0, 0.0, 0.0}, toward[3] = {1.0, 1.0, 0.0};
    ASSERT_EQ(gusuku_pose_looking_at(position, toward, &pose), GUSUKU_OK);
    const double far[3] = {1.7e308, 1.7e308, 1e308};
    ASSERT_EQ(project(far), GUSUKU_OK) << gusuku_last_error_message();
    EXPECT_EQ(in_front, 1);
    EXPECT_NEAR(pixel[0], 32.0, 1e-9);
    EXPECT_NEAR(pixel[1], 24.0 - 50.0 / (1.7 * std::sqrt(2.0)), 1e-9);
}

TEST_F(CApiProjectTest, EveryNonFiniteArgumentIsRefusedNamingIt) {
    for (const double value : {kNan, kInf, -kInf}) {
        SCOPED_TRACE(value);
        for (int axis = 0; axis < 3; ++axis) {
            double point[3] = {0.0, 0.0, 5.0};
            point[axis] = value;
            expectRefusedNaming(point, "point_enu[" + std::to_string(axis) + "]");
        }
        const double point[3] = {0.0, 0.0, 5.0};
        const gusuku_intrinsics good_intrinsics = intrinsics;
        for (double* field : {&intrinsics.fx, &intrinsics.fy, &intrinsics.cx, &intrinsics.cy}) {
            *field = value;
            expectRefusedNaming(point, "intrinsics");
            intrinsics = good_intrinsics;
        }
        const gusuku_pose good_pose = pose;
        for (int axis = 0; axis < 3; ++axis) {
            pose.position_enu[axis] = value;
            expectRefusedNaming(point, "pose.position_enu");
            pose = good_pose;
        }
        for (int element = 0; element < 9; ++element) {
            pose.camera_to_enu[element] = value;
            expectRefusedNaming(point, "pose.camera_to_enu");
            pose = good_pose;
        }
    }
}

TEST_F(CApiProjectTest, HugeFiniteArgumentsGiveAFinitePixelOrARefusal) {
    // An offset from the camera past a double (1e308 - -1e308) names the point.
    pose.position_enu[0] = -kHuge;
    const double across[3] = {kHuge, 0.0, 1.0};
    expectRefusedNaming(across, "point_enu");
    pose.position_enu[0] = 0.0;
    // 1e308 in any one place of the point, the intrinsics or the position: never OK with a non-finite pixel.
    const gusuku_intrinsics good_intrinsics = intrinsics;
    const gusuku_pose good_pose = pose;
    double* places[] = {&intrinsics.fx, &intrinsics.fy, &intrinsics.cx, &intrinsics.cy, &pose.position_enu[0],
                        &pose.position_enu[1], &pose.position_enu[2]};
    for (const double value : {kHuge, -kHuge}) {
        for (int index = 0; index < 10; ++index) {
            double point[3] = {0.5, -0.25, 2.0};
            if (index < 3) point[index] = value;
            else *places[index - 3] = value;
            pixel[0] = pixel[1] = -7.0;
            const gusuku_result result = project(point);
            if (result == GUSUKU_OK && in_front == 1)
                EXPECT_TRUE(allFinite(pixel, 2)) << index << " " << value << ": " << pixel[0] << ", " << pixel[1];
            else if (result != GUSUKU_OK)
                EXPECT_EQ(result, GUSUKU_ERROR_INVALID_ARGUMENT);
            intrinsics = good_intrinsics;
            pose = good_pose;
        }
    }
}

TEST(CApiNumeric, WeatherEstimateGivesACoverInTheUnitInterval) {
    // The estimate's only numbers are bytes and sizes: any frame gives a cover in [0, 1] or a refusal.
    unsigned char frame[16 * 16 * 4];
    for (size_t i = 0; i < sizeof frame; ++i) frame[i] = (unsigned char)(i * 37 + 11);
    gusuku_weather weather{-1.0f};
    ASSERT_EQ(gusuku_weather_estimate(frame, 16, 16, &weather), GUSUKU_OK);
    EXPECT_TRUE(weather.cloud_cover >= 0.0f && weather.cloud_cover <= 1.0f) << weather.cloud_cover;
    EXPECT_EQ(gusuku_weather_estimate(frame, 0, 16, &weather), GUSUKU_ERROR_INVALID_ARGUMENT);
    expectMessageNames("gusuku_weather_estimate", "width, height");
}

}  // namespace
