// Mann-Whitney U exact p-values and Benjamini-Hochberg q-values used by `cbrbench compare`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "harness/stats.h"

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
