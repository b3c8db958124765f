// `cbrbench calibrate` end to end on lavapipe: A/A pairs and an injected slowdown through
// compare's rule, rates with intervals in calibrate.csv, every verdict in
// calibrate_pairs.csv; bad options refused before anything is written. The rates
// themselves are timings (they live in docs/results/current.md's calibration tables, not in asserts).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::runBench;

TEST(Calibrate, WritesRatesPerKindAndRepetitionCount) {
    auto work = cbr::test::scratchDir("calibrate");
    auto out = work / "cal";
    auto r = runBench({"calibrate", "--scene", "blocks", "--path", "orbit", "--res", "64x48", "--frames", "4",
                       "--warmup", "2", "--validate", "--pairs", "2", "--slow-pairs", "1", "--slowdown", "opaque=50",
                       "--repeats", "3,4", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    auto rates = cbr::test::readCsv(out / "calibrate.csv");
    // (A/A, opaque=50) x (3, 4 repetitions).
    ASSERT_EQ(rates.rows.size(), 4u);
    std::set<std::string> kinds;
    for (size_t i = 0; i < rates.rows.size(); ++i) {
        kinds.insert(rates.at(i, "kind"));
        const bool aa = rates.at(i, "kind") == "aa";
        EXPECT_EQ(rates.at(i, "pairs"), aa ? "2" : "1");
        double rate = std::stod(rates.at(i, "rate")), lo = std::stod(rates.at(i, "rate_low")),
               hi = std::stod(rates.at(i, "rate_high"));
        EXPECT_LE(0.0, lo);
        EXPECT_LE(lo, rate);
        EXPECT_LE(rate, hi);
        EXPECT_LE(hi, 1.0);
        EXPECT_GT(hi - lo, 0.3) << "a Wilson interval over 1 or 2 pairs is wide";
    }
    EXPECT_EQ(kinds, (std::set<std::string>{"aa", "opaque=50"}));
    // Every pair's verdict at every count, and the same rule as compare's.
    auto pairs = cbr::test::readCsv(out / "calibrate_pairs.csv");
    EXPECT_EQ(pairs.rows.size(), 6u);  // (2 A/A + 1 slowdown) x 2 counts x 1 variant (full)
    for (size_t i = 0; i < pairs.rows.size(); ++i) {
        auto v = pairs.at(i, "verdict");
        EXPECT_TRUE(v == "SAME" || v == "SLOWER" || v == "FASTER" || v == "UNKNOWN") << v;
        EXPECT_EQ(pairs.at(i, "variant"), "full");
    }
    auto j = nlohmann::json::parse(std::ifstream(out / "calibrate.json"));
    EXPECT_NE(j["rule"].get<std::string>().find("Hodges-Lehmann"), std::string::npos);
    // Every run: validation layer silent, 4 repetitions (the largest count).
    int runs = 0;
    for (const auto& d : fs::directory_iterator(out / "runs")) {
        auto run = nlohmann::json::parse(std::ifstream(d.path() / "run.json"));
        EXPECT_EQ(run["validation"]["errors"], 0) << d.path();
        EXPECT_EQ(run["validation"]["warnings"], 0) << d.path();
        EXPECT_EQ(run["settings"]["repeat"], 4) << d.path();
        ++runs;
    }
    EXPECT_EQ(runs, 5);  // 2 baselines, 2 A/A twins, 1 slowed

    // The same runs judged again without rendering: another threshold and count.
    auto again = work / "again";
    auto r2 = runBench({"calibrate", "--from", out.string(), "--repeats", "3", "--threshold", "50%", "--out",
                        again.string()},
                       work);
    ASSERT_EQ(r2.exit_code, 0) << r2.out << r2.err;
    auto rates2 = cbr::test::readCsv(again / "calibrate.csv");
    ASSERT_EQ(rates2.rows.size(), 2u);  // aa and opaque=50 at 3 repetitions
    for (size_t i = 0; i < rates2.rows.size(); ++i) EXPECT_EQ(rates2.at(i, "repeats"), "3");
    EXPECT_FALSE(fs::exists(again / "runs"));
    // More repetitions than the runs have: one line, nothing written.
    auto more = work / "more";
    auto r3 = runBench({"calibrate", "--from", out.string(), "--repeats", "3,6", "--out", more.string()}, work);
    EXPECT_EQ(r3.exit_code, 2) << r3.err;
    EXPECT_NE(r3.err.find("repetitions"), std::string::npos) << r3.err;
    EXPECT_EQ(std::count(r3.err.begin(), r3.err.end(), '\n'), 1) << r3.err;
    EXPECT_FALSE(fs::exists(more));
}

TEST(Calibrate, BadOptionsAreOneLineAndNoOutput) {
    auto work = cbr::test::scratchDir("calibrate-bad");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--repeats", "2,5"}, "--repeats"},
        {{"--slowdown", "opaque"}, "PASS=PCT"},
        {{"--slowdown", "opaque=-3"}, "--slowdown"},
        {{"--slowdown", "nosuchpass=10"}, "nosuchpass"},
        {{"--threshold", "x%"}, "--threshold"},
        {{"--pairs", "0"}, "--pairs"},
    };
    for (const auto& [args, mention] : cases) {
        auto out = work / "cal";
        std::vector<std::string> all = {"calibrate", "--res", "64x48", "--frames", "4", "--out", out.string()};
        all.insert(all.end(), args.begin(), args.end());
        auto r = runBench(all, work);
        EXPECT_EQ(r.exit_code, 2) << args[1] << ": " << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(out)) << args[1];
    }
}

