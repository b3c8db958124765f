// `cbrbench stress` on lavapipe with the validation layer: every case holds, in both
// pipelines (the static and sub-pixel cases shortened to 120 frames to fit the suite's time budget).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::readCsv;
using cbr::test::runBench;

// Every case of `stress --list`, in four ctest entries that run side by side: each
// pipeline's two long cases (120 frames each) and the rest.
struct StressPart {
    std::string pipeline;
    bool long_cases;
};

void PrintTo(const StressPart& p, std::ostream* os) { *os << p.pipeline << (p.long_cases ? " long" : " rest"); }

bool isLongCase(const std::string& name) { return name == "static-camera" || name == "subpixel-motion"; }

class StressCases : public ::testing::TestWithParam<StressPart> {};

TEST_P(StressCases, EveryCaseHolds) {
    const StressPart& part = GetParam();
    const std::string label = part.pipeline + (part.long_cases ? "-long" : "-rest");
    auto work = cbr::test::scratchDir("stress-" + label);
    fs::path out = work / "out";
    auto list = runBench({"stress", "--list"}, work);
    ASSERT_EQ(list.exit_code, 0);
    std::vector<std::string> all, mine;
    std::istringstream lines(list.out);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) all.push_back(line.substr(0, line.find(' ')));
    EXPECT_GE(all.size(), 17u);
    std::string cases;
    for (const auto& c : all)
        if (isLongCase(c) == part.long_cases) mine.push_back(c), cases += (cases.empty() ? "" : ",") + c;
    ASSERT_EQ(mine.size() == 2, part.long_cases) << "the long cases were renamed: " << cases;
    auto r = runBench({"stress", "--validate", "--static-frames", "120", "--subpixel-frames", "120", "--pipelines",
                       part.pipeline, "--cases", cases, "--out", out.string()},
                      work);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    ASSERT_TRUE(fs::exists(out / "stress.csv")) << r.err;
    auto csv = readCsv(out / "stress.csv");
    EXPECT_EQ(csv.rows.size(), mine.size());
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        EXPECT_EQ(csv.at(i, "pipeline"), part.pipeline);
        EXPECT_EQ(csv.at(i, "finite"), "yes") << csv.at(i, "case") << " " << csv.at(i, "pipeline") << ": "
                                               << csv.at(i, "detail");
        EXPECT_EQ(csv.at(i, "held"), "yes") << csv.at(i, "case") << " " << csv.at(i, "pipeline") << ": "
                                             << csv.at(i, "detail");
    }
    EXPECT_NE(cbr::test::slurp(out / "stress.html").find("Every case held."), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Parts, StressCases,
                         ::testing::Values(StressPart{"forward", true}, StressPart{"forward", false},
                                           StressPart{"deferred", true}, StressPart{"deferred", false}),
                         [](const auto& info) { return info.param.pipeline + (info.param.long_cases ? "_long" : "_rest"); });

TEST(Stress, UnknownCaseIsOneLineExitTwoAndNoOutput) {
    auto work = cbr::test::scratchDir("stress-bad");
    auto r = runBench({"stress", "--cases", "no-such-case", "--out", (work / "out").string()}, work);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("no-such-case"), std::string::npos);
    EXPECT_FALSE(fs::exists(work / "out"));
}
