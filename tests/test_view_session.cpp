// gusuku-view's recorded sessions (docs/session.md, issue 45 item 2): a session written, read back field for field,
// and composited headless; one of its frames against gusuku-render drawing the same camera image from the same
// pose at the same instant (an independent program: its own command line, its look-at pose, its frame loop); and
// bad input (a missing frame, a bad pose row) refused in one line, with no output left half-written.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "camera_view.h"
#include "gpu_test_support.h"
#include "gusuku/assets/bakeset_loader.h"
#include "gusuku/assets/image.h"
#include "gusuku/formats/input_error.h"
#include "gusuku/maths/time_utc.h"
#include "gusuku_bake/bake_job.h"
#include "mini_site.h"
#include "view_render_session.h"
#include "view_session.h"

namespace gusuku::view {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::GpuTest;

constexpr uint32_t kWidth = 96, kHeight = 64;
constexpr double kFovDeg = 60.0;
constexpr float kExposure = 0.8f;
// Three views of the mini site's 2 m box house (origin, 2 m high) at 10:00, 12:00 and 14:00 on its bake day,
// the second under half cloud.
const glm::dvec3 kPositions[] = {{6.0, -7.0, 2.5}, {-1.0, -8.0, 3.0}, {-7.0, -5.0, 2.0}};
const char* const kTimes[] = {"2026-06-21T10:00:00+09:00", "2026-06-21T12:00:00+09:00", "2026-06-21T14:00:00+09:00"};
const float kCovers[] = {0.0f, 0.5f, 0.0f};
const glm::dvec3 kLookAt{0.0, 0.0, 1.0};

std::string readText(const fs::path& path) {
    std::ifstream stream(path);
    std::ostringstream text;
    text << stream.rdbuf();
    return text.str();
}

// A camera image: a sky-to-ground gradient with a pattern, different for each frame.
std::vector<uint8_t> cameraImage(size_t index) {
    std::vector<uint8_t> rgba8(size_t(kWidth) * kHeight * 4);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            uint8_t* pixel = &rgba8[(size_t(y) * kWidth + x) * 4];
            pixel[0] = uint8_t(60 + y * 2 + index * 20);
            pixel[1] = uint8_t(90 + ((x / 8 + y / 8) % 2) * 30);
            pixel[2] = uint8_t(200 - y * 2);
            pixel[3] = 255;
        }
    return rgba8;
}

struct CommandResult {
    int exit_code = -1;
    std::string stdout_text, stderr_text;
};

CommandResult runCommand(const std::vector<std::string>& args, const fs::path& scratch) {
    std::string command;
    for (const std::string& argument : args) command += "'" + argument + "' ";
    command += ">'" + (scratch / "out.txt").string() + "' 2>'" + (scratch / "err.txt").string() + "'";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(scratch / "out.txt"), readText(scratch / "err.txt")};
}

// The session of three frames written into a scratch folder; Base: GpuTest for the tests that render (one
// Vulkan device), ::testing::Test for those that only read.
template <class Base>
class SessionTest : public Base {
protected:
    void SetUp() override {
        Base::SetUp();
        dir_ = gusuku::testing::makeTemporaryDirectory("view_session");
        session_.intrinsics = CameraIntrinsics::fromFieldOfView(kWidth, kHeight, kFovDeg);
        for (size_t index = 0; index < 3; ++index) {
            SessionFrame frame;
            frame.time_iso = kTimes[index];
            frame.utc_seconds = parseIso8601Utc(kTimes[index]);
            frame.pose = bench_common::lookAtPose(kPositions[index], kLookAt);
            frame.cloud_cover = kCovers[index];
            frame.exposure = kExposure;
            frame.rgba8 = cameraImage(index);
            session_.frames.push_back(frame);
        }
        writeSession(dir_ + "/session", session_, dir_ + "/set");
    }
    void TearDown() override {
        fs::remove_all(dir_);
        Base::TearDown();
    }
    // The mini site baked at 2 samples a texel into dir_/set, where the session says its bake set is.
    BakeSetData bakeSet() {
        const SiteConfig site = gusuku::testing::loadMiniSite(dir_ + "/site", 2);
        bake::BakeOptions options;
        options.show_progress = false;
        options.output_dir = dir_ + "/set";
        EXPECT_TRUE(bake::runBake(this->context(), site, options).completed);
        return loadBakeSet(dir_ + "/set");
    }

    // The message readSession throws for the session as it now is, or "" when it reads.
    std::string readError() {
        try {
            readSession(dir_ + "/session");
        } catch (const InputError& error) {
            return error.what();
        }
        return "";
    }
    // Replaces track.csv's line `line_number` (1: the header) with `row`.
    void replaceTrackLine(size_t line_number, const std::string& row) {
        std::istringstream lines(readText(dir_ + "/session/track.csv"));
        std::string text, line;
        for (size_t number = 1; std::getline(lines, line); ++number) text += (number == line_number ? row : line) + "\n";
        std::ofstream(dir_ + "/session/track.csv") << text;
    }

