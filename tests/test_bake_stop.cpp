// A stop that stops (issue 21, item 6): SIGTERM or SIGINT ends a bake within 2 s whatever its chunks, the work
// done kept, and the same command resumes to exactly what an uninterrupted bake writes.
//
// The site: the mini site's box house at 40 texels a metre (38,400 lightmap texels, 2x2 footprint points each) at
// 128 samples a texel: a pilot of 32, then adaptive sampling's extra samples as 4-sample copies of texels, about
// 919k of them in one set. Before the fix a dispatch was at least one sample pass over a whole point set, here
// 4 samples over all the copies: measured at 3.95 s on 2-core lavapipe (the whole bake 6.6 s), and a stop waited
// for it. Now dispatches are cut into point ranges of about BakeOptions::target_chunk_seconds.
#include <signal.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "bake_process.h"
#include "gpu_test_support.h"
#include "gusuku/assets/image.h"
#include "gusuku/assets/site.h"
#include "gusuku_bake/bake_job.h"
#include "gusuku_bake/dispatch_budget.h"
#include "bake_output_checks.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

namespace fs = std::filesystem;
using gusuku::testing::expectSameBakeSets;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string writeHeavySite(const std::string& dir) {
    gusuku::testing::MiniSiteOptions options;
    options.samples_per_texel = 128;
    options.texels_per_metre = 40.0;
    options.max_bounces = 3;
    options.with_overcast_slot = false;
    return gusuku::testing::writeMiniSite(dir, options);
}

// The checkpoint header's sample counts (docs/bakeset.md: "GSKCKPT3", hash, point count, samples done, points
// holding the next sample).
struct CheckpointHeader {
    uint32_t point_count = 0, samples_done = 0, points_with_next_sample = 0;
};
CheckpointHeader readCheckpointHeader(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[8] = {};
    uint64_t hash = 0;
    CheckpointHeader header;
    file.read(magic, sizeof magic);
    file.read(reinterpret_cast<char*>(&hash), sizeof hash);
    file.read(reinterpret_cast<char*>(&header.point_count), sizeof header.point_count);
    file.read(reinterpret_cast<char*>(&header.samples_done), sizeof header.samples_done);
    file.read(reinterpret_cast<char*>(&header.points_with_next_sample), sizeof header.points_with_next_sample);
    if (!file || std::memcmp(magic, "GSKCKPT3", 8) != 0) throw std::runtime_error(path + ": not a GSKCKPT3 checkpoint");
    return header;
}

class BakeStopTest : public gusuku::testing::GpuTest {};

// A stop inside a sample pass cut into point ranges keeps the part done exactly: the checkpoint says which points
// hold the pass's sample, and the resumed bake equals, bit for bit, one that traced whole passes throughout.
TEST_F(BakeStopTest, AStopInsideAPassKeepsItsRangesAndResumesBitIdentical) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-stop-pass");
    gusuku::testing::MiniSiteOptions site_options;
    site_options.samples_per_texel = 4;
    site_options.texels_per_metre = 24.0;  // 13,824 texels: over three ranges of kMinDispatchPoints
    site_options.with_overcast_slot = false;
    const SiteConfig site = loadSiteConfig(gusuku::testing::writeMiniSite(dir, site_options));

    BakeOptions options;
    options.show_progress = false;
    options.output_dir = dir + "/whole_passes";
    options.target_chunk_seconds = 1e3;  // every dispatch whole passes of the set
    const BakeReport uninterrupted = runBake(context(), site, options);
    ASSERT_TRUE(uninterrupted.completed);
    ASSERT_GT(uninterrupted.building_texels, 3u * kMinDispatchPoints);

    // Ranges of kMinDispatchPoints; the first poll is before the set, the second after its first range.
    options = gusuku::testing::stoppableBakeOptions(dir + "/ranges");
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 2; };
    ASSERT_FALSE(runBake(context(), site, options).completed);
    const CheckpointHeader header = readCheckpointHeader(options.output_dir + "/.checkpoint/noon.building.bin");
    EXPECT_EQ(header.point_count, uninterrupted.building_texels);
    EXPECT_EQ(header.samples_done, 0u);
    EXPECT_EQ(header.points_with_next_sample, kMinDispatchPoints) << "the first range's sample is kept";

    options.should_stop = nullptr;
    const BakeReport resumed = runBake(context(), site, options);
    ASSERT_TRUE(resumed.completed);
    EXPECT_GT(resumed.resumed_fraction, 0.0);
    expectSameBakeSets(dir + "/whole_passes", dir + "/ranges");
    fs::remove_all(dir);
}

