// Per-cell time verdicts by interval and equivalence, false discovery rate across cells.
#include "harness/figures/verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace cbr::harness {

const char* const kTimeRule =
    "Per cell the samples are the per-repetition medians of gpu_ms (frames.csv rows with status ok). The change is "
    "judged on the log scale, as a ratio: the Hodges-Lehmann estimate (median of the pairwise ratios current / "
    "baseline) with the exact Mann-Whitney interval. Three one-sided exact tests per cell: the change lies above "
    "+threshold (SLOWER), below -threshold (FASTER), inside +-threshold (SAME, an equivalence test: both one-sided "
    "tests). The smallest of the three p-values is the cell's, Benjamini-Hochberg adjusted across the cells (q); "
    "the conclusion holds when q <= alpha (as Benjamini-Hochberg rejects), else UNKNOWN. The interval printed is at confidence 1 - 2 alpha R / m (R "
    "cells concluded of m; 90% for one cell at alpha 0.05): a SLOWER or FASTER cell's interval lies wholly beyond "
    "the threshold, a SAME cell's inside it, an UNKNOWN cell's straddles a boundary. The interval narrows as "
    "repetitions grow, so any real change beyond the threshold becomes a verdict with enough of them: an UNKNOWN "
    "cell names the repetitions per side likely to settle it (the interval's half-width scaled by 1/sqrt(n) until "
    "it fits between the estimate and the nearest boundary). Fewer than 3 repetitions on either side: UNKNOWN. "
    "The noise (coefficient of variation of the per-repetition medians) is reported, not a gate. The resolution is "
    "the interval's half-width: the smallest change the noise could show at all; a SAME under a threshold at least "
    "4 times wider says so in its note (and whether the interval excludes 0: a real change inside the threshold).";

namespace {

// A threshold this many times the resolution is "far wider" (the SAME note).
constexpr double kFarWider = 4.0;

struct Tests {
    double p = 1;
    std::string conclusion;
};

Tests testCell(const TimeSamples& s, double threshold) {
    const auto& b = s.baseline;
    const auto& c = s.current;
    double slower = changeAboveP(b, c, threshold);
    double faster = threshold < 1 ? changeBelowP(b, c, -threshold) : 1.0;
    double same = std::max(changeBelowP(b, c, threshold), threshold < 1 ? changeAboveP(b, c, -threshold) : 0.0);
    Tests t{slower, "SLOWER"};
    if (faster < t.p) t = {faster, "FASTER"};
    if (same < t.p) t = {same, "SAME"};
    return t;
}

// The upper quantile z with P(Z > z) = tail, by bisection.
double normalQuantile(double tail) {
    double lo = -10, hi = 10;
    for (int i = 0; i < 100; ++i) {
        double mid = (lo + hi) / 2;
        (0.5 * std::erfc(mid / std::sqrt(2.0)) > tail ? lo : hi) = mid;
    }
    return (lo + hi) / 2;
}

double logSpread(const std::vector<double>& a, const std::vector<double>& b) {
    double ss = 0;
    size_t dof = 0;
    for (const auto* side : {&a, &b}) {
        if (side->size() < 2) continue;
        double m = 0;
        for (double v : *side) m += std::log(v);
        m /= double(side->size());
        for (double v : *side) ss += (std::log(v) - m) * (std::log(v) - m);
        dof += side->size() - 1;
    }
    return dof > 0 ? std::sqrt(ss / double(dof)) : 0.0;
}

// Repetitions per side that would likely settle an UNKNOWN: the interval's half-width
// (log scale) shrinks as sqrt(1/nb + 1/nc); enough when it fits between the estimate and
// the nearest boundary of +-threshold. Also at least what the exact test needs to reach
// the tail at all (1 / C(2n, n) <= tail).
std::optional<int> repsNeeded(const TimeSamples& s, const ChangeInterval& ci, double threshold, double tail) {
    const double nb = double(s.baseline.size()), nc = double(s.current.size());
    const double up = std::log1p(threshold), down = threshold < 1 ? std::log1p(-threshold) : -INFINITY;
    const double est = std::log1p(ci.estimate);
    double dist = est > up ? est - up : est < down ? down - est : std::min(up - est, est - down);
    if (!(dist > 1e-9)) return std::nullopt;  // on a boundary: no count settles it
    double scale = ci.bounded() ? (std::log1p(ci.high) - std::log1p(ci.low)) / 2 / std::sqrt(1 / nb + 1 / nc)
                                : normalQuantile(tail) * logSpread(s.baseline, s.current) * std::sqrt(M_PI / 3);
    double n = std::ceil(2 * (scale / dist) * (scale / dist));
    int exact_min = 1;
    while (mannWhitneyNullCdf(exact_min, exact_min)[0] > tail && exact_min < 1000) ++exact_min;
    n = std::max({n, double(exact_min), std::max(nb, nc) + 1});
    return int(std::min(n, 100000.0));
}

// A SAME under a threshold far wider than what the noise resolves says so: "+2.1% SAME at
// 3%" on a machine that resolves 0.1% hides a real change inside the threshold.
std::string sameNote(const TimeVerdict& v, double threshold) {
    if (!v.resolution || !(threshold >= kFarWider * *v.resolution)) return "";
    char b[200];
    std::snprintf(b, sizeof b, "the noise resolves +-%.2g%%, far less than the %g%% threshold", *v.resolution * 100,
                  threshold * 100);
    std::string note = b;
    if (v.interval && (v.interval->low > 0 || v.interval->high < 0)) {
        std::snprintf(b, sizeof b, ": a real change of %+.2g%% (the interval excludes 0), inside the threshold",
                      v.interval->estimate * 100);
        note += b;
    }
    return note;
}

}  // namespace