// --settle: every pair an `ab --no-stop` run to its budget, replayed with both sample units;
// the replay with unit run gives exactly the verdicts ab printed itself.
TEST(Calibrate, SettleReplaysAbWithBothUnits) {
    auto work = cbr::test::scratchDir("calibrate-settle");
    auto out = work / "cal";
    auto r = runBench({"calibrate", "--settle", "--scene", "blocks", "--path", "orbit", "--res", "64x36", "--frames",
                       "4", "--warmup", "2", "--validate", "--pairs", "1", "--slow-pairs", "1", "--slowdown",
                       "opaque=400", "--repeats", "3", "--max-runs", "4", "--threshold", "50%", "--out", out.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    auto rates = cbr::test::readCsv(out / "calibrate_settle.csv");
    ASSERT_EQ(rates.rows.size(), 4u);  // (run, repetition) x (aa, opaque=400)
    std::set<std::string> seen;
    for (size_t i = 0; i < rates.rows.size(); ++i) {
        seen.insert(rates.at(i, "unit") + " " + rates.at(i, "kind"));
        EXPECT_EQ(rates.at(i, "pairs"), "1");
        EXPECT_EQ(rates.at(i, "max_runs"), "4");
    }
    EXPECT_EQ(seen, (std::set<std::string>{"run aa", "run opaque=400", "repetition aa", "repetition opaque=400"}));
    auto pairs = cbr::test::readCsv(out / "calibrate_settle_pairs.csv");
    ASSERT_EQ(pairs.rows.size(), 4u);  // one variant (full) per pair and unit
    for (size_t i = 0; i < pairs.rows.size(); ++i) {
        if (pairs.at(i, "unit") != "run") continue;
        EXPECT_EQ(pairs.at(i, "verdict"), pairs.at(i, "ab_verdict")) << i;
    }
    // Each pair ran its whole budget: 4 runs per side, ABBA.
    for (const char* pair : {"aa-000", "slow-opaque-400-000"}) {
        auto ab = nlohmann::json::parse(std::ifstream(out / "settles" / pair / "ab.json"));
        EXPECT_EQ(ab["runs_per_side"], 4) << pair;
        EXPECT_EQ(ab["runs"][1], "b-00") << pair;
    }
}
