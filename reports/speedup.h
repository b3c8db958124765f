// The speed-up against the reference, as every output prints it: the terminal summary, the
// report, sweep.html and the exports (docs/method/measurement.md, "Runs, repetitions and
// speed-ups"). It is computed once, in harness/output/outputs.cpp (summary.csv
// speedup_vs_full, speedup_ci_low, speedup_ci_high): the median of the paired per-frame
// ratios full_ms / variant_ms at the same camera pose, with a 95% percentile-bootstrap
// interval over whole repetitions. Nothing else is a speed-up: a ratio of two medians is not.
#pragma once

#include <optional>
#include <string>

namespace cbr::reports {

struct Speedup {
    std::optional<double> value, low, high;  // the median paired ratio and its 95% interval
};

// Decimals of every printed speed-up ("1.29x").
inline constexpr int kSpeedupDecimals = 2;

// "1.29x [1.27, 1.31]"; "1.29x" without an interval (one repetition); `missing` without a value.
std::string speedupText(const Speedup& s, const char* missing);
// "1.29x": where only the number fits.
std::string speedupValueText(std::optional<double> value, const char* missing);

// Measurably faster than the reference: the speed-up is above 1 and so is its interval's
// lower end, where there is one (timing.md: report only significant differences).
bool measurablyFaster(const Speedup& s);

}  // namespace cbr::reports
