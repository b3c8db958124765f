// The sweep's answers: a recommended value per swept setting (the CSO tolerance by its own
// rule), disagreements between paths, and quality at equal cost against a scaled variant
// (drr). Which variant plays which part comes from the variant table (VariantRoles).
#include "reports/sweep.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "reports/html.h"
#include "reports/sweep_detail.h"

namespace cbr::reports {
namespace {

using namespace sweep_detail;

std::optional<double> lerp(std::optional<double> a, std::optional<double> b, double f) {
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) return std::nullopt;
    return *a + f * (*b - *a);
}

// The peers of a scaled variant at equal cost (the variants whose equal_cost_with names it):
// each one's best-PSNR configuration at one cost, a variant that takes the tolerance at the
// recommended tolerance: one each, whatever else was swept.
std::vector<const SweepPoint*> peerConfigs(const std::vector<SweepPoint>& points, double cost,
                                              const std::vector<ToleranceChoice>& choices, const VariantRoles& roles,
                                              const std::string& scaled) {
    std::vector<const SweepPoint*> peers;
    for (const auto& v : roles.equalCostPeers(scaled)) {
        const SweepPoint* best = nullptr;
        for (const auto& p : points) {
            if (p.variant != v || p.shading_cost != cost || !p.hasTimes() || !p.gpu_ms) continue;
            bool at_choice = !p.number("cso_tolerance") || choices.empty();
            for (const auto& ch : choices)
                at_choice = at_choice || (ch.shading_cost == cost && ch.tolerance &&
                                          fmtShort(*p.number("cso_tolerance")) == fmtShort(*ch.tolerance));
            if (at_choice && (!best || psnrKey(p) > psnrKey(*best))) best = &p;
        }
        if (best) peers.push_back(best);
    }
    return peers;
}

// The variant whose time bounds the tolerance's choice: the cost bound of the variant that takes it.
std::string toleranceBound(const std::vector<const SweepPoint*>& cso, const VariantRoles& roles) {
    const VariantRole* r = cso.empty() ? nullptr : roles.find(cso.front()->variant);
    return r ? r->cost_bound : std::string();
}

}  // namespace

