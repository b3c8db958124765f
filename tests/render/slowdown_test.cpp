// The regression detector against a known truth on lavapipe: `--debug-slowdown opaque=10`
// (10% more work in the main pass) is SLOWER, `opaque=0` is not. Timing-sensitive: ctest
// runs this test alone (RUN_SERIAL), and the threshold is 5% because lavapipe's spin
// work is itself noisier than a GPU's (CV 1-3% here against 0.1% on an H200).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::readCsv;
using cbr::test::runBench;

TEST(Slowdown, TenPercentOfTheMainPassIsFoundAndZeroIsNot) {
    auto work = cbr::test::scratchDir("slowdown");
    const std::vector<std::string> run = {"run",     "--scene",    "atrium", "--path", "flythrough", "--res",
                                          "320x180", "--frames",   "30",     "--repeat", "5",        "--warmup",
                                          "3",       "--variants", "full"};
    auto with = [&](std::vector<std::string> extra, const std::string& out) {
        auto a = run;
        a.insert(a.end(), extra.begin(), extra.end());
        a.insert(a.end(), {"--out", (work / out).string()});
        return a;
    };
    ASSERT_EQ(runBench(with({}, "base"), work).exit_code, 0);
    ASSERT_EQ(runBench(with({"--debug-slowdown", "opaque=10"}, "slow10"), work).exit_code, 0);
    ASSERT_EQ(runBench(with({"--debug-slowdown", "opaque=0"}, "slow0"), work).exit_code, 0);

    auto slow = runBench({"compare", (work / "base").string(), (work / "slow10").string(), "--threshold", "5%"}, work);
    auto c10 = readCsv(work / "slow10" / "compare.csv");
    ASSERT_EQ(c10.rows.size(), 1u);
    EXPECT_EQ(c10.at(0, "time_verdict"), "SLOWER") << slow.out << "noise " << c10.at(0, "noise_cv_pct") << "%";
    EXPECT_EQ(slow.exit_code, 1) << slow.out;

    auto same = runBench({"compare", (work / "base").string(), (work / "slow0").string(), "--threshold", "5%"}, work);
    auto c0 = readCsv(work / "slow0" / "compare.csv");
    ASSERT_EQ(c0.rows.size(), 1u);
    EXPECT_NE(c0.at(0, "time_verdict"), "SLOWER") << same.out;
    EXPECT_NE(c0.at(0, "time_verdict"), "FASTER") << same.out;
    EXPECT_EQ(same.exit_code, 0) << same.out;
}
