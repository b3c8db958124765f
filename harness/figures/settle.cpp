// The sequential rule of self-settling verdicts: looks, alpha per look, samples per unit.
#include "harness/figures/settle.h"

#include <algorithm>
#include <stdexcept>

#include "harness/figures/stats.h"
#include "rundir/summary_csv.h"

namespace cbr::harness {

const char* const kSettleRule =
    "Sides A (baseline) and B run in ABBA order, one process per run, so slow drift of the machine falls on both "
    "alike. After every block every undecided cell is judged by the rule above on all runs so far; a cell that "
    "concludes (SAME, SLOWER or FASTER) keeps that verdict, and the runs stop when every cell has one or the "
    "budget (runs per side, seconds) is spent. Repeated looks would inflate the false-alarm rate, so alpha is "
    "spent evenly over the planned looks (Bonferroni: alpha / looks at each; only looks at which the exact test "
    "can reach that level at all are planned): the chance of any wrong conclusion over the whole sequence stays at "
    "or below alpha however early it stops. A sample is one run's median of its per-repetition medians (unit run, "
    "the default: processes drift more than repetitions within one), or each repetition's median pooled over the "
    "runs (unit repetition). A run whose summary.csv status is unsteady is left out of the cell, so no SAME rests "
    "on it; a cell still undecided when the budget is spent is UNKNOWN and fails the check.";

SampleUnit parseSampleUnit(const std::string& text, const std::string& command) {
    if (text == "run") return SampleUnit::Run;
    if (text == "repetition") return SampleUnit::Repetition;
    throw std::invalid_argument(command + ": --unit '" + text + "': accepted: run or repetition");
}

const char* sampleUnitName(SampleUnit u) { return u == SampleUnit::Run ? "run" : "repetition"; }

namespace {

int samplesPerSide(int runs, int repeat, SampleUnit unit) { return unit == SampleUnit::Run ? runs : runs * repeat; }

// The smallest one-sided p the exact test reaches with n vs n samples (complete separation).
double minOneSidedP(int n) { return n < 1 ? 1.0 : mannWhitneyNullCdf(n, n)[0]; }

}  // namespace

LookPlan planLooks(int max_runs, int runs_per_block, int repeat, SampleUnit unit, double alpha) {
    LookPlan plan;
    plan.alpha = alpha;
    std::vector<int> candidates;  // runs per side after each block, with >= 3 samples per side
    for (int runs = runs_per_block; runs <= max_runs; runs += runs_per_block)
        if (samplesPerSide(runs, repeat, unit) >= 3) candidates.push_back(runs);
    // The most looks K such that the last K candidates can each reach alpha / K. The minimal
    // p falls with the sample count, so the looks that can reach a level are a suffix.
    auto reaching = [&](int k) {
        return int(std::count_if(candidates.begin(), candidates.end(), [&](int runs) {
            return minOneSidedP(samplesPerSide(runs, repeat, unit)) <= alpha / double(k);
        }));
    };
    int k = int(candidates.size());
    while (k > 0 && reaching(k) < k) --k;
    plan.runs.assign(candidates.end() - k, candidates.end());
    plan.alpha_per_look = k > 0 ? alpha / double(k) : alpha;
    return plan;
}

RunSample runSampleOf(const reports::RunData& d, const std::string& variant) {
    return {repetitionMedians(d, variant), reports::summaryText(d, variant, rundir::summary::kStatus) == kUnsteadyStatus};
}

TimeSamples samplesOf(const CellRuns& c, int runs, SampleUnit unit) {
    TimeSamples s;
    auto side = [&](const std::vector<RunSample>& from, std::vector<double>& to) {
        for (int i = 0; i < runs && i < int(from.size()); ++i) {
            const RunSample& r = from[size_t(i)];
            if (r.unsteady || r.reps.empty()) continue;
            if (unit == SampleUnit::Run) to.push_back(median(r.reps));
            else to.insert(to.end(), r.reps.begin(), r.reps.end());
        }
    };
    side(c.a, s.baseline);
    side(c.b, s.current);
    return s;
}

void tallyRuns(CellSettle& s, const CellRuns& c, int runs) {
    s.runs_a = s.runs_b = s.reps_a = s.reps_b = s.unsteady_a = s.unsteady_b = 0;
    auto count = [&](const std::vector<RunSample>& side, int& used, int& reps, int& unsteady) {
        for (int i = 0; i < runs && i < int(side.size()); ++i) {
            const RunSample& r = side[size_t(i)];
            if (r.unsteady) ++unsteady;
            else if (!r.reps.empty()) ++used, reps += int(r.reps.size());
        }
    };
    count(c.a, s.runs_a, s.reps_a, s.unsteady_a);
    count(c.b, s.runs_b, s.reps_b, s.unsteady_b);
}

void judgeLook(std::vector<CellSettle>& state, const std::vector<CellRuns>& cells, int runs, int look,
               const LookPlan& plan, double threshold, SampleUnit unit) {
    state.resize(cells.size());
    std::vector<size_t> open;
    std::vector<TimeSamples> samples;
    for (size_t i = 0; i < cells.size(); ++i) {
        if (state[i].decided()) continue;
        open.push_back(i);
        samples.push_back(samplesOf(cells[i], runs, unit));
    }
    const auto verdicts = judgeTimes(samples, {threshold, plan.alpha_per_look});
    for (size_t k = 0; k < open.size(); ++k) {
        CellSettle& s = state[open[k]];
        const CellRuns& c = cells[open[k]];
        s.time = verdicts[k];
        s.at_runs = runs;
        tallyRuns(s, c, runs);
        if (s.time.verdict != "UNKNOWN") s.look = look;
    }
}

bool allDecided(const std::vector<CellSettle>& state) {
    return std::all_of(state.begin(), state.end(), [](const CellSettle& s) { return s.decided(); });
}

SettleReplay replaySettle(const std::vector<CellRuns>& cells, const LookPlan& plan, double threshold, SampleUnit unit) {
    SettleReplay r;
    r.cells.resize(cells.size());
    size_t have = SIZE_MAX;
    for (const auto& c : cells) have = std::min({have, c.a.size(), c.b.size()});
    for (size_t i = 0; i < plan.runs.size(); ++i) {
        const int runs = plan.runs[i];
        if (size_t(runs) > have) break;
        judgeLook(r.cells, cells, runs, int(i) + 1, plan, threshold, unit);
        r.stopped_at_runs = runs;
        if (allDecided(r.cells)) break;
    }
    return r;
}

}  // namespace cbr::harness
