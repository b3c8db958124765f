// Verdicts that settle themselves (method/timing.md, "A/B of two builds"): compare's rule
// applied at planned looks as runs accumulate, with the false-alarm rate held across the
// looks. Pure functions over samples: `ab` renders and calls them after each ABBA block,
// `calibrate --settle` replays them over runs it rendered, the unit tests call them directly.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/figures/verdict.h"

namespace cbr::harness {

// The rule's words for the looks, as the pages and docs print them (beside kTimeRule).
extern const char* const kSettleRule;

// What one sample is. `Run`: a run's (process's) median of its per-repetition medians, one
// sample per process, so the drift between processes is inside the spread the interval is
// built from. `Repetition`: every repetition's median pooled over the runs: more samples,
// but repetitions of one process share its drift and the interval comes out too narrow
// across processes (docs/method/measurement.md measures both).
enum class SampleUnit { Run, Repetition };
SampleUnit parseSampleUnit(const std::string& text, const std::string& command);  // "run" or "repetition"
const char* sampleUnitName(SampleUnit u);

// The looks: after every ABBA block (2 runs per side) up to `max_runs` per side, keeping
// only the looks at which the exact test can reach the per-look level at all. The false-alarm
// rate is spent evenly over the looks kept (Bonferroni: alpha / looks each), so the chance of
// any wrong conclusion over all of them stays at or below alpha however early it stops.
struct LookPlan {
    std::vector<int> runs;     // runs per side at each look, ascending
    double alpha_per_look = 0;
    double alpha = 0;
};
LookPlan planLooks(int max_runs, int runs_per_block, int repeat, SampleUnit unit, double alpha);

// One run of one side, for one cell: its per-repetition medians, and whether the run said its
// timed frames were unsteady (summary.csv status `unsteady`): such a run is left out of the
// cell, never counted towards a SAME.
struct RunSample {
    std::vector<double> reps;
    bool unsteady = false;
};

// A run directory's sample of one variant: repetitionMedians, and its summary.csv status.
RunSample runSampleOf(const reports::RunData& d, const std::string& variant);

// A cell's runs so far, side A (the baseline) and side B.
struct CellRuns {
    std::vector<RunSample> a, b;
};

// The samples of the first `runs` runs per side, by unit, unsteady runs left out.
TimeSamples samplesOf(const CellRuns& c, int runs, SampleUnit unit);

// Where a cell stands: its verdict as of the look that decided it (kept from then on), or as
// of the last look while undecided.
struct CellSettle {
    TimeVerdict time;
    int runs_a = 0, runs_b = 0;        // runs used per side (steady ones)
    int reps_a = 0, reps_b = 0;        // repetitions those runs hold
    int unsteady_a = 0, unsteady_b = 0;  // runs left out as unsteady
    int look = 0;                      // 1-based look that decided it (0: undecided)
    int at_runs = 0;                   // runs per side (steady or not) its verdict was judged on
    bool decided() const { return look > 0; }
};

// Counts the first `runs` runs per side into `s` (used, their repetitions, unsteady ones).
void tallyRuns(CellSettle& s, const CellRuns& c, int runs);

// Judges the undecided cells on the first `runs` runs per side, at the plan's level per look
// (Benjamini-Hochberg across the cells judged together at that look); a cell that concludes keeps
// its verdict. `look` is the 1-based look number.
void judgeLook(std::vector<CellSettle>& state, const std::vector<CellRuns>& cells, int runs, int look,
               const LookPlan& plan, double threshold, SampleUnit unit);

bool allDecided(const std::vector<CellSettle>& state);

// The whole sequence from runs already rendered (each side holding at least the plan's last
// look's runs, or fewer: the looks beyond are skipped): what `ab` would have decided, and at
// which look it would have stopped (0: never, the budget spent).
struct SettleReplay {
    std::vector<CellSettle> cells;
    int stopped_at_runs = 0;  // runs per side when every cell was decided, else the last look's
};
SettleReplay replaySettle(const std::vector<CellRuns>& cells, const LookPlan& plan, double threshold, SampleUnit unit);

}  // namespace cbr::harness
