// Mann-Whitney U exact p-values and Benjamini-Hochberg q-values used by `cbrbench compare`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "harness/figures/stats.h"
#include "harness/figures/verdict.h"

using cbr::harness::benjaminiHochberg;
using cbr::harness::mannWhitneyMinP;
using cbr::harness::mannWhitneyTwoSided;

namespace {

// Independent reference: enumerate every split of the pooled values into |x| and |y|
// (midranks for ties) and count rank sums as extreme as the observed one.
double bruteForceP(const std::vector<double>& x, const std::vector<double>& y) {
    std::vector<double> all = x;
    all.insert(all.end(), y.begin(), y.end());
    const size_t n = all.size(), nx = x.size();
    std::vector<double> rank(n);
    for (size_t i = 0; i < n; ++i) {
        double less = 0, equal = 0;
        for (double v : all) less += v < all[i], equal += v == all[i];
        rank[i] = less + (equal + 1) / 2;
    }
    double w = 0;
    for (size_t i = 0; i < nx; ++i) w += rank[i];
    double total = 0, low = 0, high = 0;
    for (unsigned mask = 0; mask < (1u << n); ++mask) {
        if (size_t(__builtin_popcount(mask)) != nx) continue;
        double s = 0;
        for (size_t i = 0; i < n; ++i)
            if (mask & (1u << i)) s += rank[i];
        total += 1;
        low += s <= w + 1e-9;
        high += s >= w - 1e-9;
    }
    return std::min(1.0, 2 * std::min(low, high) / total);
}

}  // namespace

// Hand-derived: complete separation of n vs n has one arrangement in C(2n, n) per tail.
TEST(MannWhitney, CompleteSeparationIsTwoOverBinomial) {
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3}, {4, 5, 6}), 2.0 / 20, 1e-12);           // 0.1
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3, 4}, {5, 6, 7, 8}), 2.0 / 70, 1e-12);     // 0.028571
    EXPECT_NEAR(mannWhitneyTwoSided({6, 7, 8, 9, 10}, {1, 2, 3, 4, 5}), 2.0 / 252, 1e-12);  // 0.0079365
    EXPECT_NEAR(mannWhitneyMinP(3, 3), 0.1, 1e-12);
    EXPECT_NEAR(mannWhitneyMinP(5, 5), 2.0 / 252, 1e-12);
}

// Hand-derived from the U distribution of 5 vs 5 (coefficients of the Gaussian binomial
// [10 choose 5]_q: 1 1 2 3 5 7 9 11 14 16 18 19 20 20 ...), as scipy's method='exact' gives.
TEST(MannWhitney, ExactDistributionFiveVsFive) {
    // U = 1: P(U <= 1) = 2/252.
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3, 4, 6}, {5, 7, 8, 9, 10}), 4.0 / 252, 1e-12);  // 0.015873
    // U = 10: P(U <= 10) = 87/252.
    EXPECT_NEAR(mannWhitneyTwoSided({1, 3, 5, 7, 9}, {2, 4, 6, 8, 10}), 174.0 / 252, 1e-12);  // 0.690476
    // U = 2: P(U <= 2) = 4/252.
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3, 5, 6}, {4, 7, 8, 9, 10}), 8.0 / 252, 1e-12);
    // Identical samples: p = 1.
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3}, {1, 2, 3}), 1.0, 1e-12);
}

TEST(MannWhitney, UnequalSizesAndTiesMatchEnumeration) {
    std::vector<std::vector<double>> xs = {{1.0, 1.1, 1.3}, {2, 2, 3, 4}, {5, 5, 5}, {0.9, 1.2, 1.2, 1.5, 1.7}};
    std::vector<std::vector<double>> ys = {{1.2, 1.4, 1.5, 1.6}, {2, 3, 3, 5, 6}, {5, 5, 5, 5}, {1.2, 1.6, 1.8, 1.9}};
    for (size_t i = 0; i < xs.size(); ++i)
        EXPECT_NEAR(mannWhitneyTwoSided(xs[i], ys[i]), bruteForceP(xs[i], ys[i]), 1e-12) << "case " << i;
    // 3 vs 4 complete separation: 2 / C(7, 3) = 2/35.
    EXPECT_NEAR(mannWhitneyTwoSided({1, 2, 3}, {4, 5, 6, 7}), 2.0 / 35, 1e-12);
}

TEST(MannWhitney, LargeSamplesUseNormalApproximation) {
    std::vector<double> x, y;
    for (int i = 0; i < 40; ++i) x.push_back(i), y.push_back(i + 0.5);
    double p = mannWhitneyTwoSided(x, y);
    EXPECT_GT(p, 0.5);
    EXPECT_LE(p, 1.0);
    for (auto& v : y) v += 100;
    EXPECT_LT(mannWhitneyTwoSided(x, y), 1e-10);
}