TEST(BakeStop, SigtermEndsTheBakeWithinTwoSecondsAndTheSameCommandResumesToTheSameResult) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-stop");
    const std::string site = writeHeavySite(dir);
    const auto reference_start = Clock::now();
    ASSERT_EQ(gusuku::testing::waitBakeProcess(
                  gusuku::testing::spawnBakeProcess({"bake", site, "-o", dir + "/reference", "--quiet"}), 300),
              0);
    const double reference_seconds = secondsSince(reference_start);
    std::printf("uninterrupted bake: %.1f s\n", reference_seconds);

    const std::string out = dir + "/stopped";
    const std::vector<std::string> command = {"bake", site, "-o", out, "--quiet"};
    const pid_t pid = gusuku::testing::spawnBakeProcess(command, dir + "/stopped.out", dir + "/stopped.err");
    // Into the extra samples' set: the pilot's checkpoint is written when the pilot is done (about 1 s of
    // tracing), and the extras take the next 4 s.
    const std::string pilot_checkpoint = out + "/.checkpoint/noon.building.bin";
    const auto deadline = Clock::now() + std::chrono::seconds(300);
    while (!fs::exists(pilot_checkpoint) && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(fs::exists(pilot_checkpoint)) << gusuku::testing::readTextFile(dir + "/stopped.err");
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));
    ASSERT_EQ(kill(pid, SIGTERM), 0);
    const auto signalled = Clock::now();
    const int status = gusuku::testing::waitBakeProcess(pid, 120);
    const double stop_seconds = secondsSince(signalled);
    std::printf("SIGTERM to exit: %.2f s\n", stop_seconds);
    const std::string stderr_text = gusuku::testing::readTextFile(dir + "/stopped.err");
    EXPECT_EQ(status, 130) << stderr_text;
    EXPECT_LT(stop_seconds, 2.0) << "the bake ran on for " << stop_seconds << " s after SIGTERM";
    EXPECT_NE(stderr_text.find("gusuku-bake: interrupted; the work done is saved in " + out + "/.checkpoint"),
              std::string::npos)
        << stderr_text;
    EXPECT_FALSE(fs::exists(out + "/manifest.json"));

    ASSERT_EQ(gusuku::testing::waitBakeProcess(
                  gusuku::testing::spawnBakeProcess(command, dir + "/resumed.out", dir + "/resumed.err"), 300),
              0)
        << gusuku::testing::readTextFile(dir + "/resumed.err");
    EXPECT_NE(gusuku::testing::readTextFile(dir + "/resumed.out").find("of the work came from checkpoints"),
              std::string::npos)
        << "the rerun resumed nothing";
    expectSameBakeSets(dir + "/reference", out);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gusuku::bake

