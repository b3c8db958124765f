// What the settings may never change by being reorganised: the plan hash of every setting
// at a non-default value, the CSV headers, compare's key and run.json's settings keys,
// against values stored in tests/data/golden/settings/ (taken at commit 0e07ad7, before the
// settings table). A setting added since may add a run.json key (anywhere) and a place at
// the end of compare's key; nothing stored may change. CBR_GOLDEN_WRITE=1 rewrites the files
// from this build instead of comparing.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench_runner.h"

namespace {

namespace fs = std::filesystem;
using cbr::test::runBench;

const fs::path kGolden = fs::path(CBR_TEST_DATA) / "golden" / "settings";

enum class Match { Exact, Prefix, Subset };  // the stored lines: all of them, the first ones, or among them

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    for (size_t start = 0, end; start < text.size(); start = end + 1) {
        end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        out.push_back(text.substr(start, end - start));
    }
    return out;
}

// Compares `lines` with the golden file `name`, one value a line (or writes it).
void expectGolden(const std::string& name, const std::vector<std::string>& current, Match match = Match::Exact) {
    std::string text;
    for (const auto& l : current) text += l + "\n";
    if (const char* w = std::getenv("CBR_GOLDEN_WRITE"); w && std::string(w) == "1") {
        fs::create_directories(kGolden);
        std::ofstream(kGolden / name, std::ios::binary) << text;
        return;
    }
    ASSERT_TRUE(fs::exists(kGolden / name)) << kGolden / name;
    const std::string stored = cbr::test::slurp(kGolden / name);
    if (match == Match::Exact) {
        EXPECT_EQ(stored, text) << name;
        return;
    }
    const auto want = lines(stored);
    if (match == Match::Prefix) {
        ASSERT_GE(current.size(), want.size()) << name;
        EXPECT_EQ(std::vector<std::string>(current.begin(), current.begin() + long(want.size())), want) << name;
        return;
    }
    for (const auto& w : want)
        EXPECT_NE(std::find(current.begin(), current.end(), w), current.end()) << name << ": " << w << " missing";
}

std::vector<std::string> header(const fs::path& csv) { return cbr::test::readCsv(csv).header; }

// Every setting of run, plan and sweep at a value other than its default (one at a time),
// and the plans of the default and of a matrix.
const std::vector<std::vector<std::string>> kPlanCases = {
    {},
    {"--scene", "atrium,blocks"}, {"--path", "orbit"}, {"--pipeline", "deferred"}, {"--res", "640x360"},
    {"--pipeline", "forward,deferred", "--res", "64x36,128x72"},
    {"--variants", "drr"}, {"--frames", "30"}, {"--repeat", "3"}, {"--warmup", "2"}, {"--device", "0"},
    {"--validate"}, {"--save-frames"}, {"--export", "gbench"}, {"--out", "elsewhere"},
    {"--drr-scale", "0.5"}, {"--drr-filter", "bilinear"}, {"--drr-target-ms", "8"},
    {"--taau-scale", "0.5"}, {"--taau-phases", "16"}, {"--taau-blend", "0.25"},
    {"--shading-cost", "2"}, {"--exposure", "1.5"}, {"--cbr-route", "multiview"}, {"--cbr-history", "full"},
    {"--history-filter", "bilinear"}, {"--history-format", "rgba16f"}, {"--cbr-lod-bias", "-0.5"},
    {"--cso-tolerance", "0.1"}, {"--cso-mode", "absolute"}, {"--resolve-impl", "separate"},
    {"--target-clear", "compute"}, {"--debug-shading", "pixel-id"}, {"--debug-slowdown", "opaque=10"},
    {"--reference", "ssaa"}, {"--ssaa", "2"}, {"--flip-ppd", "30"}, {"--scorer", "cpu"},
    {"--scene-offset", "1,2,3"}, {"--scene-scale", "2"}, {"--near", "0.1"}, {"--far", "100"},
    {"--animation", "none"}, {"--fps", "30"},
};

TEST(SettingsGolden, PlanHashes) {
    auto work = cbr::test::scratchDir("settings-golden-plan");
    std::vector<std::string> lines;
    for (const auto& extra : kPlanCases) {
        std::vector<std::string> args{"plan"};
        args.insert(args.end(), extra.begin(), extra.end());
        auto r = runBench(args, work);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        std::string label;
        for (const auto& a : extra) label += (label.empty() ? "" : " ") + a;
        lines.push_back((label.empty() ? "(defaults)" : label) + "\t" + r.out.substr(0, r.out.find(':')));
    }
    expectGolden("plan_hashes.txt", lines);
}

// One small run of every variant: summary.csv's and frames.csv's headers, run.json's
// settings keys, and compare's key (the run against itself: compare.csv's settings cell).
TEST(SettingsGolden, RunHeadersAndCompareKey) {
    auto work = cbr::test::scratchDir("settings-golden-run");
    const fs::path dir = work / "run";
    auto r = runBench({"run", "--res", "64x36", "--frames", "3", "--repeat", "1", "--warmup", "0", "--out", dir.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expectGolden("summary_header.txt", header(dir / "summary.csv"));
    expectGolden("frames_header.txt", header(dir / "frames.csv"));
    auto run = nlohmann::json::parse(cbr::test::slurp(dir / "run.json"));
    std::vector<std::string> keys;
    for (const auto& [k, v] : run.at("settings").items()) keys.push_back(k);
    expectGolden("run_json_settings.txt", keys, Match::Subset);

    auto c = runBench({"compare", dir.string(), dir.string()}, work);
    // One repetition per side decides no time verdict: inconclusive (2), compare.csv written.
    ASSERT_EQ(c.exit_code, 2) << c.err;
    auto csv = cbr::test::readCsv(dir / "compare.csv");
    ASSERT_FALSE(csv.rows.empty());
    std::vector<std::string> key;
    std::string cell = csv.at(0, "settings");
    for (size_t start = 0; start <= cell.size();) {
        size_t end = cell.find(';', start);
        key.push_back(cell.substr(start, end == std::string::npos ? std::string::npos : end - start));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    expectGolden("compare_key.txt", key, Match::Prefix);
}

// sweep.csv's header, from a sweep small enough to run in seconds.
TEST(SettingsGolden, SweepHeader) {
    auto work = cbr::test::scratchDir("settings-golden-sweep");
    const fs::path dir = work / "sweep";
    auto r = runBench({"sweep", "--res", "64x36", "--frames", "3", "--repeat", "1", "--warmup", "0", "--variants", "drr",
                       "--param", "drr-scale=0.5,1", "--out", dir.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expectGolden("sweep_header.txt", header(dir / "sweep.csv"));
}

}  // namespace
