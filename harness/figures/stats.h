// Order statistics and the bootstrap used for timing summaries (method/timing.md).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace cbr::harness {

double median(std::vector<double> v);
// Linear interpolation between order statistics (numpy's default), p in [0, 100].
double percentile(std::vector<double> v, double p);
double mean(const std::vector<double>& v);
// Coefficient of variation (sample standard deviation / mean); 0 for fewer than 2 values.
double coefficientOfVariation(const std::vector<double>& v);

struct Interval {
    double low = 0;
    double high = 0;
};
// Percentile bootstrap of the median of pooled per-frame ratios, resampling whole runs
// (frames of one run are not independent). `runs[r]` holds run r's per-frame ratios.
// Deterministic (fixed seed). Needs at least 2 runs.
Interval bootstrapMedianOverRuns(const std::vector<std::vector<double>>& runs, int resamples = 2000,
                                 double confidence = 0.95, uint64_t seed = 0x5eed);

// Wilson score interval for k successes of n at 95% ({0, 1} for n = 0).
Interval wilsonInterval(int k, int n);

// Mann-Whitney U test, two-sided, of x against y (regression verdicts, method/timing.md).
// Exact: the permutation distribution of the rank sum of x, midranks for ties, counted
// by dynamic programming over all C(n, nx) splits (what scipy's method='exact' gives
// without ties). Used up to 60 values in all; above that the normal approximation with
// tie correction and continuity correction. p = min(1, 2 min(P(W <= w), P(W >= w))).
// 1.0 when either side is empty.
double mannWhitneyTwoSided(const std::vector<double>& x, const std::vector<double>& y);
// The smallest two-sided p any nx vs ny comparison can reach (complete separation):
// 2 / C(nx + ny, nx). With 3 vs 3 it is 0.1, so no such cell can pass alpha 0.05.
double mannWhitneyMinP(int nx, int ny);
// Benjamini-Hochberg adjusted p-values (q-values), in the input's order: q_(i) =
// min over j >= i of p_(j) m / j on the ascending order, capped at 1.
std::vector<double> benjaminiHochberg(const std::vector<double>& p);

// The null distribution of the Mann-Whitney count U (pairs with x_i > y_j, no ties) for
// nx vs ny values: cdf[u] = P(U <= u), u = 0 .. nx * ny. Exact (counts of rank sums by
// dynamic programming) up to 120 values in all, above that the normal approximation with
// continuity correction. Cached per size.
const std::vector<double>& mannWhitneyNullCdf(int nx, int ny);

// A change of `current` against `baseline` (positive values, e.g. per-repetition median
// frame times) on the log scale, so that it reads as a ratio: the Hodges-Lehmann estimate
// (median of the nx * ny pairwise differences log c_i - log b_j) with the exact
// Mann-Whitney confidence interval (Lehmann 1975; Hollander & Wolfe ch. 4.3): the k-th
// smallest and k-th largest difference, k the largest with P(U <= k - 1) <= (1 - confidence) / 2.
// The discrete distribution gives an achieved confidence >= the requested one; too few
// values for the requested one give an unbounded interval (3 vs 3 reaches 90%, not 95%).
// Relative changes: low, estimate, high are ratio - 1.
struct ChangeInterval {
    double estimate = 0;
    double low = -1;        // -1 (ratio 0) when unbounded below
    double high = INFINITY; // +inf when unbounded above
    double confidence = 0;  // achieved; 0 when unbounded
    bool bounded() const { return confidence > 0; }
};
ChangeInterval changeInterval(const std::vector<double>& baseline, const std::vector<double>& current,
                              double confidence);

// One-sided exact p-values of the Mann-Whitney test with the shift moved to `change`
// (relative, > -1): the evidence that the true change lies above it, resp. below it
// (H0: change <= `change`, resp. >= `change`). Consistent with changeInterval: the
// interval at confidence 1 - 2a lies wholly above `change` exactly when
// changeAboveP(...) <= a (without ties among the pairwise differences).
double changeAboveP(const std::vector<double>& baseline, const std::vector<double>& current, double change);
double changeBelowP(const std::vector<double>& baseline, const std::vector<double>& current, double change);

}  // namespace cbr::harness
