// `cbrbench stress` on lavapipe with the validation layer: every case holds, in both
// pipelines (the static and sub-pixel cases shortened to 120 frames to fit the suite's time budget).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::readCsv;
using cbr::test::runBench;

TEST(Stress, EveryCaseHoldsInBothPipelines) {
    auto work = cbr::test::scratchDir("stress");
    fs::path out = work / "out";
    auto r = runBench({"stress", "--validate", "--static-frames", "120", "--subpixel-frames", "120", "--out",
                       out.string()},
                      work);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    ASSERT_TRUE(fs::exists(out / "stress.csv")) << r.err;
    auto csv = readCsv(out / "stress.csv");
    auto list = runBench({"stress", "--list"}, work);
    ASSERT_EQ(list.exit_code, 0);
    const size_t cases = size_t(std::count(list.out.begin(), list.out.end(), '\n'));
    EXPECT_GE(cases, 17u);
    EXPECT_EQ(csv.rows.size(), 2 * cases);  // every case in forward and deferred
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        EXPECT_EQ(csv.at(i, "finite"), "yes") << csv.at(i, "case") << " " << csv.at(i, "pipeline") << ": "
                                               << csv.at(i, "detail");
        EXPECT_EQ(csv.at(i, "held"), "yes") << csv.at(i, "case") << " " << csv.at(i, "pipeline") << ": "
                                             << csv.at(i, "detail");
    }
    EXPECT_NE(cbr::test::slurp(out / "stress.html").find("Every case held."), std::string::npos);
}

TEST(Stress, UnknownCaseIsOneLineExitTwoAndNoOutput) {
    auto work = cbr::test::scratchDir("stress-bad");
    auto r = runBench({"stress", "--cases", "no-such-case", "--out", (work / "out").string()}, work);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("no-such-case"), std::string::npos);
    EXPECT_FALSE(fs::exists(work / "out"));
}
