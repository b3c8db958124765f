// Medians, percentiles, coefficient of variation, run-level bootstrap.
#include "harness/figures/stats.h"

#include <algorithm>
#include <map>
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

namespace cbr::harness {

namespace {

// Above this many values in all the exact count table gets large; normal approximation.
constexpr size_t kExactLimit = 60;

double normalTail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

}  // namespace

double mannWhitneyMinP(int nx, int ny) {
    if (nx <= 0 || ny <= 0) return 1.0;
    // C(nx + ny, nx) as a double: exact enough for the sizes this is used with.
    double combos = 1;
    for (int i = 1; i <= nx; ++i) combos = combos * double(ny + i) / double(i);
    return std::min(1.0, 2.0 / combos);
}

double mannWhitneyTwoSided(const std::vector<double>& x, const std::vector<double>& y) {
    const size_t nx = x.size(), ny = y.size(), n = nx + ny;
    if (nx == 0 || ny == 0) return 1.0;
    // Midranks, doubled so ties stay integers: rank r (1-based) of a group spanning
    // sorted positions [i, j) is (i + 1 + j), i.e. twice the mean rank.
    std::vector<std::pair<double, int>> all;
    for (double v : x) all.push_back({v, 0});
    for (double v : y) all.push_back({v, 1});
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<int> rank2(n);
    std::vector<int> is_x(n);
    double tie_term = 0;  // sum of t^3 - t over tie groups
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && all[j].first == all[i].first) ++j;
        for (size_t k = i; k < j; ++k) rank2[k] = int(i + 1 + j), is_x[k] = all[k].second == 0;
        double t = double(j - i);
        tie_term += t * t * t - t;
        i = j;
    }
    long w2 = 0;  // doubled rank sum of x
    for (size_t k = 0; k < n; ++k)
        if (is_x[k]) w2 += rank2[k];

    if (n <= kExactLimit) {
        // ways[k][s]: subsets of k values whose doubled ranks sum to s. Counts reach
        // C(60, 30) ~ 1.2e17, so doubles (exact to 2^53, relative 1e-16 above) suffice.
        const long max_sum = long(n) * long(n + 1);
        std::vector<std::vector<double>> ways(nx + 1, std::vector<double>(size_t(max_sum + 1), 0.0));
        ways[0][0] = 1;
        for (size_t item = 0; item < n; ++item)
            for (size_t k = std::min(nx, item + 1); k >= 1; --k)
                for (long s = max_sum; s >= rank2[item]; --s) ways[k][size_t(s)] += ways[k - 1][size_t(s - rank2[item])];
        double total = 0, low = 0, high = 0;
        for (long s = 0; s <= max_sum; ++s) {
            double c = ways[nx][size_t(s)];
            total += c;
            if (s <= w2) low += c;
            if (s >= w2) high += c;
        }
        return std::min(1.0, 2.0 * std::min(low, high) / total);
    }
    double u = double(w2) / 2.0 - double(nx) * double(nx + 1) / 2.0;
    double mu = double(nx) * double(ny) / 2.0;
    double var = double(nx) * double(ny) / 12.0 * (double(n + 1) - tie_term / (double(n) * double(n - 1)));
    if (var <= 0) return 1.0;
    double z = (std::abs(u - mu) - 0.5) / std::sqrt(var);
    return std::min(1.0, 2.0 * normalTail(std::max(z, 0.0)));
}

std::vector<double> benjaminiHochberg(const std::vector<double>& p) {
    const size_t m = p.size();
    std::vector<size_t> order(m);
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
    std::vector<double> q(m);
    double running = 1.0;
    for (size_t i = m; i-- > 0;) {
        running = std::min(running, p[order[i]] * double(m) / double(i + 1));
        q[order[i]] = std::min(1.0, running);
    }
    return q;
}