    std::string dir_;
    Session session_;
};
using ViewSessionTest = SessionTest<GpuTest>;
using SessionFolderTest = SessionTest<::testing::Test>;

TEST_F(ViewSessionTest, WrittenSessionReadsBackAndItsFrameIsGusukuRendersOfTheSamePoseAndInstant) {
    const Session read = readSession(dir_ + "/session");
    EXPECT_EQ(read.intrinsics.fx, session_.intrinsics.fx);
    EXPECT_EQ(read.intrinsics.cx, session_.intrinsics.cx);
    EXPECT_EQ(read.intrinsics.width, kWidth);
    EXPECT_EQ(read.intrinsics.height, kHeight);
    ASSERT_TRUE(sessionBakeSet(read));
    EXPECT_EQ(*sessionBakeSet(read), (fs::path(dir_) / "set").lexically_normal().string());
    ASSERT_EQ(read.frames.size(), 3u);
    for (size_t index = 0; index < 3; ++index) {
        const SessionFrame& frame = read.frames[index];
        EXPECT_EQ(frame.time_iso, kTimes[index]);
        EXPECT_EQ(frame.utc_seconds, session_.frames[index].utc_seconds);
        EXPECT_EQ(frame.pose.position_enu, kPositions[index]);
        for (int column = 0; column < 3; ++column)
            for (int row = 0; row < 3; ++row)
                EXPECT_NEAR(frame.pose.camera_to_enu[column][row], session_.frames[index].pose.camera_to_enu[column][row],
                            1e-12);
        EXPECT_EQ(frame.cloud_cover, kCovers[index]);
        EXPECT_EQ(frame.exposure, kExposure);
        EXPECT_TRUE(frame.rgba8.empty()) << "pixels are read when drawn";
    }
    // The runtime's camera convention: camera z (the third column) points from the camera at the point looked at.
    const glm::dvec3 forward = read.frames[0].pose.camera_to_enu[2];
    EXPECT_NEAR(glm::dot(forward, glm::normalize(kLookAt - kPositions[0])), 1.0, 1e-12);
    // The frames are the images written, bit for bit.
    const ImageRGBA frame1 = readImage(dir_ + "/session/frames/000001.png", ImageEncoding::Linear);
    EXPECT_EQ(frame1.texel(5, 7)[0], float(cameraImage(1)[(7 * kWidth + 5) * 4]) / 255.0f);

    // Composited headless, every frame; frame 1 against gusuku-render of the same pose and instant.
    SessionRenderOptions options;
    options.show_progress = false;
    EXPECT_EQ(renderSession(context(), bakeSet(), read, dir_ + "/frames", options), 3u);
    for (size_t index = 0; index < 3; ++index) EXPECT_TRUE(fs::exists(dir_ + "/frames/" + outputFrameName(index)));
    EXPECT_FALSE(fs::exists(dir_ + "/.frames.tmp-" + std::to_string(getpid())));

    const glm::dvec3& position = kPositions[1];
    const std::string triple = std::to_string(position.x) + "," + std::to_string(position.y) + "," +
                               std::to_string(position.z);
    const CommandResult render = runCommand(
        {GUSUKU_RENDER_EXECUTABLE, dir_ + "/set", "-o", dir_ + "/reference.png", "--camera",
         dir_ + "/session/frames/000001.png", "--position", triple, "--look-at", "0,0,1", "--fov", "60", "--time",
         kTimes[1], "--weather", "0.5", "--exposure", "0.8", "--colour-match", "off", "--frames", "1"},
        dir_);
    ASSERT_EQ(render.exit_code, 0) << render.stderr_text;
    const ImageRGBA reference = readImage(dir_ + "/reference.png", ImageEncoding::Linear);
    const ImageRGBA drawn = readImage(dir_ + "/frames/" + outputFrameName(1), ImageEncoding::Linear);
    ASSERT_EQ(drawn.width, reference.width);
    ASSERT_EQ(drawn.height, reference.height);
    // Byte-identical: the same runtime on the same inputs, the pose through the track's quaternion text
    // (1e-16 of the look-at rotation) landing on the same pixels.
    const ImageRGBA camera = readImage(dir_ + "/session/frames/000001.png", ImageEncoding::Linear);
    int differing = 0, building = 0;
    for (int y = 0; y < drawn.height; ++y)
        for (int x = 0; x < drawn.width; ++x) {
            differing += !std::equal(drawn.texel(x, y), drawn.texel(x, y) + 4, reference.texel(x, y));
            building += !std::equal(drawn.texel(x, y), drawn.texel(x, y) + 4, camera.texel(x, y));
        }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(building, 200) << "the house is drawn into the frame";

    // OUT.png: the same frames as one animated PNG, its default image the first frame (what a plain reader shows).
    EXPECT_EQ(renderSession(context(), bakeSet(), read, dir_ + "/day.png", options), 3u);
    const std::string apng = readText(dir_ + "/day.png");
    const size_t actl = apng.find("acTL");
    ASSERT_NE(actl, std::string::npos);
    EXPECT_EQ(uint8_t(apng[actl + 7]), 3u) << "acTL's frame count";
    size_t frame_controls = 0;
    for (size_t at = apng.find("fcTL"); at != std::string::npos; at = apng.find("fcTL", at + 4)) ++frame_controls;
    EXPECT_EQ(frame_controls, 3u);
    const ImageRGBA first = readImage(dir_ + "/day.png", ImageEncoding::Linear);
    const ImageRGBA frame0 = readImage(dir_ + "/frames/" + outputFrameName(0), ImageEncoding::Linear);
    EXPECT_EQ(first.texels, frame0.texels);
}

