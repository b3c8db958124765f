// The sequential rule of self-settling verdicts (harness/figures/settle.h): the looks and the
// alpha each gets, the samples per unit, unsteady runs, kept verdicts, and the false-alarm rate
// over all looks on simulated A/A sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "harness/figures/settle.h"
#include "harness/figures/stats.h"

using namespace cbr::harness;

namespace {

// One run: `reps` repetition medians around `ms`, spread by `noise` (relative, lognormal).
RunSample run(std::mt19937_64& rng, double ms, double noise, int reps = 3) {
    std::normal_distribution<double> z(0, 1);
    RunSample r;
    for (int i = 0; i < reps; ++i) r.reps.push_back(ms * std::exp(noise * z(rng)));
    return r;
}

CellRuns cell(std::mt19937_64& rng, int runs, double a_ms, double b_ms, double noise) {
    CellRuns c;
    for (int i = 0; i < runs; ++i) c.a.push_back(run(rng, a_ms, noise)), c.b.push_back(run(rng, b_ms, noise));
    return c;
}

}  // namespace

TEST(Settle, LooksSpendAlphaEvenlyOverLooksThatCanReachIt) {
    // Run unit, 12 runs per side: looks after blocks at 4, 6, ..., 12 runs; 4 runs can reach
    // 1/70 = 0.014 at best, not 0.05 / 5 = 0.01 nor 0.05 / 4 = 0.0125: looks at 6..12.
    LookPlan p = planLooks(12, 2, 3, SampleUnit::Run, 0.05);
    EXPECT_EQ(p.runs, (std::vector<int>{6, 8, 10, 12}));
    EXPECT_DOUBLE_EQ(p.alpha_per_look, 0.0125);
    EXPECT_NEAR(p.alpha_per_look * double(p.runs.size()), 0.05, 1e-12);
    for (int runs : p.runs) EXPECT_LE(mannWhitneyNullCdf(runs, runs)[0], p.alpha_per_look) << runs;
    // The smallest budgets: 2 runs (2 samples) cannot reach any level; 4 runs one look at alpha.
    EXPECT_TRUE(planLooks(2, 2, 3, SampleUnit::Run, 0.05).runs.empty());
    LookPlan four = planLooks(4, 2, 3, SampleUnit::Run, 0.05);
    EXPECT_EQ(four.runs, (std::vector<int>{4}));
    EXPECT_DOUBLE_EQ(four.alpha_per_look, 0.05);
    // Repetition unit: 2 runs of 3 repetitions are 6 samples per side, a look after every block.
    LookPlan reps = planLooks(6, 2, 3, SampleUnit::Repetition, 0.05);
    EXPECT_EQ(reps.runs, (std::vector<int>{2, 4, 6}));
    EXPECT_NEAR(reps.alpha_per_look, 0.05 / 3, 1e-12);
}

