// Time verdicts from the uncertainty of a change (method/timing.md, "Regression verdicts"):
// the rule `compare` applies per cell and `calibrate` measures, and the samples and
// thresholds both read the same way.
#pragma once

#include <climits>
#include <optional>
#include <string>
#include <vector>

#include "harness/figures/stats.h"
#include "reports/report_data.h"

namespace cbr::harness {

// summary.csv's status of a variant whose timed frames drifted or ramped: never SAME.
inline constexpr const char* kUnsteadyStatus = "unsteady";

// The rule, stated once: compare.html, the printed output and docs/method/measurement.md say the same.
extern const char* const kTimeRule;

struct VerdictRule {
    double threshold = 0.03;  // relative time change that counts
    double alpha = 0.05;      // false discovery rate across the cells judged together
};

// One cell's samples: the per-repetition medians of the frame time, each side.
struct TimeSamples {
    std::vector<double> baseline, current;
};

struct TimeVerdict {
    std::string verdict = "UNKNOWN";  // SLOWER, FASTER, SAME or UNKNOWN
    std::optional<double> change;     // median(current) / median(baseline) - 1
    std::optional<ChangeInterval> interval;  // Hodges-Lehmann estimate and interval
    std::optional<double> noise;      // coefficient of variation, the larger side
    std::optional<double> p, q;       // the likeliest conclusion's one-sided p, BH q
    std::optional<double> detectable; // smallest change these repetitions would call SLOWER
    std::optional<double> resolution; // smallest change the noise could show at all: the interval's half-width
    std::optional<int> reps_needed;   // UNKNOWN: repetitions per side likely to settle it
    std::string note;
};

// Judges every cell together: per cell the one-sided exact Mann-Whitney tests of "above
// +threshold" (SLOWER), "below -threshold" (FASTER) and "inside +-threshold" (SAME, both
// one-sided tests), the smallest p of the three as the cell's p, Benjamini-Hochberg over
// the cells. A cell gets its conclusion when q <= alpha, else UNKNOWN. The interval shown is
// at confidence 1 - 2 alpha R / m (R cells concluded of m; Benjamini-Yekutieli's false
// coverage rate), so a concluded cell's interval lies wholly beyond (SLOWER, FASTER) or
// inside (SAME) the threshold, and an UNKNOWN cell's straddles a boundary.
std::vector<TimeVerdict> judgeTimes(const std::vector<TimeSamples>& cells, const VerdictRule& rule);

// A quality verdict of one cell from summary.csv: BETTER, WORSE or SAME when the value changed
// by more than the threshold (absolute, or relative to the baseline), n/a where a side has none.
struct QualityVerdict {
    std::optional<double> base, cur, delta;
    std::string verdict = "n/a";
};
// Higher is better for PSNR and SSIM (absolute threshold), lower for ECI (relative).
void judgeQuality(QualityVerdict& q, bool higher_better, double threshold, bool relative);

// "3%" or "0.03" -> 0.03; anything else throws std::invalid_argument naming COMMAND, the
// option and what is accepted.
double parseFraction(const std::string& text, const std::string& command, const std::string& option);

// A cell's samples: the median gpu_ms of each repetition (frames.csv rows with status ok)
// of `variant`, repetitions 0 .. max_repeats - 1 (a run's first repetitions are what a
// shorter run would have measured: calibrate judges several counts from one run).
std::vector<double> repetitionMedians(const reports::RunData& d, const std::string& variant, int max_repeats = INT_MAX);

}  // namespace cbr::harness
