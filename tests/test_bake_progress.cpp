// The progress bar's time left (issue 7, part A.7): from measured tracing throughput only, "--" until there is
// a measurement, never inflated by setup time spent before the first sample.
#include <chrono>
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "gusuku_bake/bake_progress.h"

namespace gusuku::bake {
namespace {

TEST(BakeProgress, TimeLeftComesFromMeasuredThroughputOnly) {
    BakeProgress progress(1000.0, false);
    EXPECT_TRUE(std::isnan(progress.secondsLeft())) << "nothing measured yet";
    EXPECT_EQ(formatDuration(progress.secondsLeft()), "--");
    // Setup (BVH, pipelines) takes a while before the first chunk; it must not count as tracing time.
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    progress.advance("noon building", 1, 10, 100.0, 1000, 0.5);  // 100 point-samples in 0.5 s
    EXPECT_DOUBLE_EQ(progress.secondsLeft(), 900.0 * 0.5 / 100.0);
    progress.addResumedWork(400.0);  // resumed work is done, free, and not part of the rate
    progress.advance("noon building", 2, 10, 100.0, 1000, 0.5);
    EXPECT_DOUBLE_EQ(progress.secondsLeft(), 400.0 * 1.0 / 200.0);
}

TEST(BakeProgress, DurationsFormat) {
    EXPECT_EQ(formatDuration(65.0), "1:05");
    EXPECT_EQ(formatDuration(3723.0), "1:02:03");
    EXPECT_EQ(formatDuration(-1.0), "--");
}

}  // namespace
}  // namespace gusuku::bake