namespace gusuku::bake {
namespace {

// A stop during setup (here right after the device is opened, while the model, BVH, charts and pipelines are
// prepared: 2.6 s on the shrine at 16 texels a metre under load, before this) ends the bake at once: nothing
// is traced yet, so nothing is lost.
TEST(BakeStop, SigtermDuringSetupEndsTheBakeAtOnce) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-stop-setup");
    const std::string site = writeHeavySite(dir);
    const std::string out = dir + "/out";
    const pid_t pid =
        gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet"}, "/dev/null", dir + "/bake.err");
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (gusuku::testing::readTextFile(dir + "/bake.err").find("device") == std::string::npos &&
           Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_EQ(kill(pid, SIGTERM), 0);
    const auto signalled = Clock::now();
    const int status = gusuku::testing::waitBakeProcess(pid, 60);
    const double stop_seconds = secondsSince(signalled);
    const std::string stderr_text = gusuku::testing::readTextFile(dir + "/bake.err");
    EXPECT_EQ(status, 130) << stderr_text;
    EXPECT_LT(stop_seconds, 1.5);
    // Every run has the message. About one run in five had none: the signal came while the sky photos were
    // decoded, when descriptor 2 points at image_read.cpp's capture file, and the message went there. The stop
    // now writes to a copy of stderr taken before.
    EXPECT_NE(stderr_text.find("interrupted before tracing began"), std::string::npos)
        << "exit status " << status << " after " << stop_seconds << " s; stderr: " << stderr_text;
    EXPECT_FALSE(fs::exists(out + "/manifest.json"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gusuku::bake

namespace gusuku::bake {
namespace {

// A second signal ends the bake at once (bake_stop_signals.h): here it comes while the first stop is being
// honoured, and the process must not wait for the cooperative stop's checkpoint or its deadline. The work on disk
// still resumes the bake.
TEST(BakeStop, ASecondSignalEndsTheBakeAtOnce) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-stop-second");
    const std::string site = writeHeavySite(dir);
    const std::string out = dir + "/out";
    const pid_t pid =
        gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet"}, "/dev/null", dir + "/bake.err");
    const std::string pilot_checkpoint = out + "/.checkpoint/noon.building.bin";
    const auto deadline = Clock::now() + std::chrono::seconds(300);
    while (!fs::exists(pilot_checkpoint) && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(fs::exists(pilot_checkpoint)) << gusuku::testing::readTextFile(dir + "/bake.err");
    ASSERT_EQ(kill(pid, SIGTERM), 0);
    ASSERT_EQ(kill(pid, SIGINT), 0);
    const auto second_signal = Clock::now();
    const int status = gusuku::testing::waitBakeProcess(pid, 60);
    const double stop_seconds = secondsSince(second_signal);
    const std::string stderr_text = gusuku::testing::readTextFile(dir + "/bake.err");
    EXPECT_EQ(status, 130) << stderr_text;
    // At once: by the second signal, not by the cooperative stop or its deadline (each says so in its own words),
    // and within the promise's 1.5 s (the process's own teardown took up to 0.51 s on a loaded machine).
    EXPECT_LT(stop_seconds, 1.5) << stderr_text;
    EXPECT_NE(stderr_text.find("interrupted twice; stopped at once"), std::string::npos) << stderr_text;
    EXPECT_FALSE(fs::exists(out + "/manifest.json"));
    ASSERT_EQ(gusuku::testing::waitBakeProcess(
                  gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--quiet"}, dir + "/resumed.out",
                                                    dir + "/resumed.err"),
                  300),
              0)
        << gusuku::testing::readTextFile(dir + "/resumed.err");
    EXPECT_NE(gusuku::testing::readTextFile(dir + "/resumed.out").find("of the work came from checkpoints"),
              std::string::npos);
    fs::remove_all(dir);
}

// A stop while the runtime pack is written (after the bake set is complete) ends at once and says the set is
// complete; the same command then writes the pack without baking again.
TEST(BakeStop, AStopWhileThePackIsWrittenKeepsTheSetAndTheRerunWritesThePack) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-stop-pack");
    // The heavy site's lightmaps at few samples: a short bake, and a pack whose ASTC encoding takes a while.
    gusuku::testing::MiniSiteOptions options;
    options.samples_per_texel = 4;
    options.texels_per_metre = 40.0;
    const std::string site = gusuku::testing::writeMiniSite(dir, options);
    const std::string out = dir + "/out";
    const std::vector<std::string> command = {"bake", site, "-o", out, "--quiet"};
    const pid_t pid = gusuku::testing::spawnBakeProcess(command, "/dev/null", dir + "/bake.err");
    // The set's manifest is the bake's last write; the pack follows it.
    const auto deadline = Clock::now() + std::chrono::seconds(300);
    int status = -1;
    while (!fs::exists(out + "/manifest.json") && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    ASSERT_TRUE(fs::exists(out + "/manifest.json")) << gusuku::testing::readTextFile(dir + "/bake.err");
    const bool pack_written_already = fs::exists(out + "/pack/manifest.json");
    ASSERT_EQ(kill(pid, SIGTERM), 0);
    const auto signalled = Clock::now();
    status = gusuku::testing::waitBakeProcess(pid, 60);
    const double stop_seconds = secondsSince(signalled);
    const std::string stderr_text = gusuku::testing::readTextFile(dir + "/bake.err");
    if (pack_written_already || status == 0) GTEST_SKIP() << "the pack was done before the signal came";
    EXPECT_EQ(status, 130) << stderr_text;
    EXPECT_LT(stop_seconds, 1.5);
    EXPECT_NE(stderr_text.find("interrupted while writing the runtime pack"), std::string::npos) << stderr_text;
    EXPECT_FALSE(fs::exists(out + "/pack/manifest.json"));
    ASSERT_EQ(gusuku::testing::waitBakeProcess(
                  gusuku::testing::spawnBakeProcess(command, dir + "/rerun.out", dir + "/rerun.err"), 300),
              0)
        << gusuku::testing::readTextFile(dir + "/rerun.err");
    EXPECT_NE(gusuku::testing::readTextFile(dir + "/rerun.out").find("up to date"), std::string::npos);
    EXPECT_TRUE(fs::exists(out + "/pack/manifest.json"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace gusuku::bake
