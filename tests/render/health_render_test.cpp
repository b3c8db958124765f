// Measurement health in real runs on lavapipe with validation: run.json `health` holds the
// warm-up, drift and machine figures; a run with two busy processes beside it says the
// machine was busy, marks its variants unsteady and prints one line; `unsteady` is a status
// of summary.csv, run.json and the report alike.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/render/bench_runner.h"

namespace cbr::test {
namespace {

std::vector<std::string> smallRun(const std::filesystem::path& out) {
    return {"run", "--res", "96x54", "--frames", "8", "--repeat", "3", "--warmup", "2", "--variants", "full,cbr-aso",
            "--validate", "--out", out.string()};
}

// Spinning processes, killed with the guard.
struct Spinners {
    std::vector<pid_t> pids;
    explicit Spinners(int n) {
        for (int i = 0; i < n; ++i) {
            pid_t pid = fork();
            if (pid == 0) {
                volatile unsigned long x = 0;
                for (;;) x = x + 1;
            }
            pids.push_back(pid);
        }
    }
    ~Spinners() {
        for (pid_t p : pids) kill(p, SIGKILL);
        for (pid_t p : pids) waitpid(p, nullptr, 0);
    }
};

TEST(Health, RunJsonRecordsWarmUpDriftAndTheMachine) {
    auto work = scratchDir("health-keys");
    auto r = runBench(smallRun(work / "out"), work, {"CBR_HEALTH_STATUS=on"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(work / "out" / "run.json");
    const auto& h = run["health"];
    ASSERT_TRUE(h.is_object());
    EXPECT_TRUE(h["status_gate"].get<bool>());
    ASSERT_EQ(h["variants"].size(), 2u);
    for (const auto& v : h["variants"]) {
        ASSERT_EQ(v["warm_up_frames"].size(), 3u) << v.dump();
        for (const auto& n : v["warm_up_frames"]) EXPECT_GE(n.get<int>(), 2);  // --warmup is a minimum
        EXPECT_TRUE(v["drift"]["tested"].get<bool>());
        EXPECT_EQ(v["drift"]["repetition_ratios"].size(), 3u);
        EXPECT_GE(v["drift"]["noise"].get<double>(), 0.0);
    }
    EXPECT_GT(h["machine"]["samples"].get<int>(), 1);
    EXPECT_GT(h["machine"]["cpu"]["own_cores"].get<double>(), 0.0);
    EXPECT_FALSE(h["machine"]["gpu"]["nvml"].get<bool>());  // lavapipe: no GPU to ask, not an error
    // The verdict and the statuses agree, and the line is printed exactly when there is one.
    const std::string line = h["line"];
    EXPECT_EQ(h["quiet"].get<bool>(), line.empty());
    EXPECT_EQ(r.out.find("measurement disturbed") != std::string::npos, !line.empty()) << r.out;
    auto summary = readCsv(work / "out" / "summary.csv");
    for (size_t i = 0; i < summary.rows.size(); ++i) {
        const bool unsteady = h["variants"][i]["unsteady"].get<bool>();
        EXPECT_EQ(summary.at(i, "status"), unsteady ? "unsteady" : "ok");
    }
}

TEST(Health, TwoBusyProcessesMakeTheRunBusyAndItsVariantsUnsteady) {
    auto work = scratchDir("health-busy");
    BenchResult r;
    {
        Spinners busy(2);  // two cores' worth of other work for the whole run
        r = runBench(smallRun(work / "out"), work, {"CBR_HEALTH_STATUS=on"});
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(work / "out" / "run.json");
    const auto& h = run["health"];
    EXPECT_TRUE(h["busy"].get<bool>()) << h.dump(1);
    EXPECT_FALSE(h["quiet"].get<bool>());
    EXPECT_GT(h["machine"]["cpu"]["other_cores_max"].get<double>(), h["rule"]["busy_other_cores"].get<double>());
    EXPECT_NE(r.out.find("cbrbench: measurement disturbed: the machine was busy"), std::string::npos) << r.out;
    auto summary = readCsv(work / "out" / "summary.csv");
    for (size_t i = 0; i < summary.rows.size(); ++i) {
        EXPECT_EQ(summary.at(i, "status"), "unsteady");
        EXPECT_NE(summary.at(i, "note").find("other processes used"), std::string::npos) << summary.at(i, "note");
    }
    // The frames keep their times and status: they are what was measured.
    auto frames = readCsv(work / "out" / "frames.csv");
    for (size_t i = 0; i < frames.rows.size(); ++i) EXPECT_EQ(frames.at(i, "status"), "ok");
    // The report says so at the top and in its provenance.
    const std::string page = slurp(work / "out" / "report.html");
    EXPECT_NE(page.find("<b>Measurement:</b> measurement disturbed"), std::string::npos);
    EXPECT_NE(page.find("Measurement health"), std::string::npos);
    EXPECT_EQ(run["validation"]["errors"].get<int>() + run["validation"]["warnings"].get<int>(), 0);
}

TEST(Health, StatusGateOffReportsButKeepsStatusOk) {
    auto work = scratchDir("health-gate-off");
    BenchResult r;
    {
        Spinners busy(2);
        r = runBench(smallRun(work / "out"), work, {"CBR_HEALTH_STATUS=off"});
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = readJson(work / "out" / "run.json");
    EXPECT_FALSE(run["health"]["status_gate"].get<bool>());
    EXPECT_TRUE(run["health"]["busy"].get<bool>());  // still measured and said
    auto summary = readCsv(work / "out" / "summary.csv");
    for (size_t i = 0; i < summary.rows.size(); ++i) EXPECT_EQ(summary.at(i, "status"), "ok");
}

}  // namespace
}  // namespace cbr::test
