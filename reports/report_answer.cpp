// The report's answer: one sentence on which variant gives the best quality for its cost.
#include <algorithm>
#include <cmath>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"

namespace cbr::reports {

namespace {

// The quality the answer compares: ColorVideoVDP's JOD where a variant other than the
// reference has one (reports/jod.h), else the sequence PSNR. Both are higher-is-better; the
// reference's is 10 JOD, or an infinite PSNR.
struct AnswerQuality {
    bool jod = false;
    std::string reference;

    std::optional<double> of(const CostQuality& v) const {
        if (jod) return v.name == reference ? v.jod.value_or(kJodNoDifference) : v.jod;
        return v.name == reference ? std::optional<double>(INFINITY) : v.psnr_db;
    }
    // "26.10 dB", "identical to full" or "9.42 JOD".
    std::string text(double q) const {
        if (jod) return jodText(q, kDash);
        return std::isinf(q) ? "identical to " + reference : fmt(q, 2) + " dB";
    }
    // "PSNR 26.10 dB" or "9.42 JOD".
    std::string named(double q) const { return jod ? text(q) : "PSNR " + text(q); }
    // The best variant's second figure: its SSIM beside a PSNR, its PSNR beside a JOD.
    std::string aside(const CostQuality& v) const {
        if (jod) return v.psnr_db ? " (PSNR " + fmt(v.psnr_db, 2) + " dB)" : "";
        return v.ssim ? " (SSIM " + fmt(*v.ssim, 4) + ")" : "";
    }
};

bool jodOf(const std::vector<CostQuality>& all, const std::string& reference) {
    return std::any_of(all.begin(), all.end(),
                       [&](const CostQuality& v) { return v.name != reference && v.jod && std::isfinite(*v.jod); });
}

// The Pareto front of speed-up (higher better) against quality (higher better), as indices into
// `who`; paretoFront minimises x, so x is the speed-up negated.
std::vector<size_t> speedFront(const std::vector<const CostQuality*>& who, const std::vector<double>& quality) {
    std::vector<ScatterPoint> pts;
    for (size_t i = 0; i < who.size(); ++i) pts.push_back({who[i]->name, "", -*who[i]->speedup.value, quality[i]});
    return paretoFront(pts, /*y_higher_is_better=*/true);
}

// The variants with a paired speed-up and a quality, and the best of them: on the front,
// measurably faster than the reference, the highest quality (then the fastest).
struct Ranked {
    std::vector<const CostQuality*> who;
    std::vector<double> quality;
    std::optional<size_t> best;
    std::vector<size_t> others;  // every non-reference variant but the best, fastest first
    double speed(size_t i) const { return *who[i]->speedup.value; }
};

Ranked rank(const std::vector<CostQuality>& all, const AnswerQuality& aq) {
    Ranked r;
    for (const auto& v : all) {
        std::optional<double> y = aq.of(v);
        if (!v.speedup.value || !std::isfinite(*v.speedup.value) || !y || std::isnan(*y)) continue;
        r.who.push_back(&v);
        r.quality.push_back(*y);
    }
    if (r.who.size() <= 1) return r;
    const auto front = speedFront(r.who, r.quality);
    auto onFront = [&](size_t i) { return std::find(front.begin(), front.end(), i) != front.end(); };
    for (size_t i = 0; i < r.who.size(); ++i) {
        if (r.who[i]->name == aq.reference || !onFront(i) || !measurablyFaster(r.who[i]->speedup)) continue;
        if (!r.best || r.quality[i] > r.quality[*r.best] ||
            (r.quality[i] == r.quality[*r.best] && r.speed(i) > r.speed(*r.best)))
            r.best = i;
    }
    for (size_t i = 0; i < r.who.size(); ++i)
        if (r.who[i]->name != aq.reference && (!r.best || i != *r.best)) r.others.push_back(i);
    std::sort(r.others.begin(), r.others.end(), [&](size_t a, size_t b) { return r.speed(a) > r.speed(b); });
    return r;
}

// "; drr is faster (2.00x [1.90, 2.10]) but lower quality (25.30 dB)": one variant against the best.
std::string againstBest(const Ranked& r, size_t i, const AnswerQuality& aq) {
    const std::string speed = speedupText(r.who[i]->speedup, kDash), q = aq.text(r.quality[i]);
    const bool faster = r.speed(i) > r.speed(*r.best), better = r.quality[i] > r.quality[*r.best];
    std::string s = "; " + r.who[i]->name;
    if (!measurablyFaster(r.who[i]->speedup))
        return s + " is not measurably faster than " + aq.reference + " (" + speed + ") at " + aq.named(r.quality[i]);
    if (faster && better) return s + " is faster (" + speed + ") and higher quality (" + q + ")";
    if (faster) return s + " is faster (" + speed + ") but lower quality (" + q + ")";
    if (better) return s + " is higher quality (" + q + ") but slower (" + speed + ")";
    return s + " is dominated: slower (" + speed + ") and no better (" + q + ")";
}

}  // namespace

std::string paretoSentence(const std::vector<CostQuality>& all, const std::string& reference) {
    const CostQuality* ref = nullptr;
    for (const auto& v : all)
        if (v.name == reference) ref = &v;
    const std::string& full = reference;
    if (!ref || !ref->gpu_ms || !std::isfinite(*ref->gpu_ms) || *ref->gpu_ms <= 0)
        return "No timed reference (" + full + ") in this run, so no variant's cost can be compared with " + full + "'s.";

    const AnswerQuality aq{jodOf(all, reference), reference};
    const Ranked r = rank(all, aq);
    if (r.who.size() <= 1)
        return "Only the reference (" + full + ") has a speed-up and quality here, so there is nothing to compare.";
    auto speed = [&](size_t i) { return speedupText(r.who[i]->speedup, kDash); };
    const std::string why = " (speed-ups: medians of the paired per-frame ratios " + full +
                            "/variant, with 95% intervals).";
    std::string s;
    if (!r.best) {
        s = "No variant is both on the Pareto front and measurably faster than " + full + ", so " + full +
            " gives the best quality for its cost here";
        for (size_t i : r.others)
            s += "; " + r.who[i]->name + " runs at " + speed(i) + " the speed of " + full + " with " + aq.named(r.quality[i]);
        return s + why;
    }
    s = r.who[*r.best]->name + " gives the best quality for its cost: it is on the Pareto front with " +
        aq.named(r.quality[*r.best]) + aq.aside(*r.who[*r.best]) + " at " + speed(*r.best) + " the speed of " + full;
    for (size_t i : r.others) s += againstBest(r, i, aq);
    return s + why;
}

std::vector<CostQuality> costQuality(const RunData& d) {
    std::vector<CostQuality> cq;
    for (const auto& v : d.variants) {
        if (!variantOk(d, v)) continue;
        cq.push_back({v, summaryNum(d, v, summary_csv::kGpuMsMedian), summaryNum(d, v, summary_csv::kPsnrDbMean),
                      summaryNum(d, v, summary_csv::kSsimMean), summarySpeedup(d, v),
                      summaryNum(d, v, summary_csv::kCvvdpJod)});
    }
    return cq;
}

std::string paretoSentence(const RunData& d) { return paretoSentence(costQuality(d), d.reference); }

bool answersInJod(const RunData& d) { return jodOf(costQuality(d), d.reference); }

}  // namespace cbr::reports