std::vector<ToleranceChoice> recommendTolerance(const std::vector<SweepPoint>& points, const VariantRoles& roles,
                                                double margin) {
    std::vector<ToleranceChoice> out;
    for (double cost : shadingCosts(points)) {
        std::vector<const SweepPoint*> cso;
        for (const auto& p : points)
            if (p.shading_cost == cost && p.hasTimes() && p.gpu_ms && p.number("cso_tolerance"))
                cso.push_back(&p);
        if (cso.empty()) continue;
        ToleranceChoice c;
        c.shading_cost = cost;
        const std::string bound = toleranceBound(cso, roles);
        const SweepPoint* aso = bound.empty() ? nullptr : findVariant(points, bound, cost);
        std::vector<const SweepPoint*> within;
        for (const auto* p : cso)
            if (!aso || *p->gpu_ms <= *aso->gpu_ms * (1 + margin)) within.push_back(p);
        const bool none_within = within.empty();
        if (none_within) within = cso;  // every tolerance costs more: still name the best one
        // The plateau of the best PSNR (within 0.02 dB of it), then its lowest ECI (within
        // 1e-4), then the loosest tolerance of those: the edge of the plateau, before
        // reuse starts to cost quality.
        double top = -1e300, low_eci = 1e300;
        for (const auto* p : within) top = std::max(top, psnrKey(*p));
        std::vector<const SweepPoint*> plateau;
        for (const auto* p : within)
            if (psnrKey(*p) >= top - 0.02) plateau.push_back(p), low_eci = std::min(low_eci, p->eci.value_or(1e300));
        const SweepPoint* best = nullptr;
        for (const auto* p : plateau)
            if (p->eci.value_or(1e300) <= low_eci + 1e-4 && (!best || *p->number("cso_tolerance") > *best->number("cso_tolerance"))) best = p;
        const SweepPoint* worst = cso.front();
        for (const auto* p : cso)
            if (psnrKey(*p) < psnrKey(*worst)) worst = p;
        c.tolerance = best->number("cso_tolerance");
        std::string s = "cso-tolerance " + fmtShort(*best->number("cso_tolerance")) + costSuffix(points, cost) + ": ";
        const bool on_plateau = plateau.size() > 1;
        const std::string n = std::to_string(cso.size());
        if (aso && none_within) {
            s += "every one of the " + n + " tolerances costs more than " + fmtShort(margin * 100) +
                 "% above " + bound + "'s " + fmtMs(*aso->gpu_ms) + ", and this one has the best sequence PSNR, " +
                 fmtDb(best->psnr_db) + " (" + bound + " " + fmtDb(aso->psnr_db) + ")";
        } else if (aso) {
            s += std::string(on_plateau ? "the loosest tolerance within 0.02 dB of the best sequence PSNR, "
                                        : "the best sequence PSNR, ") +
                 fmtDb(best->psnr_db) + " against " + bound + "'s " + fmtDb(aso->psnr_db) + ", among the " +
                 std::to_string(within.size()) + " of " + n + " tolerances whose median GPU time stays within " +
                 fmtShort(margin * 100) + "% of " + bound + "'s (" + fmtMs(*best->gpu_ms) + " vs " + fmtMs(*aso->gpu_ms) + ")";
        } else {
            s += "the best sequence PSNR of the " + n + " tolerances, " + fmtDb(best->psnr_db) +
                 " (no " + (bound.empty() ? std::string("variant") : bound + " configuration") + " to bound the cost)";
        }
        s += ", with ECI " + fmt(best->eci, 4) + (aso ? " (" + bound + " " + fmt(aso->eci, 4) + ")" : std::string());
        if (worst != best && best->psnr_db && worst->psnr_db && *best->psnr_db - *worst->psnr_db >= 0.01)
            s += ", while tolerance " + fmtShort(*worst->number("cso_tolerance")) + " loses " +
                 fmt(*best->psnr_db - *worst->psnr_db, 2) + " dB";
        else
            s += "; PSNR varies less than 0.01 dB across the tolerances";
        c.sentence = s + ".";
        out.push_back(c);
    }
    return out;
}

