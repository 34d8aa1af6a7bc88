// DispatchBudget (gusuku_bake/dispatch_budget.h): dispatches sized by the measured cost of a point-sample, so a
// stop waits about one target time on any set. Checked against the arithmetic of the rule, worked by hand.
#include <gtest/gtest.h>

#include <stdexcept>

#include "gusuku_bake/dispatch_budget.h"

namespace gusuku::bake {
namespace {

TEST(DispatchBudget, BeforeAnyMeasurementTracesOneSampleOverASmallRange) {
    const DispatchBudget budget(0.25);
    const DispatchSize large = budget.next(919000, 0, 4);
    EXPECT_EQ(large.samples, 1u);
    EXPECT_EQ(large.points, kMinDispatchPoints);
    const DispatchSize small = budget.next(100, 0, 40);  // a small set: its whole pass, one sample
    EXPECT_EQ(small.samples, 1u);
    EXPECT_EQ(small.points, 100u);
}

TEST(DispatchBudget, ACheapSetGetsWholePassesUpToTheTarget) {
    DispatchBudget budget(0.25);
    budget.measured(100.0, 100.0 * 1e-6);  // 1 us a point-sample, 100 point-samples done
    // Wanted: min(0.25 s / 1 us, 4 x 100) = 400 point-samples = 4 passes of 100 points.
    DispatchSize size = budget.next(100, 0, 40);
    EXPECT_EQ(size.samples, 4u);
    EXPECT_EQ(size.points, 100u);
    budget.measured(400.0, 400.0 * 1e-6);
    budget.measured(1600.0, 1600.0 * 1e-6);
    budget.measured(6400.0, 6400.0 * 1e-6);
    // Wanted min(250000, 25600) = 256 passes, capped at the samples left.
    size = budget.next(100, 0, 40);
    EXPECT_EQ(size.samples, 40u);
    // And at kMaxSamplesPerDispatch when more are left.
    EXPECT_EQ(budget.next(100, 0, 1000).samples, kMaxSamplesPerDispatch);
}

TEST(DispatchBudget, ALargeSetAfterACheapOneIsCutIntoRangesByCostPerPoint) {
    DispatchBudget budget(0.25);
    budget.measured(6400.0, 6400.0 * 4e-6);  // a ground set: 64 passes over 100 cells at 4 us a point-sample
    // The building's 919k copies: min(0.25 / 4e-6, 4 x 6400) = 25600 points, one sample, not 64 passes.
    const DispatchSize size = budget.next(919000, 0, 4);
    EXPECT_EQ(size.samples, 1u);
    EXPECT_EQ(size.points, 25600u);
    // Measured at 0.1 s: 0.25 s holds 64000 of them.
    budget.measured(25600.0, 0.1);
    EXPECT_EQ(budget.next(919000, 25600, 4).points, 64000u);
    // Measured at 0.01 s the target would hold 640000: the growth cap allows 4 x 25600.
    budget.measured(25600.0, 0.01);
    EXPECT_EQ(budget.next(919000, 51200, 4).points, 102400u);
}

TEST(DispatchBudget, APartDonePassIsFinishedInRangesBeforeWholePassesResume) {
    DispatchBudget budget(0.25);
    budget.measured(1e6, 1e6 * 1e-9);  // cheap: whole passes would fit
    // 900 of 1000 points hold the pass's sample: the next dispatch is the other 100, one sample.
    const DispatchSize rest = budget.next(1000, 900, 10);
    EXPECT_EQ(rest.samples, 1u);
    EXPECT_EQ(rest.points, 100u);
    // A range is never cut below kMinDispatchPoints however slow a point-sample.
    budget.measured(1.0, 10.0);
    EXPECT_EQ(budget.next(1000000, 0, 10).points, kMinDispatchPoints);
}

TEST(DispatchBudget, RefusesATargetThatIsNotPositiveAndAnEmptyRequest) {
    EXPECT_THROW(DispatchBudget(0.0), std::invalid_argument);
    EXPECT_THROW(DispatchBudget(-1.0), std::invalid_argument);
    const DispatchBudget budget(0.25);
    EXPECT_THROW(budget.next(0, 0, 1), std::invalid_argument);
    EXPECT_THROW(budget.next(10, 0, 0), std::invalid_argument);
    EXPECT_THROW(budget.next(10, 10, 1), std::invalid_argument);
}

}  // namespace
}  // namespace gusuku::bake
