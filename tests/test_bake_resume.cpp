// A bake stopped part-way and run again gives exactly what an uninterrupted bake gives (issue 3, "Progress and
// resume"): through the API (a stop request between chunks) and through the command line (SIGKILL mid-bake,
// then the same command again).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
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
#include "bake_output_checks.h"
#include "mini_site.h"

namespace gusuku::bake {
namespace {

using gusuku::testing::GpuTest;
namespace fs = std::filesystem;
using gusuku::testing::expectSameBakeSets;

class BakeResumeTest : public GpuTest {};

TEST_F(BakeResumeTest, StoppedAndResumedBakeEqualsUninterruptedBake) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-resume");
    const SiteConfig site = gusuku::testing::loadMiniSite(dir, 6);

    BakeOptions options = gusuku::testing::stoppableBakeOptions(dir + "/uninterrupted");
    const BakeReport uninterrupted = runBake(context(), site, options);
    ASSERT_TRUE(uninterrupted.completed);
    EXPECT_TRUE(fs::exists(options.output_dir + "/manifest.json"));
    EXPECT_FALSE(fs::exists(options.output_dir + "/.checkpoint")) << "checkpoints are removed once complete";

    options.output_dir = dir + "/resumed";
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 9; };  // stops inside the second point set
    const BakeReport stopped = runBake(context(), site, options);
    EXPECT_FALSE(stopped.completed);
    EXPECT_FALSE(fs::exists(options.output_dir + "/manifest.json")) << "no manifest for an unfinished bake";
    EXPECT_TRUE(fs::exists(options.output_dir + "/.checkpoint"));

    options.should_stop = nullptr;
    const BakeReport resumed = runBake(context(), site, options);
    ASSERT_TRUE(resumed.completed);
    EXPECT_LT(resumed.rays_traced, uninterrupted.rays_traced) << "the resumed run reuses the checkpointed work";
    expectSameBakeSets(dir + "/uninterrupted", dir + "/resumed");

    const BakeReport again = runBake(context(), site, options);
    EXPECT_TRUE(again.up_to_date) << "a finished bake set with the same inputs is not baked again";
}

// The same with adaptive sampling (32 samples: a pilot of 16 a texel, then the extra samples as a set of their
// own): stopped inside the extra samples' set, resumed, it writes what the uninterrupted bake writes.
TEST_F(BakeResumeTest, StoppedInsideAdaptiveSamplingsExtraSamplesResumesToTheSameBakeSet) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-resume-adaptive");
    const SiteConfig site = gusuku::testing::loadMiniSite(dir, 32);

    BakeOptions options = gusuku::testing::stoppableBakeOptions(dir + "/uninterrupted");
    const BakeReport uninterrupted = runBake(context(), site, options);
    ASSERT_TRUE(uninterrupted.completed);

    options.output_dir = dir + "/resumed";
    // Polls: one before the pilot, one after each of its 16 chunks and one when it is done, one before the extra
    // samples' set and one after its first chunk: the 20th stops there.
    int polls = 0;
    options.should_stop = [&polls] { return ++polls == 20; };
    const BakeReport stopped = runBake(context(), site, options);
    EXPECT_FALSE(stopped.completed);
    bool extras_checkpointed = false;
    for (const auto& entry : fs::directory_iterator(options.output_dir + "/.checkpoint"))
        extras_checkpointed = extras_checkpointed || entry.path().filename().string().find("building_extra") != std::string::npos;
    EXPECT_TRUE(extras_checkpointed) << "stopped inside the extra samples' set";

    options.should_stop = nullptr;
    const BakeReport resumed = runBake(context(), site, options);
    ASSERT_TRUE(resumed.completed);
    EXPECT_LT(resumed.rays_traced, uninterrupted.rays_traced);
    expectSameBakeSets(dir + "/uninterrupted", dir + "/resumed");

    // And adaptive sampling is not uniform sampling: --uniform-sampling writes other lightmaps.
    options.output_dir = dir + "/uniform";
    options.adaptive_sampling = false;
    ASSERT_TRUE(runBake(context(), site, options).completed);
    const ImageRGBA adaptive_lightmap = readImage(dir + "/uninterrupted/" + gusuku::testing::exrFilesIn(dir + "/uninterrupted").front());
    const ImageRGBA uniform_lightmap = readImage(dir + "/uniform/" + gusuku::testing::exrFilesIn(dir + "/uniform").front());
    EXPECT_NE(adaptive_lightmap.texels, uniform_lightmap.texels);
}