// Worked example: p = (0.01, 0.04, 0.03, 0.005), m = 4. Ascending 0.005, 0.01, 0.03, 0.04
// times m / rank: 0.02, 0.02, 0.04, 0.04; running minimum from the top keeps them.
TEST(BenjaminiHochberg, WorkedExample) {
    auto q = benjaminiHochberg({0.01, 0.04, 0.03, 0.005});
    ASSERT_EQ(q.size(), 4u);
    EXPECT_NEAR(q[0], 0.02, 1e-12);
    EXPECT_NEAR(q[1], 0.04, 1e-12);
    EXPECT_NEAR(q[2], 0.04, 1e-12);
    EXPECT_NEAR(q[3], 0.02, 1e-12);
}

// The step-up minimum: p = (0.01, 0.02, 0.03, 0.5, 0.5): 0.05, 0.05, 0.05, 0.625, 0.5
// become 0.05, 0.05, 0.05, 0.5, 0.5; and q never exceeds 1.
TEST(BenjaminiHochberg, MonotoneAndCapped) {
    auto q = benjaminiHochberg({0.01, 0.02, 0.03, 0.5, 0.5});
    std::vector<double> want = {0.05, 0.05, 0.05, 0.5, 0.5};
    for (size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(q[i], want[i], 1e-12) << i;
    auto one = benjaminiHochberg({0.9, 0.95});
    EXPECT_NEAR(one[0], 0.95, 1e-12);
    EXPECT_NEAR(one[1], 0.95, 1e-12);
    EXPECT_TRUE(benjaminiHochberg({}).empty());
}

// The change interval (Hodges-Lehmann with the exact Mann-Whitney interval) and the verdict
// rule built on it (method/timing.md, "Regression verdicts").
namespace {

using cbr::harness::changeAboveP;
using cbr::harness::changeBelowP;
using cbr::harness::changeInterval;
using cbr::harness::judgeTimes;
using cbr::harness::mannWhitneyNullCdf;
using cbr::harness::TimeSamples;

std::vector<double> sortedLogRatios(const std::vector<double>& b, const std::vector<double>& c) {
    std::vector<double> d;
    for (double x : c)
        for (double y : b) d.push_back(std::log(x) - std::log(y));
    std::sort(d.begin(), d.end());
    return d;
}

// Times with a log-normal spread `cv` around `ms`, from a fixed generator (mt19937 is
// specified exactly; the Box-Muller transform here too).
std::vector<double> noisyTimes(double ms, double cv, int n, unsigned seed) {
    std::mt19937 rng(seed);
    auto uniform = [&] { return (double(rng()) + 0.5) / 4294967296.0; };
    std::vector<double> out;
    for (int i = 0; i < n; ++i) {
        double z = std::sqrt(-2 * std::log(uniform())) * std::cos(2 * M_PI * uniform());
        out.push_back(ms * std::exp(cv * z));
    }
    return out;
}

}  // namespace

// Hand-counted: of the C(10, 5) = 252 splits, U <= 4 in 12 (Hollander & Wolfe, table A.6).
TEST(ChangeInterval, NullDistributionFiveVsFive) {
    const auto& cdf = mannWhitneyNullCdf(5, 5);
    ASSERT_EQ(cdf.size(), 26u);
    const double counts[] = {1, 1, 2, 3, 5, 7};  // U = 0..5
    double running = 0;
    for (int u = 0; u < 6; ++u) EXPECT_NEAR(cdf[size_t(u)], (running += counts[u]) / 252.0, 1e-12) << u;
    EXPECT_NEAR(cdf[25], 1.0, 1e-12);
    EXPECT_NEAR(cdf[12], 1.0 - cdf[12], 1e-12 + cdf[12] - (1.0 - cdf[12]));  // symmetric about 12.5
    EXPECT_NEAR(cdf[12], 0.5, 1e-12);
}

TEST(ChangeInterval, OrderStatisticsOfTheLogRatios) {
    std::vector<double> b = {10.0, 10.3, 9.8, 10.1, 10.6}, c = {11.0, 10.9, 11.6, 10.4, 11.2};
    auto ci = changeInterval(b, c, 0.90);
    auto d = sortedLogRatios(b, c);
    // 5 vs 5 at 90%: P(U <= 4) = 12/252 <= 0.05 < P(U <= 5) = 19/252, so k = 5.
    EXPECT_NEAR(ci.low, std::expm1(d[4]), 1e-12);
    EXPECT_NEAR(ci.high, std::expm1(d[20]), 1e-12);
    EXPECT_NEAR(ci.estimate, std::expm1(d[12]), 1e-12);
    EXPECT_NEAR(ci.confidence, 1.0 - 24.0 / 252.0, 1e-12);
    // The one-sided tests agree with the interval's ends (duality).
    EXPECT_LE(changeAboveP(b, c, ci.low - 1e-9), 0.05);
    EXPECT_GT(changeAboveP(b, c, ci.low + 1e-9), 0.05);
    EXPECT_LE(changeBelowP(b, c, ci.high + 1e-9), 0.05);
    EXPECT_GT(changeBelowP(b, c, ci.high - 1e-9), 0.05);
}

TEST(ChangeInterval, TooFewValuesGiveNoBoundedInterval) {
    std::vector<double> b = {1, 1.1, 1.2}, c = {2, 2.1, 2.2};
    EXPECT_FALSE(changeInterval(b, c, 0.95).bounded());  // needs P(U <= 0) = 1/20 <= 0.025
    auto ci = changeInterval(b, c, 0.90);                 // 1/20 <= 0.05: the extreme ratios
    ASSERT_TRUE(ci.bounded());
    EXPECT_NEAR(ci.low, 2.0 / 1.2 - 1, 1e-12);
    EXPECT_NEAR(ci.high, 2.2 / 1.0 - 1, 1e-12);
    EXPECT_NEAR(ci.confidence, 0.9, 1e-12);
}

// The rule is arithmetic, so synthetic samples show it: a real +10% change with 10% noise
// is UNKNOWN at 5 repetitions (the interval straddles +3%), the cell names more, and with
// 60 the interval clears the threshold: SLOWER. The old rule (noise above the threshold:
// UNKNOWN) stayed UNKNOWN at any count.
TEST(TimeVerdict, MoreRepetitionsTurnUnknownIntoAVerdict) {
    TimeSamples few{noisyTimes(20.0, 0.10, 5, 7), noisyTimes(22.0, 0.10, 5, 8)};
    auto v = judgeTimes({few}, {0.03, 0.05});
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].verdict, "UNKNOWN") << v[0].note;
    ASSERT_TRUE(v[0].interval && v[0].interval->bounded());
    EXPECT_LT(v[0].interval->low, 0.03);
    EXPECT_GT(v[0].interval->high, 0.03);
    ASSERT_TRUE(v[0].reps_needed);
    EXPECT_GT(*v[0].reps_needed, 5);
    EXPECT_LE(*v[0].reps_needed, 60);

    TimeSamples many{noisyTimes(20.0, 0.10, 60, 1), noisyTimes(22.0, 0.10, 60, 2)};
    auto w = judgeTimes({many}, {0.03, 0.05});
    EXPECT_EQ(w[0].verdict, "SLOWER") << w[0].note;
    EXPECT_GT(w[0].interval->low, 0.03);
    EXPECT_FALSE(w[0].reps_needed);
}