TEST(Settle, SamplesPerUnitLeaveUnsteadyRunsOut) {
    CellRuns c;
    c.a = {{{1, 2, 3}, false}, {{10, 20, 30}, true}, {{4, 5, 6}, false}};
    c.b = {{{7, 8, 9}, false}};
    TimeSamples run = samplesOf(c, 3, SampleUnit::Run);
    EXPECT_EQ(run.baseline, (std::vector<double>{2, 5}));  // the unsteady run left out
    EXPECT_EQ(run.current, (std::vector<double>{8}));
    TimeSamples rep = samplesOf(c, 2, SampleUnit::Repetition);
    EXPECT_EQ(rep.baseline, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(rep.current, (std::vector<double>{7, 8, 9}));
}

TEST(Settle, ClearSlowdownSettlesAtTheFirstLookAndStays) {
    std::mt19937_64 rng(7);
    std::vector<CellRuns> cells = {cell(rng, 12, 10.0, 12.0, 0.01), cell(rng, 12, 10.0, 10.0, 0.001)};
    const LookPlan plan = planLooks(12, 2, 3, SampleUnit::Run, 0.05);
    SettleReplay r = replaySettle(cells, plan, 0.03, SampleUnit::Run);
    EXPECT_EQ(r.cells[0].time.verdict, "SLOWER");
    EXPECT_EQ(r.cells[1].time.verdict, "SAME");
    EXPECT_EQ(r.stopped_at_runs, 6);
    EXPECT_EQ(r.cells[0].look, 1);
    EXPECT_EQ(r.cells[0].runs_a, 6);
    // A kept verdict: later runs that would make the cell UNKNOWN do not undo it.
    std::vector<CellSettle> state = r.cells;
    std::vector<CellRuns> later = cells;
    for (auto& c : later)
        for (int i = 0; i < 6; ++i) c.b.push_back({{5.0, 30.0, 5.0}, false}), c.a.push_back({{30.0, 5.0, 30.0}, false});
    judgeLook(state, later, 18, 2, plan, 0.03, SampleUnit::Run);
    EXPECT_EQ(state[0].time.verdict, "SLOWER");
    EXPECT_EQ(state[0].look, 1);
}

TEST(Settle, UnsteadyRunsNeverMakeASame) {
    std::mt19937_64 rng(11);
    CellRuns c = cell(rng, 12, 10.0, 10.0, 0.001);
    for (auto& r : c.b) r.unsteady = true;
    SettleReplay r = replaySettle({c}, planLooks(12, 2, 3, SampleUnit::Run, 0.05), 0.03, SampleUnit::Run);
    EXPECT_EQ(r.cells[0].time.verdict, "UNKNOWN");
    EXPECT_FALSE(r.cells[0].decided());
    EXPECT_EQ(r.cells[0].unsteady_b, 12);
    EXPECT_EQ(r.cells[0].runs_b, 0);
}

// A/A sequences with a threshold near 0 (so a wrong SLOWER or FASTER is a plain test's false
// alarm): over all looks the rate stays at or below alpha with the per-look level, and looking
// four times at the full alpha would not (the reason for the correction).
TEST(Settle, FalseAlarmRateOverAllLooksStaysAtAlpha) {
    std::mt19937_64 rng(2024);
    const LookPlan plan = planLooks(12, 2, 3, SampleUnit::Run, 0.05);
    LookPlan naive = plan;
    naive.alpha_per_look = 0.05;
    const int sequences = 1500;
    int wrong = 0, naive_wrong = 0;
    for (int i = 0; i < sequences; ++i) {
        std::vector<CellRuns> cells = {cell(rng, 12, 10.0, 10.0, 0.05)};
        auto falseAlarm = [&](const LookPlan& p) {
            const std::string v = replaySettle(cells, p, 1e-6, SampleUnit::Run).cells[0].time.verdict;
            return v == "SLOWER" || v == "FASTER";
        };
        wrong += falseAlarm(plan);
        naive_wrong += falseAlarm(naive);
    }
    const double rate = double(wrong) / sequences, naive_rate = double(naive_wrong) / sequences;
    EXPECT_LE(rate, 0.05 + 3 * std::sqrt(0.05 * 0.95 / sequences)) << rate;
    EXPECT_GT(naive_rate, rate) << naive_rate;
}

// The case: +2.1% with 0.0% noise is SAME under 3%, and says the noise resolves far less.
TEST(Settle, SameUnderAWideThresholdSaysWhatTheNoiseResolves) {
    TimeSamples s;
    for (int i = 0; i < 10; ++i) s.baseline.push_back(10.0 * (1 + 1e-4 * i)), s.current.push_back(10.21 * (1 + 1e-4 * i));
    const TimeVerdict v = judgeTimes({s}, {0.03, 0.05})[0];
    EXPECT_EQ(v.verdict, "SAME");
    ASSERT_TRUE(v.resolution);
    EXPECT_LT(*v.resolution, 0.003);
    EXPECT_NE(v.note.find("resolves"), std::string::npos) << v.note;
    EXPECT_NE(v.note.find("excludes 0"), std::string::npos) << v.note;
}