std::vector<TimeVerdict> judgeTimes(const std::vector<TimeSamples>& cells, const VerdictRule& rule) {
    std::vector<TimeVerdict> out(cells.size());
    std::vector<Tests> tests(cells.size());
    std::vector<double> ps;
    std::vector<size_t> tested;
    for (size_t i = 0; i < cells.size(); ++i) {
        const auto& s = cells[i];
        auto& v = out[i];
        if (!s.baseline.empty() && !s.current.empty() && median(s.baseline) > 0)
            v.change = median(s.current) / median(s.baseline) - 1.0;
        if (s.baseline.size() >= 2 && s.current.size() >= 2)
            v.noise = std::max(coefficientOfVariation(s.baseline), coefficientOfVariation(s.current));
        if (s.baseline.size() < 3 || s.current.size() < 3) {
            v.note = "fewer than 3 repetitions (" + std::to_string(s.baseline.size()) + " vs " +
                     std::to_string(s.current.size()) + ")";
            v.reps_needed = 3;
            continue;
        }
        tests[i] = testCell(s, rule.threshold);
        v.p = tests[i].p;
        ps.push_back(tests[i].p);
        tested.push_back(i);
    }
    const auto qs = benjaminiHochberg(ps);
    size_t concluded = 0;
    for (size_t k = 0; k < tested.size(); ++k) {
        auto& v = out[tested[k]];
        v.q = qs[k];
        if (qs[k] <= rule.alpha) v.verdict = tests[tested[k]].conclusion, ++concluded;
    }
    // Benjamini-Yekutieli: intervals of the selected cells at 1 - 2 alpha R / m.
    const double tail = rule.alpha * double(std::max<size_t>(concluded, 1)) / double(std::max<size_t>(tested.size(), 1));
    for (size_t i : tested) {
        const auto& s = cells[i];
        auto& v = out[i];
        v.interval = changeInterval(s.baseline, s.current, 1.0 - 2.0 * tail);
        if (v.interval->bounded()) {
            double half = (std::log1p(v.interval->high) - std::log1p(v.interval->low)) / 2;
            v.detectable = std::expm1(std::log1p(rule.threshold) + half);
            v.resolution = std::expm1(half);
        }
        if (v.verdict == "SAME") v.note = sameNote(v, rule.threshold);
        if (v.verdict != "UNKNOWN") continue;
        v.reps_needed = repsNeeded(s, *v.interval, rule.threshold, tail);
        v.note = v.reps_needed ? "interval straddles a boundary: about " + std::to_string(*v.reps_needed) +
                                     " repetitions per side would likely settle it"
                               : "estimate on the threshold: more repetitions will not settle it";
        if (!v.interval->bounded()) v.note = "too few repetitions for the interval; " + v.note.substr(v.note.find(':') + 2);
    }
    return out;
}

std::vector<double> repetitionMedians(const reports::RunData& d, const std::string& variant, int max_repeats) {
    std::vector<double> out;
    for (auto& [rep, v] : reports::gpuMsByRepetition(d, variant, max_repeats)) out.push_back(median(v));
    return out;
}

void judgeQuality(QualityVerdict& q, bool higher_better, double threshold, bool relative) {
    if (!q.base || !q.cur) return;
    double b = *q.base, c = *q.cur;
    if (b == c) {  // covers inf == inf (full against itself)
        q.delta = 0;
        q.verdict = "SAME";
        return;
    }
    double delta = relative ? (b != 0 ? (c - b) / std::abs(b) : (c > b ? INFINITY : -INFINITY)) : c - b;
    if (std::isfinite(delta)) q.delta = delta;
    bool up = c > b;
    if (std::abs(delta) <= threshold) q.verdict = "SAME";
    else q.verdict = up == higher_better ? "BETTER" : "WORSE";
}

double parseFraction(const std::string& text, const std::string& command, const std::string& option) {
    std::string t = text;
    bool pct = !t.empty() && t.back() == '%';
    if (pct) t.pop_back();
    size_t used = 0;
    double v = 0;
    try {
        v = std::stod(t, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (t.empty() || used != t.size() || !std::isfinite(v) || v < 0)
        throw std::invalid_argument(command + ": " + option + " '" + text +
                                    "': accepted: a non-negative percentage such as 3% or a fraction such as 0.03");
    return pct ? v / 100.0 : v;
}

}  // namespace cbr::harness