TEST_F(SessionFolderTest, MissingFrameOrBadPoseRowIsOneLineNamingLineAndColumn) {
    fs::rename(dir_ + "/session/frames/000002.png", dir_ + "/000002.png");
    EXPECT_EQ(readError(), dir_ + "/session/track.csv: line 4 image: frames/000002.png: file not found");
#ifdef GUSUKU_VIEW_EXECUTABLE
    // The viewer's headless render says the same in one line, exits 1 and writes nothing.
    const CommandResult result =
        runCommand({GUSUKU_VIEW_EXECUTABLE, "--render", dir_ + "/out", dir_ + "/session"}, dir_);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_EQ(result.stderr_text,
              "gusuku-view: error: " + dir_ + "/session/track.csv: line 4 image: frames/000002.png: file not found\n");
    EXPECT_FALSE(fs::exists(dir_ + "/out"));
#endif
    fs::rename(dir_ + "/000002.png", dir_ + "/session/frames/000002.png");

    const std::string track = dir_ + "/session/track.csv";
    const std::string good = [&] {
        std::istringstream lines(readText(track));
        std::string line;
        std::getline(lines, line);
        std::getline(lines, line);
        return line;
    }();
    auto cells = [&](size_t column, const std::string& value) {
        std::vector<std::string> parts;
        std::istringstream stream(good);
        std::string part;
        while (std::getline(stream, part, ',')) parts.push_back(part);
        parts.resize(11);
        parts[column] = value;
        std::string row;
        for (size_t index = 0; index < parts.size(); ++index) row += (index ? "," : "") + parts[index];
        return row;
    };
    replaceTrackLine(3, cells(6, "x"));
    EXPECT_EQ(readError(), track + ": line 3 qx: 'x' is not a number");
    replaceTrackLine(3, cells(5, "2"));
    EXPECT_EQ(readError().rfind(track + ": line 3 qw: qw, qx, qy, qz is not a unit quaternion (norm ", 0), 0u)
        << readError();
    replaceTrackLine(3, cells(1, "2026-06-21T12:00:00"));
    EXPECT_EQ(readError().rfind(track + ": line 3 time: '2026-06-21T12:00:00': ", 0), 0u) << readError();
    replaceTrackLine(3, cells(1, "2026-06-21T09:00:00+09:00"));
    EXPECT_EQ(readError(), track + ": line 3 time: goes back in time (rows are in time order)");
    replaceTrackLine(3, cells(9, "1.5"));
    EXPECT_EQ(readError(), track + ": line 3 cloud_cover: must be in [0, 1]");
    replaceTrackLine(3, good + ",7");
    EXPECT_EQ(readError(), track + ": line 3: has 12 columns, expected 11 (" + kTrackHeader + ")");
    replaceTrackLine(3, cells(0, "../set/manifest.json"));
    EXPECT_EQ(readError(), track + ": line 3 image: '../set/manifest.json' is not a path inside the session folder");
    for (const std::string& message : {readError()}) EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST_F(ViewSessionTest, FrameThatFailsMidRenderLeavesThePreviousRenderWhole) {
    SessionRenderOptions options;
    options.show_progress = false;
    const BakeSetData bake_set = bakeSet();
    Session read = readSession(dir_ + "/session");
    ASSERT_EQ(renderSession(context(), bake_set, read, dir_ + "/frames", options), 3u);
    const std::string before = readText(dir_ + "/frames/" + outputFrameName(0));
    // The last frame's file is damaged after the session was read: the render stops there.
    std::ofstream(dir_ + "/session/frames/000002.png", std::ios::trunc) << "not a png";
    options.beside_direct_only = true;
    EXPECT_THROW(renderSession(context(), bake_set, read, dir_ + "/frames", options), InputError);
    EXPECT_EQ(readText(dir_ + "/frames/" + outputFrameName(0)), before) << "the previous frames are untouched";
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    // Refused before anything: an output inside the session, or a folder holding someone else's files.
    EXPECT_THROW(refuseUnsafeRenderFolder(dir_ + "/session/out", dir_ + "/session", dir_ + "/set"), InputError);
    EXPECT_THROW(refuseUnsafeRenderFolder(dir_ + "/site", dir_ + "/session", dir_ + "/set"), InputError);
    EXPECT_NO_THROW(refuseUnsafeRenderFolder(dir_ + "/frames", dir_ + "/session", dir_ + "/set"));
    EXPECT_THROW(writeSession(dir_ + "/site", session_), InputError) << "a folder that is not a session";
}


}  // namespace
}  // namespace gusuku::view