// Runs gusuku-bake with args; returns its pid (the caller waits).
pid_t spawnBake(const std::vector<std::string>& args) {
    const pid_t pid = fork();
    if (pid == 0) {
        std::vector<char*> argv;
        static std::string executable = gusuku::testing::bakeExecutablePath();
        argv.push_back(executable.data());
        std::vector<std::string> copies = args;
        for (std::string& arg : copies) argv.push_back(arg.data());
        argv.push_back(nullptr);
        execv(executable.c_str(), argv.data());
        _exit(127);
    }
    return pid;
}

int waitExitCode(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Starts a bake of a site long enough to be stopped part-way, waits for its first checkpoint and sends
// `signal_number`; returns the bake's exit code, or -1 when it finished before the signal (nothing to test).
int interruptBake(const std::string& site, const std::string& out_dir, int signal_number) {
    const pid_t pid = spawnBake({"bake", site, "-o", out_dir, "--quiet"});
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? -1 : 255;
        if (fs::exists(out_dir + "/.checkpoint") && !fs::is_empty(out_dir + "/.checkpoint")) break;
    }
    kill(pid, signal_number);
    return waitExitCode(pid);
}

class BakeCommandResume : public ::testing::TestWithParam<int> {};

TEST_P(BakeCommandResume, InterruptedBakeResumesToTheSameResult) {
    const int signal_number = GetParam();
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-interrupt");
    gusuku::testing::MiniSiteOptions site_options;
    // Long enough (several seconds on lavapipe) to be interrupted part-way.
    site_options.samples_per_texel = 160;
    site_options.texels_per_metre = 12.0;
    site_options.max_bounces = 3;
    site_options.with_overcast_slot = false;
    const std::string site = gusuku::testing::writeMiniSite(dir, site_options);
    ASSERT_EQ(waitExitCode(spawnBake({"bake", site, "-o", dir + "/reference", "--quiet"})), 0);

    const std::string interrupted_dir = dir + "/interrupted";
    const int status = interruptBake(site, interrupted_dir, signal_number);
    if (status == -1) GTEST_SKIP() << "the bake finished before it could be interrupted; nothing to resume";
    if (signal_number == SIGINT)
        EXPECT_EQ(status, 130) << "Ctrl-C checkpoints and exits with 130";
    else
        EXPECT_EQ(status, 128 + SIGKILL);
    EXPECT_FALSE(fs::exists(interrupted_dir + "/manifest.json"));
    EXPECT_TRUE(fs::exists(interrupted_dir + "/.checkpoint"));

    ASSERT_EQ(waitExitCode(spawnBake({"bake", site, "-o", interrupted_dir, "--quiet"})), 0);
    expectSameBakeSets(dir + "/reference", interrupted_dir);
}

// Ctrl-C at one sample per point: every set is a single chunk, so a stop polled only inside a set's loop was
// never seen and the bake ran to the end. Sent right after the device line (setup, before the first sample).
TEST(BakeCommandCtrlC, StopsPromptlyAtOneSample) {
    const std::string dir = gusuku::testing::makeTemporaryDirectory("gusuku-ctrlc-one");
    gusuku::testing::MiniSiteOptions site_options;
    site_options.texels_per_metre = 24.0;
    site_options.max_bounces = 3;
    const std::string site = gusuku::testing::writeMiniSite(dir, site_options);
    const std::string out = dir + "/out";
    const pid_t pid = gusuku::testing::spawnBakeProcess({"bake", site, "-o", out, "--samples", "1", "--quiet"},
                                                        "/dev/null", dir + "/bake.err");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (gusuku::testing::readTextFile(dir + "/bake.err").find("device") == std::string::npos &&
           std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    kill(pid, SIGINT);
    const auto signalled = std::chrono::steady_clock::now();
    const int status = gusuku::testing::waitBakeProcess(pid, 60);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    EXPECT_EQ(status, 130) << gusuku::testing::readTextFile(dir + "/bake.err");
    EXPECT_LT(seconds, 5.0) << "Ctrl-C took effect only after " << seconds << " s";
    EXPECT_FALSE(fs::exists(out + "/manifest.json")) << "the bake ran to the end despite Ctrl-C";
    // And the same command finishes the job.
    ASSERT_EQ(waitExitCode(spawnBake({"bake", site, "-o", out, "--samples", "1", "--quiet"})), 0);
    EXPECT_TRUE(fs::exists(out + "/manifest.json"));
}

INSTANTIATE_TEST_SUITE_P(CtrlCAndKill, BakeCommandResume, ::testing::Values(SIGINT, SIGKILL),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return std::string(info.param == SIGINT ? "CtrlC" : "Kill");
                         });

}  // namespace
}  // namespace gusuku::bake
