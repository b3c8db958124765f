// The sweep's answers: a recommended value per swept setting (the CSO tolerance by its own
// rule), disagreements between paths, and the lines `cbrbench sweep` prints (quality at
// equal cost: sweep_equal.cpp). Quality is the JOD where the sweep has it, else the PSNR
// (sweep_detail.h, Quality). Which variant plays which part comes from the variant table
// (VariantRoles).
#include "reports/sweep.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/sweep_detail.h"
#include "rundir/setting_columns.h"

namespace cbr::reports {
namespace {

using namespace sweep_detail;

// The variant whose time bounds the tolerance's choice: the cost bound of the variant that takes it.
std::string toleranceBound(const std::vector<const SweepPoint*>& cso, const VariantRoles& roles) {
    const VariantRole* r = cso.empty() ? nullptr : roles.find(cso.front()->variant);
    return r ? r->cost_bound : std::string();
}

}  // namespace

namespace {

// The tolerances of one cost as the rule narrows them: those within the cost margin of the
// bound (all of them where none is), the plateau of the best quality, the choice and the worst.
struct TolerancePick {
    std::vector<const SweepPoint*> within, plateau;
    bool none_within = false;
    const SweepPoint* best = nullptr;
    const SweepPoint* worst = nullptr;
};

TolerancePick pickTolerance(const std::vector<const SweepPoint*>& cso, const SweepPoint* aso, double margin,
                            const Quality& q) {
    TolerancePick t;
    for (const auto* p : cso)
        if (!aso || *p->gpu_ms <= *aso->gpu_ms * (1 + margin)) t.within.push_back(p);
    t.none_within = t.within.empty();
    if (t.none_within) t.within = cso;  // every tolerance costs more: still name the best one
    // The plateau of the best quality (within 0.02 dB or 0.02 JOD of it), then its lowest ECI
    // (within 1e-4), then the loosest tolerance of those: the edge of the plateau, before
    // reuse starts to cost quality.
    double top = -1e300, low_eci = 1e300;
    for (const auto* p : t.within) top = std::max(top, q.key(*p));
    for (const auto* p : t.within)
        if (q.key(*p) >= top - q.tie()) t.plateau.push_back(p), low_eci = std::min(low_eci, p->eci.value_or(1e300));
    for (const auto* p : t.plateau)
        if (p->eci.value_or(1e300) <= low_eci + 1e-4 &&
            (!t.best || *p->number(rundir::settingColumn("cso-tolerance")) > *t.best->number(rundir::settingColumn("cso-tolerance"))))
            t.best = p;
    t.worst = cso.front();
    for (const auto* p : cso)
        if (q.key(*p) < q.key(*t.worst)) t.worst = p;
    return t;
}

// The sentence of a tolerance's choice (after "cso-tolerance 0.1: ").
std::string toleranceSentence(const TolerancePick& t, size_t n_cso, const SweepPoint* aso, const std::string& bound,
                              double margin, const Quality& q) {
    const SweepPoint* best = t.best;
    const std::string n = std::to_string(n_cso);
    std::string s;
    if (aso && t.none_within) {
        s += "every one of the " + n + " tolerances costs more than " + fmtShort(margin * 100) + "% above " + bound +
             "'s " + fmtMs(*aso->gpu_ms) + ", and this one has the best " + q.name() + ", " + q.text(q.of(*best)) +
             " (" + bound + " " + q.text(q.of(*aso)) + ")";
    } else if (aso) {
        s += (t.plateau.size() > 1 ? "the loosest tolerance within " + q.diff(q.tie()) + " of the best " + q.name() + ", "
                                   : "the best " + q.name() + ", ") +
             q.text(q.of(*best)) + " against " + bound + "'s " + q.text(q.of(*aso)) + ", among the " +
             std::to_string(t.within.size()) + " of " + n + " tolerances whose median GPU time stays within " +
             fmtShort(margin * 100) + "% of " + bound + "'s (" + fmtMs(*best->gpu_ms) + " vs " + fmtMs(*aso->gpu_ms) + ")";
    } else {
        s += "the best " + q.name() + " of the " + n + " tolerances, " + q.text(q.of(*best)) + " (no " +
             (bound.empty() ? std::string("variant") : bound + " configuration") + " to bound the cost)";
    }
    s += ", with ECI " + fmt(best->eci, 4) + (aso ? " (" + bound + " " + fmt(aso->eci, 4) + ")" : std::string());
    const auto top = q.of(*best), low = q.of(*t.worst);
    if (t.worst != best && top && low && *top - *low >= 0.01)
        s += ", while tolerance " + fmtShort(*t.worst->number(rundir::settingColumn("cso-tolerance"))) + " loses " + q.diff(*top - *low);
    else
        s += "; " + q.brief() + " varies less than " + q.diff(0.01) + " across the tolerances";
    return s + ".";
}

}  // namespace

std::vector<ToleranceChoice> recommendTolerance(const std::vector<SweepPoint>& points, const VariantRoles& roles,
                                                double margin) {
    const Quality q = qualityOf(points);
    std::vector<ToleranceChoice> out;
    for (double cost : shadingCosts(points)) {
        std::vector<const SweepPoint*> cso;
        for (const auto& p : points)
            if (p.shading_cost == cost && p.hasTimes() && p.gpu_ms && p.number(rundir::settingColumn("cso-tolerance")))
                cso.push_back(&p);
        if (cso.empty()) continue;
        const std::string bound = toleranceBound(cso, roles);
        const SweepPoint* aso = bound.empty() ? nullptr : findVariant(points, bound, cost);
        const TolerancePick t = pickTolerance(cso, aso, margin, q);
        ToleranceChoice c;
        c.shading_cost = cost;
        c.tolerance = t.best->number(rundir::settingColumn("cso-tolerance"));
        c.sentence = "cso-tolerance " + fmtShort(*c.tolerance) + costSuffix(points, cost) + ": " +
                     toleranceSentence(t, cso.size(), aso, bound, margin, q);
        out.push_back(c);
    }
    return out;
}

std::string settingRule(const VariantRoles& roles, bool jod) {
    const VariantRole* bounded = roles.bounded();
    const std::string bound = bounded ? bounded->cost_bound : std::string("its cost bound");
    const Quality q{jod};
    return "for each swept setting, per path, reference and shading cost, take the configurations it applies to that ran, "
           "keep their Pareto front of median GPU time against " + q.name() +
           (jod ? " (ColorVideoVDP, higher is better)" : "") + ", and of the front's configurations not "
           "measurably slower than its fastest one (median within 5%, or 95% intervals of the median overlapping) "
           "recommend the value of the one with the highest " + q.brief() + ", a " + q.brief() + " within " +
           q.diff(q.tie()) + " counting as a tie broken by the higher SSIM (within 1e-4), then the lower ECI (within "
           "1e-4), then the lower time (cso-tolerance keeps its own rule: the edge of the quality plateau within 5% of " +
           bound + "'s time)";
}

namespace {

// Keeps the points whose key lies within `eps` of the best (`higher`: larger is better).
void keepBest(std::vector<const SweepPoint*>& c, const std::function<double(const SweepPoint&)>& key, double eps,
              bool higher) {
    double best = higher ? -1e300 : 1e300;
    for (const auto* p : c) best = higher ? std::max(best, key(*p)) : std::min(best, key(*p));
    std::erase_if(c, [&](const SweepPoint* p) { return higher ? key(*p) < best - eps : key(*p) > best + eps; });
}

double ssimKey(const SweepPoint& p) { return p.ssim.value_or(-1e300); }
double eciKey(const SweepPoint& p) { return p.eci.value_or(1e300); }
double timeKey(const SweepPoint& p) { return *p.gpu_ms; }

// kSettingRule on the configurations of one setting; `why` says which criterion decided.
const SweepPoint* bestOnFront(const std::vector<const SweepPoint*>& ran, double margin, const Quality& q,
                              size_t& eligible_count, std::string& why) {
    auto quality = [&](const SweepPoint& p) { return q.key(p); };
    std::vector<const SweepPoint*> front;
    for (const auto* p : ran) {
        bool dominated = std::any_of(ran.begin(), ran.end(), [&](const SweepPoint* o) {
            return o != p && *o->gpu_ms <= *p->gpu_ms && quality(*o) >= quality(*p) &&
                   (*o->gpu_ms < *p->gpu_ms || quality(*o) > quality(*p));
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
    const std::string tied = q.brief();
    why = "the highest " + q.name();
    keepBest(c, quality, q.tie(), true);
    if (c.size() > 1) why = tied + " tied within " + q.diff(q.tie()) + ", the highest SSIM", keepBest(c, ssimKey, 1e-4, true);
    if (c.size() > 1) why = tied + " and SSIM tied, the lowest ECI", keepBest(c, eciKey, 1e-4, false);
    if (c.size() > 1) why = tied + ", SSIM and ECI tied, the fastest", keepBest(c, timeKey, 0, false);
    return c.front();
}

std::string settingSentence(const SweepSettingField& f, const std::vector<const SweepPoint*>& ran,
                            const SweepPoint& best, size_t eligible, const std::string& why, double margin,
                            const Quality& q) {
    std::string s = std::string(f.name) + " " + *settingText(best, f) + " (" + best.config + ": " +
                    fmtMs(*best.gpu_ms) + ", " + (q.jod ? jodText(best.jod, kDash) + ", " : "") +
                    fmtDb(best.psnr_db) + ", SSIM " + fmt(best.ssim, 4) + ", ECI " +
                    fmt(best.eci, 4) + "): " + why + " of the " +
                    (eligible == 1 ? std::string("one Pareto-front configuration")
                                   : std::to_string(eligible) + " Pareto-front configurations") +
                    " not measurably slower than the fastest (within " + fmtShort(margin * 100) +
                    "% or overlapping intervals), of " + std::to_string(ran.size()) + " that ran";
    const SweepPoint* worst = ran.front();
    for (const auto* p : ran)
        if (q.key(*p) < q.key(*worst)) worst = p;
    const auto top = q.of(best), low = q.of(*worst);
    if (top && low && *top - *low >= 0.01)
        s += "; " + worst->config + " scores " + q.diff(*top - *low) + " less";
    else
        s += "; " + q.brief() + " varies less than " + q.diff(0.01) + " across them";
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
                    if (p->number(rundir::settingColumn("cso-tolerance")) && !best && fmtShort(*p->number(rundir::settingColumn("cso-tolerance"))) == fmtShort(*t.tolerance))
                        best = p, c.sentence = t.sentence;
    }
    if (!best) {
        size_t eligible = 0;
        std::string why;
        const Quality q = qualityOf(g.points);
        best = bestOnFront(ran, margin, q, eligible, why);
        c.sentence = settingSentence(f, ran, *best, eligible, why + suffix, margin, q);
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
    const bool jod = sweepRanksByJod(points);
    if (!choices.empty()) lines.push_back("rule: " + settingRule(roles, jod) + ".");
    for (const auto& w : pathDisagreements(choices)) lines.push_back("warning: " + w + ".");
    for (const auto& g : gs) {
        std::string where = groupName(g, paths_vary, refs_vary);
        for (const auto& e : equalCost(g.points, recommendTolerance(g.points, roles), roles))
            lines.push_back("equal cost: " + (where.empty() ? "" : "[" + where + "] ") + e.verdict);
    }
    if (jod && !lines.empty()) lines.push_back("quality: " + std::string(kJodMeaning));
    return lines;
}

}  // namespace cbr::reports
