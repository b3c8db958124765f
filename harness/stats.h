// Order statistics and the bootstrap used for timing summaries (method/timing.md).
#pragma once

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

}  // namespace cbr::harness
