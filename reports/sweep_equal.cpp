// The sweep's quality at equal cost: each peer of a scaled variant (drr) against the scale
// whose GPU time matches its own (reports/sweep.h, EqualCost), compared by JOD where the
// sweep has it, else by PSNR (sweep_detail.h, Quality).
#include "reports/sweep.h"

#include <algorithm>
#include <cmath>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/sweep_detail.h"
#include "rundir/setting_columns.h"

namespace cbr::reports {
namespace {

using namespace sweep_detail;

std::optional<double> lerp(std::optional<double> a, std::optional<double> b, double f) {
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) return std::nullopt;
    return *a + f * (*b - *a);
}

// The peers of a scaled variant at equal cost (the variants whose equal_cost_with names it):
// each one's best-quality configuration at one cost, a variant that takes the tolerance at the
// recommended tolerance: one each, whatever else was swept.
std::vector<const SweepPoint*> peerConfigs(const std::vector<SweepPoint>& points, double cost,
                                           const std::vector<ToleranceChoice>& choices, const VariantRoles& roles,
                                           const std::string& scaled, const Quality& q) {
    std::vector<const SweepPoint*> peers;
    for (const auto& v : roles.equalCostPeers(scaled)) {
        const SweepPoint* best = nullptr;
        for (const auto& p : points) {
            if (p.variant != v || p.shading_cost != cost || !p.hasTimes() || !p.gpu_ms) continue;
            bool at_choice = !p.number(rundir::settingColumn("cso-tolerance")) || choices.empty();
            for (const auto& ch : choices)
                at_choice = at_choice || (ch.shading_cost == cost && ch.tolerance &&
                                          fmtShort(*p.number(rundir::settingColumn("cso-tolerance"))) == fmtShort(*ch.tolerance));
            if (at_choice && (!best || q.key(p) > q.key(*best))) best = &p;
        }
        if (best) peers.push_back(best);
    }
    return peers;
}

// A configuration as the sentences name it: cbr-cso (tolerance 0.01), taau.
std::string configName(const SweepPoint& c) {
    return c.number(rundir::settingColumn("cso-tolerance")) ? c.variant + " (tolerance " + fmtShort(*c.number(rundir::settingColumn("cso-tolerance"))) + ")"
                                     : c.variant;
}

// The peer's side of an equal-cost comparison.
EqualCost peerSide(const SweepPoint& c) {
    EqualCost e;
    e.config = c.config;
    e.shading_cost = c.shading_cost;
    e.cbr_ms = *c.gpu_ms;
    e.cbr_psnr = c.psnr_db;
    e.cbr_ssim = c.ssim;
    e.cbr_eci = c.eci;
    e.cbr_jod = c.jod;
    return e;
}

// ": checkerboard is better by 1.00 dB at equal cost", or the same by JOD.
std::string equalCostJudgement(const EqualCost& e, const std::string& kind, const Quality& q) {
    const auto mine = q.jod ? e.cbr_jod : e.cbr_psnr, theirs = q.jod ? e.drr_jod : e.drr_psnr;
    if (!mine || !theirs) return "";
    const double d = *mine - *theirs, same = q.jod ? kJodThreshold : 0.05;
    if (std::abs(d) < same)
        return q.jod ? ": the same JOD at equal cost (within " + jodDiffText(same) + ")" : ": the same PSNR at equal cost";
    return ": " + kind + " is " + (d > 0 ? "better" : "worse") + " by " + q.diff(d) + " at equal cost";
}

// The sentence of one equal-cost comparison, e filled in.
std::string equalCostSentence(const EqualCost& e, const SweepPoint& c, const VariantRoles& roles,
                              const std::string& scaled, const std::string& suffix, const Quality& q) {
    const VariantRole* role = roles.find(c.variant);
    const std::string kind = role && role->checkerboard ? "checkerboard" : c.variant;
    // The scaled side's quality and the peer's: "PSNR 28.00 dB ... against 29.00 dB", or JODs.
    const std::string theirs = q.jod ? jodText(e.drr_jod, kDash) : "PSNR " + fmtDb(e.drr_psnr);
    const std::string mine = q.jod ? jodText(e.cbr_jod, kDash) : fmtDb(e.cbr_psnr);
    std::string s = configName(c) + " at " + fmtMs(e.cbr_ms) + suffix + ": ";
    if (e.matched) {
        s += scaled + " at the same cost renders at scale " + fmt(e.drr_scale, 3) + " with " +
             (q.jod ? theirs + ", PSNR " + fmtDb(e.drr_psnr) : theirs) + ", SSIM " + fmt(e.drr_ssim, 4) + ", ECI " +
             fmt(e.drr_eci, 4) + ", against " + (q.jod ? mine + ", " + fmtDb(e.cbr_psnr) : mine) + ", " +
             fmt(e.cbr_ssim, 4) + ", " + fmt(e.cbr_eci, 4) + equalCostJudgement(e, kind, q);
    } else if (e.cbr_ms < *e.drr_ms) {
        s += "cheaper than every " + scaled + " scale swept (the cheapest, scale " + fmt(e.drr_scale, 3) + ", takes " +
             fmtMs(*e.drr_ms) + " with " + theirs + " against " + mine + "); no equal-cost " + scaled +
             " scale in the range";
    } else {
        s += "dearer than every " + scaled + " scale swept (the dearest, scale " + fmt(e.drr_scale, 3) + ", takes " +
             fmtMs(*e.drr_ms) + " with " + theirs + " against " + mine + "); at its cost " + scaled +
             " renders at scale " + fmt(e.drr_scale, 3) + " or more";
    }
    return s + ".";
}

// One peer configuration against the scaled variant's configurations at its cost (sorted by
// time): the scale whose time matches, interpolated, or the nearest end of the range.
EqualCost matchAtEqualCost(const SweepPoint& c, const std::vector<const SweepPoint*>& by_time) {
    EqualCost e = peerSide(c);
    const SweepPoint* lo = nullptr;
    const SweepPoint* hi = nullptr;
    for (size_t i = 0; i + 1 < by_time.size(); ++i)
        if (*by_time[i]->gpu_ms <= e.cbr_ms && e.cbr_ms <= *by_time[i + 1]->gpu_ms) lo = by_time[i], hi = by_time[i + 1];
    if (by_time.size() == 1 && *by_time[0]->gpu_ms == e.cbr_ms) lo = hi = by_time[0];
    if (lo) {
        double span = *hi->gpu_ms - *lo->gpu_ms;
        double f = span > 0 ? (e.cbr_ms - *lo->gpu_ms) / span : 0.0;
        e.matched = true;
        e.drr_ms = e.cbr_ms;
        e.drr_scale = lerp(lo->number(rundir::settingColumn("drr-scale")), hi->number(rundir::settingColumn("drr-scale")), f);
        e.drr_psnr = lerp(lo->psnr_db, hi->psnr_db, f);
        e.drr_ssim = lerp(lo->ssim, hi->ssim, f);
        e.drr_eci = lerp(lo->eci, hi->eci, f);
        e.drr_jod = lerp(lo->jod, hi->jod, f);
    } else {
        const SweepPoint* near = e.cbr_ms < *by_time.front()->gpu_ms ? by_time.front() : by_time.back();
        e.drr_scale = near->number(rundir::settingColumn("drr-scale"));
        e.drr_ms = near->gpu_ms;
        e.drr_psnr = near->psnr_db;
        e.drr_ssim = near->ssim;
        e.drr_eci = near->eci;
        e.drr_jod = near->jod;
    }
    return e;
}

void equalCostAt(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices,
                 const VariantRoles& roles, const std::string& scaled, double cost, std::vector<EqualCost>& out) {
    const Quality q = qualityOf(points);
    std::vector<const SweepPoint*> by_time;
    for (const auto& p : points)
        if (p.variant == scaled && p.shading_cost == cost && p.hasTimes() && p.gpu_ms) by_time.push_back(&p);
    std::sort(by_time.begin(), by_time.end(), [](auto* a, auto* b) { return *a->gpu_ms < *b->gpu_ms; });
    const std::string suffix = costSuffix(points, cost);
    for (const auto* c : peerConfigs(points, cost, choices, roles, scaled, q)) {
        if (by_time.empty()) {
            EqualCost e = peerSide(*c);
            e.verdict = configName(*c) + ": no " + scaled + " configuration ran" + suffix +
                        ", so there is nothing to match its cost with (add --param drr-scale=LO:HI:lin:N).";
            out.push_back(e);
            continue;
        }
        EqualCost e = matchAtEqualCost(*c, by_time);
        e.verdict = equalCostSentence(e, *c, roles, scaled, suffix, q);
        out.push_back(e);
    }
}

}  // namespace

std::vector<EqualCost> equalCost(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices,
                                 const VariantRoles& roles) {
    std::vector<EqualCost> out;
    for (double cost : shadingCosts(points))
        for (const std::string& scaled : roles.equalCostBaselines()) equalCostAt(points, choices, roles, scaled, cost, out);
    return out;
}

}  // namespace cbr::reports
