// Medians, percentiles, coefficient of variation, run-level bootstrap.
#include "harness/stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace cbr::harness {

double percentile(std::vector<double> v, double p) {
    if (v.empty()) throw std::invalid_argument("percentile of an empty series");
    std::sort(v.begin(), v.end());
    double pos = std::clamp(p, 0.0, 100.0) / 100.0 * double(v.size() - 1);
    size_t lo = size_t(std::floor(pos));
    size_t hi = std::min(lo + 1, v.size() - 1);
    // Equal neighbours (e.g. two +inf PSNRs) must not interpolate to inf - inf = NaN.
    if (v[lo] == v[hi]) return v[lo];
    return v[lo] + (v[hi] - v[lo]) * (pos - double(lo));
}

double median(std::vector<double> v) { return percentile(std::move(v), 50.0); }

double mean(const std::vector<double>& v) {
    if (v.empty()) throw std::invalid_argument("mean of an empty series");
    return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

double coefficientOfVariation(const std::vector<double>& v) {
    if (v.size() < 2) return 0;
    double m = mean(v);
    double ss = 0;
    for (double x : v) ss += (x - m) * (x - m);
    double sd = std::sqrt(ss / double(v.size() - 1));
    return m != 0 ? sd / m : 0;
}

Interval bootstrapMedianOverRuns(const std::vector<std::vector<double>>& runs, int resamples, double confidence,
                                 uint64_t seed) {
    if (runs.size() < 2) throw std::invalid_argument("bootstrap over runs needs at least 2 runs");
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<size_t> pick(0, runs.size() - 1);
    std::vector<double> medians;
    medians.reserve(size_t(resamples));
    std::vector<double> pooled;
    for (int b = 0; b < resamples; ++b) {
        pooled.clear();
        for (size_t r = 0; r < runs.size(); ++r) {
            const auto& run = runs[pick(rng)];
            pooled.insert(pooled.end(), run.begin(), run.end());
        }
        medians.push_back(median(pooled));
    }
    double tail = (1.0 - confidence) / 2.0 * 100.0;
    return {percentile(medians, tail), percentile(medians, 100.0 - tail)};
}

}  // namespace cbr::harness