const std::vector<double>& mannWhitneyNullCdf(int nx, int ny) {
    static std::map<std::pair<int, int>, std::vector<double>> cache;
    if (nx < 1 || ny < 1) throw std::invalid_argument("Mann-Whitney distribution needs at least one value per side");
    auto [it, fresh] = cache.try_emplace({nx, ny});
    std::vector<double>& cdf = it->second;
    if (!fresh) return cdf;
    const int n = nx + ny, top = nx * ny;
    cdf.assign(size_t(top) + 1, 0.0);
    if (n <= 120) {
        // ways[k][w]: subsets of k of the ranks 1..item with rank sum w; U = W - nx(nx+1)/2.
        const int max_sum = n * (n + 1) / 2;
        std::vector<std::vector<double>> ways(size_t(nx) + 1, std::vector<double>(size_t(max_sum) + 1, 0.0));
        ways[0][0] = 1;
        for (int rank = 1; rank <= n; ++rank)
            for (int k = std::min(nx, rank); k >= 1; --k)
                for (int w = max_sum; w >= rank; --w) ways[size_t(k)][size_t(w)] += ways[size_t(k - 1)][size_t(w - rank)];
        const int offset = nx * (nx + 1) / 2;
        double total = 0;
        for (int u = 0; u <= top; ++u) total += ways[size_t(nx)][size_t(u + offset)];
        double running = 0;
        for (int u = 0; u <= top; ++u) {
            running += ways[size_t(nx)][size_t(u + offset)];
            cdf[size_t(u)] = std::min(1.0, running / total);
        }
    } else {
        const double mu = double(top) / 2.0, sd = std::sqrt(double(nx) * double(ny) * double(n + 1) / 12.0);
        for (int u = 0; u <= top; ++u) cdf[size_t(u)] = 1.0 - normalTail((double(u) + 0.5 - mu) / sd);
    }
    cdf[size_t(top)] = 1.0;
    return cdf;
}

namespace {

// The sorted pairwise differences log c_i - log b_j.
std::vector<double> logDifferences(const std::vector<double>& baseline, const std::vector<double>& current) {
    if (baseline.empty() || current.empty()) throw std::invalid_argument("a change needs values on both sides");
    std::vector<double> d;
    d.reserve(baseline.size() * current.size());
    for (double c : current)
        for (double b : baseline) {
            if (!(c > 0 && b > 0 && std::isfinite(c) && std::isfinite(b)))
                throw std::invalid_argument("a change on the log scale needs positive finite values");
            d.push_back(std::log(c) - std::log(b));
        }
    std::sort(d.begin(), d.end());
    return d;
}

// P(U >= u) under the null, for a count u that may be a half (ties count one half):
// rounded down, so a tie never makes the evidence look stronger. Read off the lower tail
// by symmetry (P(U >= k) = P(U <= nx ny - k)): 1 - cdf would turn 3 vs 3's exact 1/20 into
// 0.05000000000000004, just above alpha.
double upperTail(const std::vector<double>& cdf, double u) {
    long k = long(std::floor(u));
    if (k <= 0) return 1.0;
    const long top = long(cdf.size()) - 1;
    if (k > top) return 0.0;
    return cdf[size_t(top - k)];
}

double countAbove(const std::vector<double>& d, double at) {
    auto lo = std::lower_bound(d.begin(), d.end(), at), hi = std::upper_bound(d.begin(), d.end(), at);
    return double(d.end() - hi) + 0.5 * double(hi - lo);
}

}  // namespace

ChangeInterval changeInterval(const std::vector<double>& baseline, const std::vector<double>& current,
                              double confidence) {
    const auto d = logDifferences(baseline, current);
    const auto& cdf = mannWhitneyNullCdf(int(current.size()), int(baseline.size()));
    ChangeInterval out;
    out.estimate = std::expm1(median(d));
    const double tail = (1.0 - confidence) / 2.0;
    // k: the largest with P(U <= k - 1) <= tail, found on the (symmetric) lower tail.
    size_t k = 0;
    while (k < cdf.size() && cdf[k] <= tail + 1e-12) ++k;
    if (k == 0) return out;  // even complete separation is not that unlikely
    const size_t n = d.size();
    k = std::min(k, (n + 1) / 2);
    out.low = std::expm1(d[k - 1]);
    out.high = std::expm1(d[n - k]);
    out.confidence = 1.0 - 2.0 * cdf[k - 1];
    return out;
}

double changeAboveP(const std::vector<double>& baseline, const std::vector<double>& current, double change) {
    const auto d = logDifferences(baseline, current);
    const auto& cdf = mannWhitneyNullCdf(int(current.size()), int(baseline.size()));
    return upperTail(cdf, countAbove(d, std::log1p(change)));
}

double changeBelowP(const std::vector<double>& baseline, const std::vector<double>& current, double change) {
    const auto d = logDifferences(baseline, current);
    const auto& cdf = mannWhitneyNullCdf(int(current.size()), int(baseline.size()));
    return upperTail(cdf, double(d.size()) - countAbove(d, std::log1p(change)));
}

Interval wilsonInterval(int k, int n) {
    if (n == 0) return {0, 1};
    const double z = 1.959963984540054, ph = double(k) / n, z2n = z * z / n;
    double centre = (ph + z2n / 2) / (1 + z2n);
    double half = z / (1 + z2n) * std::sqrt(ph * (1 - ph) / n + z2n / (4.0 * n));
    return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace cbr::harness