namespace {

// A configuration as the sentences name it: cbr-cso (tolerance 0.01), taau.
std::string configName(const SweepPoint& c) {
    return c.number("cso_tolerance") ? c.variant + " (tolerance " + fmtShort(*c.number("cso_tolerance")) + ")"
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
    return e;
}

// The sentence of one equal-cost comparison, e filled in.
std::string equalCostSentence(const EqualCost& e, const SweepPoint& c, const VariantRoles& roles,
                              const std::string& scaled, const std::string& suffix) {
    const VariantRole* role = roles.find(c.variant);
    const std::string kind = role && role->checkerboard ? "checkerboard" : c.variant;
    std::string s = configName(c) + " at " + fmtMs(e.cbr_ms) + suffix + ": ";
    if (e.matched) {
        s += scaled + " at the same cost renders at scale " + fmt(e.drr_scale, 3) + " with PSNR " + fmtDb(e.drr_psnr) +
             ", SSIM " + fmt(e.drr_ssim, 4) + ", ECI " + fmt(e.drr_eci, 4) + ", against " + fmtDb(e.cbr_psnr) + ", " +
             fmt(e.cbr_ssim, 4) + ", " + fmt(e.cbr_eci, 4);
        if (e.drr_psnr && e.cbr_psnr) {
            double d = *e.cbr_psnr - *e.drr_psnr;
            s += std::abs(d) < 0.05 ? ": the same PSNR at equal cost"
                                    : ": " + kind + " is " + (d > 0 ? "better" : "worse") + " by " +
                                          fmt(std::abs(d), 2) + " dB at equal cost";
        }
    } else if (e.cbr_ms < *e.drr_ms) {
        s += "cheaper than every " + scaled + " scale swept (the cheapest, scale " + fmt(e.drr_scale, 3) + ", takes " +
             fmtMs(*e.drr_ms) + " with PSNR " + fmtDb(e.drr_psnr) + " against " + fmtDb(e.cbr_psnr) +
             "); no equal-cost " + scaled + " scale in the range";
    } else {
        s += "dearer than every " + scaled + " scale swept (the dearest, scale " + fmt(e.drr_scale, 3) + ", takes " +
             fmtMs(*e.drr_ms) + " with PSNR " + fmtDb(e.drr_psnr) + " against " + fmtDb(e.cbr_psnr) +
             "); at its cost " + scaled + " renders at scale " + fmt(e.drr_scale, 3) + " or more";
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
        e.drr_scale = lerp(lo->number("drr_scale"), hi->number("drr_scale"), f);
        e.drr_psnr = lerp(lo->psnr_db, hi->psnr_db, f);
        e.drr_ssim = lerp(lo->ssim, hi->ssim, f);
        e.drr_eci = lerp(lo->eci, hi->eci, f);
    } else {
        const SweepPoint* near = e.cbr_ms < *by_time.front()->gpu_ms ? by_time.front() : by_time.back();
        e.drr_scale = near->number("drr_scale");
        e.drr_ms = near->gpu_ms;
        e.drr_psnr = near->psnr_db;
        e.drr_ssim = near->ssim;
        e.drr_eci = near->eci;
    }
    return e;
}

void equalCostAt(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices,
                 const VariantRoles& roles, const std::string& scaled, double cost, std::vector<EqualCost>& out) {
    std::vector<const SweepPoint*> by_time;
    for (const auto& p : points)
        if (p.variant == scaled && p.shading_cost == cost && p.hasTimes() && p.gpu_ms) by_time.push_back(&p);
    std::sort(by_time.begin(), by_time.end(), [](auto* a, auto* b) { return *a->gpu_ms < *b->gpu_ms; });
    const std::string suffix = costSuffix(points, cost);
    for (const auto* c : peerConfigs(points, cost, choices, roles, scaled)) {
        if (by_time.empty()) {
            EqualCost e = peerSide(*c);
            e.verdict = configName(*c) + ": no " + scaled + " configuration ran" + suffix +
                        ", so there is nothing to match its cost with (add --param drr-scale=LO:HI:lin:N).";
            out.push_back(e);
            continue;
        }
        EqualCost e = matchAtEqualCost(*c, by_time);
        e.verdict = equalCostSentence(e, *c, roles, scaled, suffix);
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

std::string settingRule(const VariantRoles& roles) {
    const VariantRole* bounded = roles.bounded();
    const std::string bound = bounded ? bounded->cost_bound : std::string("its cost bound");
    return "for each swept setting, per path, reference and shading cost, take the configurations it applies to that ran, "
    "keep their Pareto front of median GPU time against sequence PSNR, and of the front's configurations not "
    "measurably slower than its fastest one (median within 5%, or 95% intervals of the median overlapping) "
    "recommend the value of the one with the highest PSNR, a PSNR within 0.02 dB counting "
    "as a tie broken by the higher SSIM (within 1e-4), then the lower ECI (within 1e-4), then the lower time "
    "(cso-tolerance keeps its own rule: the edge of the quality plateau within 5% of " +
           bound + "'s time)";
}

namespace {

// Keeps the points whose key lies within `eps` of the best (`higher`: larger is better).
void keepBest(std::vector<const SweepPoint*>& c, double (*key)(const SweepPoint&), double eps, bool higher) {
    double best = higher ? -1e300 : 1e300;
    for (const auto* p : c) best = higher ? std::max(best, key(*p)) : std::min(best, key(*p));
    std::erase_if(c, [&](const SweepPoint* p) { return higher ? key(*p) < best - eps : key(*p) > best + eps; });
}

double ssimKey(const SweepPoint& p) { return p.ssim.value_or(-1e300); }
double eciKey(const SweepPoint& p) { return p.eci.value_or(1e300); }
double timeKey(const SweepPoint& p) { return *p.gpu_ms; }

// kSettingRule on the configurations of one setting; `why` says which criterion decided.
const SweepPoint* bestOnFront(const std::vector<const SweepPoint*>& ran, double margin, size_t& eligible_count,
                              std::string& why) {
    std::vector<const SweepPoint*> front;
    for (const auto* p : ran) {
        bool dominated = std::any_of(ran.begin(), ran.end(), [&](const SweepPoint* q) {
            return q != p && *q->gpu_ms <= *p->gpu_ms && psnrKey(*q) >= psnrKey(*p) &&
                   (*q->gpu_ms < *p->gpu_ms || psnrKey(*q) > psnrKey(*p));
        });
        if (!dominated) front.push_back(p);
    }
    const SweepPoint* fastest = front.front();
    for (const auto* p : front)
        if (*p->gpu_ms < *fastest->gpu_ms) fastest = p;
    // Not measurably slower than the fastest: within the margin, or the 95% intervals of
    // the median overlap (on a noisy device the fastest median is often luck).
    std::vector<const SweepPoint*> c;
    for (const auto* p : front)
        if (*p->gpu_ms <= *fastest->gpu_ms * (1 + margin) ||
            (p->gpu_ms_low && fastest->gpu_ms_high && *p->gpu_ms_low <= *fastest->gpu_ms_high))
            c.push_back(p);
    eligible_count = c.size();
    why = "the highest sequence PSNR";
    keepBest(c, psnrKey, 0.02, true);
    if (c.size() > 1) why = "PSNR tied within 0.02 dB, the highest SSIM", keepBest(c, ssimKey, 1e-4, true);
    if (c.size() > 1) why = "PSNR and SSIM tied, the lowest ECI", keepBest(c, eciKey, 1e-4, false);
    if (c.size() > 1) why = "PSNR, SSIM and ECI tied, the fastest", keepBest(c, timeKey, 0, false);
    return c.front();
}

std::string settingSentence(const SweepSettingField& f, const std::vector<const SweepPoint*>& ran,
                            const SweepPoint& best, size_t eligible, const std::string& why, double margin) {
    std::string s = std::string(f.name) + " " + *settingText(best, f) + " (" + best.config + ": " +
                    fmtMs(*best.gpu_ms) + ", " + fmtDb(best.psnr_db) + ", SSIM " + fmt(best.ssim, 4) + ", ECI " +
                    fmt(best.eci, 4) + "): " + why + " of the " +
                    (eligible == 1 ? std::string("one Pareto-front configuration")
                                   : std::to_string(eligible) + " Pareto-front configurations") +
                    " not measurably slower than the fastest (within " + fmtShort(margin * 100) +
                    "% or overlapping intervals), of " + std::to_string(ran.size()) + " that ran";
    const SweepPoint* worst = ran.front();
    for (const auto* p : ran)
        if (psnrKey(*p) < psnrKey(*worst)) worst = p;
    if (best.psnr_db && worst->psnr_db && *best.psnr_db - *worst->psnr_db >= 0.01)
        s += "; " + worst->config + " scores " + fmt(*best.psnr_db - *worst->psnr_db, 2) + " dB less";
    else
        s += "; PSNR varies less than 0.01 dB across them";
    return s + ".";
}

// One setting at one cost of one group; nullopt when it was not swept there.
std::optional<SettingChoice> chooseSetting(const Group& g, double cost, const SweepSettingField& f,
                                           const std::vector<ToleranceChoice>& tolerances, double margin) {
    std::set<std::string> values;
    std::vector<const SweepPoint*> ran;
    for (const auto& p : g.points) {
        if (p.shading_cost != cost || !settingText(p, f)) continue;
        values.insert(*settingText(p, f));
        if (p.hasTimes() && p.gpu_ms) ran.push_back(&p);
    }
    if (values.size() < 2) return std::nullopt;
    SettingChoice c{g.path, g.reference, cost, f.name, "", "", ""};
    const std::string suffix = costSuffix(g.points, cost);
    if (ran.empty()) {
        c.sentence = std::string(f.name) + suffix + ": none of its configurations ran (skipped or failed), so no value "
                     "is recommended.";
        return c;
    }
    const SweepPoint* best = nullptr;
    if (std::string(f.name) == "cso-tolerance") {
        for (const auto& t : tolerances)
            if (t.shading_cost == cost && t.tolerance)
                for (const auto* p : ran)
                    if (p->number("cso_tolerance") && !best && fmtShort(*p->number("cso_tolerance")) == fmtShort(*t.tolerance))
                        best = p, c.sentence = t.sentence;
    }
    if (!best) {
        size_t eligible = 0;
        std::string why;
        best = bestOnFront(ran, margin, eligible, why);
        c.sentence = settingSentence(f, ran, *best, eligible, why + suffix, margin);
    }
    c.value = *settingText(*best, f);
    c.config = best->config;
    return c;
}

}  // namespace

std::vector<SettingChoice> recommendSettings(const std::vector<SweepPoint>& points, const VariantRoles& roles,
                                             double margin) {
    std::vector<SettingChoice> out;
    for (const auto& g : groups(points)) {
        const auto tolerances = recommendTolerance(g.points, roles, margin);
        for (double cost : shadingCosts(g.points))
            for (const auto& f : sweepSettingFields())
                if (auto c = chooseSetting(g, cost, f, tolerances, margin)) out.push_back(std::move(*c));
    }
    return out;
}

std::vector<std::string> pathDisagreements(const std::vector<SettingChoice>& choices) {
    std::map<std::tuple<std::string, std::string, double>, std::vector<const SettingChoice*>> by;
    std::set<std::string> references;
    std::set<double> costs;
    for (const auto& c : choices) {
        if (c.value.empty()) continue;
        by[{c.setting, c.reference, c.shading_cost}].push_back(&c);
        references.insert(c.reference);
        costs.insert(c.shading_cost);
    }
    std::vector<std::string> out;
    for (const auto& [key, list] : by) {
        std::set<std::string> values, paths;
        for (const auto* c : list) values.insert(c->value), paths.insert(c->path);
        if (values.size() < 2 || paths.size() < 2) continue;
        const auto& [setting, reference, cost] = key;
        std::string s = "the recommended " + setting + " differs between paths";
        if (references.size() > 1) s += " (reference " + reference + ")";
        if (costs.size() > 1) s += " at shading cost " + fmtShort(cost);
        s += ":";
        for (size_t i = 0; i < list.size(); ++i)
            s += std::string(i ? "," : "") + " " + list[i]->value + " on " + list[i]->path;
        out.push_back(s + "; the best value depends on the content: choose by the path closest to yours, or sweep more");
    }
    return out;
}

std::vector<std::string> sweepSummaryLines(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    std::vector<std::string> lines;
    const auto gs = groups(points);
    const bool paths_vary = pathsVary(gs), refs_vary = referencesVary(gs);
    const auto choices = recommendSettings(points, roles);
    for (const auto& c : choices) {
        Group g{c.path, c.reference, {}};
        std::string where = groupName(g, paths_vary, refs_vary);
        lines.push_back("recommended " + (where.empty() ? "" : "[" + where + "] ") + c.sentence);
    }
    if (!choices.empty()) lines.push_back("rule: " + settingRule(roles) + ".");
    for (const auto& w : pathDisagreements(choices)) lines.push_back("warning: " + w + ".");
    for (const auto& g : gs) {
        std::string where = groupName(g, paths_vary, refs_vary);
        for (const auto& e : equalCost(g.points, recommendTolerance(g.points, roles), roles))
            lines.push_back("equal cost: " + (where.empty() ? "" : "[" + where + "] ") + e.verdict);
    }
    return lines;
}

}  // namespace cbr::reports
