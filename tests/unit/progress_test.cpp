// The progress bar's line: count, percentage, rate and time left.
#include <gtest/gtest.h>

#include "harness/base/progress.h"

using cbr::harness::ProgressBar;

TEST(ProgressBar, LineShowsCountRateAndTimeLeft) {
    EXPECT_EQ(ProgressBar::line("repeat 1/5 full", 5, 10, "frames", 2.0, 10),
              "repeat 1/5 full [#####.....]  50% 5/10 frames  2.5/s  ETA 2 s");
    EXPECT_EQ(ProgressBar::line("", 0, 600, "frames", 0.0, 4), "[....]   0% 0/600 frames");
    EXPECT_EQ(ProgressBar::line("merge", 3, 3, "jobs", 1.0, 4), "merge [####] 100% 3/3 jobs  3.0/s");
    // Slow work: rates below one a second, ETA in minutes.
    EXPECT_EQ(ProgressBar::line("calibrate base-000", 1, 40, "runs", 30.0, 4),
              "calibrate base-000 [....]   2% 1/40 runs  0.03/s  ETA 19 min 30 s");
    // More done than planned (a total that was an estimate) stays at 100%.
    EXPECT_EQ(ProgressBar::line("x", 12, 10, "runs", 1.0, 2), "x [##] 100% 12/10 runs  12/s");
}