TEST(TimeVerdict, NoChangeBecomesSameAndIntervalsFollowTheVerdict) {
    // A/A with 1% noise: inside +-3% with 10 repetitions, an equivalence.
    auto v = judgeTimes({{noisyTimes(10.0, 0.01, 10, 3), noisyTimes(10.0, 0.01, 10, 4)}}, {0.03, 0.05})[0];
    EXPECT_EQ(v.verdict, "SAME") << v.note;
    EXPECT_GT(v.interval->low, -0.03);
    EXPECT_LT(v.interval->high, 0.03);
    // Faster by 20%, low noise.
    auto f = judgeTimes({{noisyTimes(10.0, 0.01, 5, 5), noisyTimes(8.0, 0.01, 5, 6)}}, {0.03, 0.05})[0];
    EXPECT_EQ(f.verdict, "FASTER");
    EXPECT_LT(f.interval->high, -0.03);
    // Fewer than 3 repetitions: no verdict, and 3 named.
    auto s = judgeTimes({{{1.0, 1.1}, {2.0, 2.1, 2.2}}}, {0.03, 0.05})[0];
    EXPECT_EQ(s.verdict, "UNKNOWN");
    EXPECT_EQ(s.reps_needed.value_or(0), 3);
}

// Benjamini-Hochberg across cells: one clear regression among many equal cells stays SLOWER,
// and the intervals widen with the number of cells (false coverage rate).
TEST(TimeVerdict, ManyCellsWidenTheIntervals) {
    std::vector<TimeSamples> cells;
    for (unsigned i = 0; i < 8; ++i) cells.push_back({noisyTimes(10.0, 0.01, 8, 10 + i), noisyTimes(10.0, 0.01, 8, 30 + i)});
    cells.push_back({noisyTimes(10.0, 0.01, 8, 50), noisyTimes(13.0, 0.01, 8, 51)});
    auto v = judgeTimes(cells, {0.03, 0.05});
    EXPECT_EQ(v.back().verdict, "SLOWER");
    auto alone = judgeTimes({cells.back()}, {0.03, 0.05})[0];
    EXPECT_GE(v.back().interval->confidence, alone.interval->confidence);
    for (size_t i = 0; i + 1 < v.size(); ++i) EXPECT_NE(v[i].verdict, "SLOWER") << i;
}

// 3 vs 3 with complete separation: p = 1/20 exactly, which is alpha 0.05, so the cell
// concludes (Benjamini-Hochberg rejects at p <= alpha) and its 90% interval clears the
// threshold. (1 - P(U <= 8) in floating point was 0.05000000000000004: never SLOWER.)
TEST(TimeVerdict, ThreeVersusThreeCompleteSeparationConcludes) {
    EXPECT_EQ(changeAboveP({10.0, 10.01, 10.02}, {11.0, 11.01, 11.02}, 0.03), 0.05);
    auto v = judgeTimes({{{10.0, 10.01, 10.02}, {11.0, 11.01, 11.02}}}, {0.03, 0.05})[0];
    EXPECT_EQ(v.verdict, "SLOWER") << v.note;
    EXPECT_GT(v.interval->low, 0.03);
}
