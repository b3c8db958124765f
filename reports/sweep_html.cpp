// sweep.html: the answers, the error-against-time plane, metrics against each swept
// setting and the configurations; and the index page of a sweep over outer dimensions.
#include "reports/sweep.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "reports/csv.h"
#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_data.h"
#include "reports/report_sections.h"
#include "reports/svg.h"
#include "reports/sweep_detail.h"

namespace cbr::reports {
namespace {

using namespace sweep_detail;

// The variants the sweep ran, in the order of their rows (the harness writes them in the
// variant table's order): reports never list variants themselves.
std::vector<std::string> variantsOf(const std::vector<SweepPoint>& points) {
    std::vector<std::string> out;
    for (const auto& p : points)
        if (std::find(out.begin(), out.end(), p.variant) == out.end()) out.push_back(p.variant);
    return out;
}

const char* kCostColours[] = {"#009e73", "#0072b2", "#d55e00", "#cc79a7", "#e69f00", "#56b4e9", "#a08c00"};

std::string jsonString(const nlohmann::json& j, const std::string& ptr) {
    try {
        const auto& v = j.at(nlohmann::json::json_pointer(ptr));
        return v.is_string() ? v.get<std::string>() : v.dump();
    } catch (const std::exception&) {
        return "";
    }
}

struct Metric {
    const char* label;
    std::function<std::optional<double>(const SweepPoint&)> value;
    bool jod = false;  // charted only where the sweep has JODs (sweepRanksByJod)
};
std::optional<double> classShare(const SweepPoint& p, const char* cls) {
    return p.classes.count(cls) ? std::optional<double>(p.classes.at(cls)) : std::nullopt;
}
const std::vector<Metric>& metrics() {
    static const std::vector<Metric> m = {
        {"GPU frame time, median (ms)", [](const SweepPoint& p) { return p.gpu_ms; }},
        {"sequence PSNR (dB)", [](const SweepPoint& p) { return p.psnr_db; }},
        {"ColorVideoVDP (JOD)", [](const SweepPoint& p) { return p.jod; }, true},
        {"SSIM", [](const SweepPoint& p) { return p.ssim; }},
        {"edge crawl index ECI", [](const SweepPoint& p) { return p.eci; }}};
    return m;
}
const std::vector<Metric>& classMetrics() {
    static const std::vector<Metric> m = {
        {"px_reused share", [](const SweepPoint& p) { return classShare(p, rundir::pixels::kReused); }},
        {"px_occluded share", [](const SweepPoint& p) { return classShare(p, rundir::pixels::kOccluded); }}};
    return m;
}

// What a point shares with the others of its line in a chart against one setting: its
// variant, the other settings that vary, its shading cost and its (path, reference) sweep.
struct Families {
    std::vector<const SweepSettingField*> varying;
    bool costs_vary = false, groups_vary = false;
    std::string of(const SweepPoint& p) const {
        std::string key = p.variant;
        for (const auto* f : varying) key += " " + std::string(f->name) + "=" + settingText(p, *f).value_or("-");
        if (costs_vary) key += " cost " + fmtShort(p.shading_cost);
        if (groups_vary) key += " [" + p.path + (p.reference.empty() ? "" : " ref=" + p.reference) + "]";
        return key;
    }
};

Families familiesFor(const std::vector<SweepPoint>& points, const std::string& variant, const SweepSettingField& f) {
    Families fam;
    fam.costs_vary = shadingCosts(points).size() > 1;
    fam.groups_vary = groups(points).size() > 1;
    for (const auto& other : sweepSettingFields()) {
        std::set<std::string> values;
        for (const auto& p : points)
            if (p.variant == variant && &other != &f) values.insert(settingText(p, other).value_or("-"));
        if (values.size() > 1) fam.varying.push_back(&other);
    }
    return fam;
}

// Charts of each metric against one numeric setting for one variant, a line per family
// (Families); `flat` (cbr-aso beside the tolerance) is drawn as a constant line.
std::string paramCharts(const std::vector<SweepPoint>& points, const std::string& variant, const SweepSettingField& f,
                        const char* flat, bool with_classes) {
    std::set<double> xs_set;
    for (const auto& p : points)
        if (p.variant == variant && p.number(f.column)) xs_set.insert(*p.number(f.column));
    if (xs_set.size() < 2) return "";
    std::vector<double> xs(xs_set.begin(), xs_set.end());
    const bool log_x = xs.front() > 0 && xs.back() / xs.front() >= 20;
    std::vector<double> x_plot;
    for (double x : xs) x_plot.push_back(log_x ? std::log10(x) : x);
    const Families fam = familiesFor(points, variant, f);
    std::vector<std::string> families;
    for (const auto& p : points)
        if (p.variant == variant && p.number(f.column)) {
            std::string family = fam.of(p);
            if (std::find(families.begin(), families.end(), family) == families.end()) families.push_back(family);
        }
    std::vector<Series> legend;
    for (size_t k = 0; k < families.size(); ++k) legend.push_back({families[k], kCostColours[k % 7], {}});
    if (flat) legend.push_back({flat, "#888", {}});
    std::string out = "<h3>" + esc(variant) + " against " + esc(f.name) + "</h3>" +
                      legendHtml(legend, flat ? std::string(flat) + ": grey, flat (it has no such setting)." : "") +
                      "<div class=\"grid2\">";
    auto chart = [&](const Metric& m) {
        LineChart c;
        c.y_label = m.label;
        c.x_label = log_x ? "log10 " + std::string(f.name) : std::string(f.name);
        c.x = x_plot;
        c.x_integer = false;
        for (size_t k = 0; k < families.size(); ++k) {
            Series s{families[k], kCostColours[k % 7], {}};
            for (double x : xs) {
                std::optional<double> y;
                for (const auto& p : points)
                    if (p.variant == variant && p.number(f.column) == x && p.hasTimes() &&
                        fam.of(p) == families[k])
                        y = m.value(p);
                s.y.push_back(y);
            }
            c.series.push_back(s);
        }
        if (flat)
            if (const auto* fp = findVariant(points, flat, shadingCosts(points).front())) {
                Series fs{flat, "#888", {}};
                fs.y.assign(xs.size(), m.value(*fp));
                c.series.push_back(fs);
            }
        return "<div class=\"chart-block\">" + lineChartSvg(c) + "</div>";
    };
    const bool jod = sweepRanksByJod(points);
    for (const auto& m : metrics())
        if (!m.jod || jod) out += chart(m);
    // Where the reconstruction's pixels come from, against the setting (checkerboard only).
    if (with_classes)
        for (const auto& m : classMetrics()) out += chart(m);
    return out + "</div>";
}

// Charts against every swept numeric setting, for each variant it changes.
std::string paramsSection(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    std::string html = "<section id=\"params\"><h2>Metrics against each setting</h2>";
    for (const auto& f : sweepSettingFields()) {
        if (!f.number) continue;
        const bool tol = std::string(f.name) == "cso-tolerance";
        for (const auto& v : variantsOf(points)) {
            // The tolerance's charts show the variant that bounds its cost as a flat line.
            const VariantRole* role = roles.find(v);
            const char* flat = tol && role && !role->cost_bound.empty() ? role->cost_bound.c_str() : nullptr;
            if (v != roles.reference) html += paramCharts(points, v.c_str(), f, flat, tol);
        }
    }
    if (shadingCosts(points).size() > 1) {
        html += "<h3>GPU time against shading cost</h3><div class=\"grid2\">";
        LineChart c;
        c.y_label = "GPU frame time, median (ms)";
        c.x_label = "shading cost";
        c.x = shadingCosts(points);
        c.x_integer = false;
        std::vector<Series> legend;
        const std::vector<std::string> variants = variantsOf(points);
        for (const auto& v : variants) {
            // The first configuration of each variant per cost (the swept values' first).
            Series s{v, variantColor(variants, v, roles.reference), {}};
            for (double cost : c.x) {
                const SweepPoint* p = findVariant(points, v, cost);
                s.y.push_back(p ? p->gpu_ms : std::nullopt);
            }
            c.series.push_back(s);
            legend.push_back({v, variantColor(variants, v, roles.reference), {}});
        }
        html += legendHtml(legend) + "<div class=\"chart-block\">" + lineChartSvg(c) + "</div></div>";
    }
    return html + "</section>";
}

std::string answerSection(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    const Quality q = qualityOf(points);
    const auto choices = recommendTolerance(points, roles);
    const auto settings = recommendSettings(points, roles);
    const VariantRole* bounded = roles.bounded();
    const std::string tuned = bounded ? bounded->name : "tolerance", bound = bounded ? bounded->cost_bound : "bound";
    const bool others = std::any_of(settings.begin(), settings.end(),
                                    [](const SettingChoice& c) { return c.setting != "cso-tolerance"; });
    std::string html = "<section id=\"answer\">";
    if (choices.empty() && !others)
        html += "<p class=\"answer\"><b>CSO tolerance:</b> no " + esc(tuned) + " configuration ran, so none is recommended.</p>";
    for (const auto& c : choices) html += "<p class=\"answer\"><b>Recommended:</b> " + esc(c.sentence) + "</p>";
    if (!choices.empty() || !others)
        html += "<p class=\"note\">Rule: among the " + esc(tuned) + " tolerances whose median GPU time stays within " +
                fmtShort(kCostMargin * 100) + "% of " + esc(bound) + "'s at the same shading cost, those within " +
                esc(q.diff(q.tie())) + " of the best " + esc(q.name()) + "; of these the lowest edge crawl index (within "
                "1e-4); of these the loosest tolerance: the edge of the quality plateau, before more reuse starts to "
                "cost quality.</p>";
    bool any = false;
    for (const auto& c : settings)
        if (c.setting != "cso-tolerance")
            html += "<p class=\"answer\"><b>Recommended:</b> " + esc(c.sentence) + "</p>", any = true;
    if (any) {
        std::string rule = settingRule(roles, q.jod);
        rule[0] = char(std::toupper(static_cast<unsigned char>(rule[0])));
        html += "<p class=\"note\">Rule for every other swept setting: " + esc(rule) + ".</p>";
    }
    if (q.jod) html += "<p class=\"note\">" + esc(kJodMeaning) + "</p>";
    return html + "</section>";
}

// "a, b and c".
std::string listed(const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i) s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return s;
}

// The equal-cost comparisons side by side, with each side's JOD where the sweep has them.
std::string equalTable(const std::vector<EqualCost>& equal, const std::string& scaled, bool jod) {
    auto num = [](const std::string& text) { return "<td class=\"num\">" + text + "</td>"; };
    const std::string jod_head = jod ? "<th class=\"num\">JOD</th>" : "";
    std::string html = "<div class=\"scroll\"><table><tr><th>configuration</th><th class=\"num\">cost</th><th "
                       "class=\"num\">GPU ms</th>" + jod_head + "<th class=\"num\">PSNR dB</th><th class=\"num\">SSIM</th>"
                       "<th class=\"num\">ECI</th><th>" + esc(scaled) + " at that cost</th><th class=\"num\">scale</th>"
                       "<th class=\"num\">GPU ms</th>" + jod_head + "<th class=\"num\">PSNR dB</th>"
                       "<th class=\"num\">SSIM</th><th class=\"num\">ECI</th></tr>";
    for (const auto& e : equal)
        html += "<tr><td>" + esc(e.config) + "</td>" + num(fmtShort(e.shading_cost)) + num(fmt(e.cbr_ms, 2)) +
                (jod ? num(jodText(e.cbr_jod, kDash)) : "") + num(fmt(e.cbr_psnr, 2)) + num(fmt(e.cbr_ssim, 4)) +
                num(fmt(e.cbr_eci, 4)) + "<td>" + (e.matched ? "interpolated" : "nearest (no match)") + "</td>" +
                num(fmt(e.drr_scale, 3)) + num(fmt(e.drr_ms, 2)) + (jod ? num(jodText(e.drr_jod, kDash)) : "") +
                num(fmt(e.drr_psnr, 2)) + num(fmt(e.drr_ssim, 4)) + num(fmt(e.drr_eci, 4)) + "</tr>";
    return html + "</table></div>";
}

std::string equalSection(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    const auto equal = equalCost(points, recommendTolerance(points, roles), roles);
    const auto baselines = roles.equalCostBaselines();
    std::vector<std::string> peers;
    for (const auto& b : baselines)
        for (const auto& v : roles.equalCostPeers(b)) peers.push_back(v);
    const std::string scaled = listed(baselines);
    std::string html = "<section id=\"equal\"><h2>Quality at equal cost: " + esc(listed(peers)) + " against " +
                       esc(scaled) + "</h2>";
    for (const auto& e : equal) html += "<p class=\"answer\">" + esc(e.verdict) + "</p>";
    if (!equal.empty()) html += equalTable(equal, scaled, sweepRanksByJod(points));
    return html + "<p class=\"note\">The " + esc(scaled) + " scale whose median GPU time equals the configuration's, "
                  "with its quality, interpolated linearly in time between the two swept scales around it (their times "
                  "sorted). Without a swept scale on both sides the nearest is shown and no equal-cost claim is made.</p>"
                  "</section>";
}

// The plane of the quality the sweep ranks by (sweep_detail.h, Quality) against time, per cost.
std::string planeSection(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    const Quality q = qualityOf(points);
    std::string html = "<section id=\"plane\"><h2>Error against run time</h2>";
    std::vector<Series> legend;
    const std::vector<std::string> variants = variantsOf(points);
    for (const auto& v : variants) legend.push_back({v, variantColor(variants, v, roles.reference), {}});
    for (double cost : shadingCosts(points)) {
        ScatterChart sc;
        sc.title = q.brief() + " against GPU time" + costSuffix(points, cost);
        sc.width = 560;
        sc.label_front_only = true;
        // drr at scale 1 is nearly the reference: on the lane, not squashing the rest (a JOD ends at 10).
        if (!q.jod) sc.lane_above = 50.0;
        sc.x_label = "GPU frame time, median (ms)";
        sc.y_label = q.jod ? "ColorVideoVDP (JOD, higher is better)" : "sequence PSNR (dB)";
        sc.y_higher_is_better = true;
        for (const auto& p : points)
            if (p.shading_cost == cost && p.hasTimes() && p.gpu_ms)
                sc.points.push_back({p.config, variantColor(variants, p.variant, roles.reference), *p.gpu_ms, q.of(p),
                                     std::nullopt, "speed-up " + speedupText(p.speedup, kDash)});
        html += "<h3>" + std::string(q.jod ? "JOD" : "Sequence PSNR") + " against median GPU time" +
                esc(costSuffix(points, cost)) + "</h3>" + legendHtml(legend) +
                "<div class=\"chart-block\" style=\"max-width:900px\">" + scatterChartSvg(sc) + "</div>";
        std::string list;
        for (size_t i : paretoFront(sc.points, true)) list += (list.empty() ? "" : ", ") + sc.points[i].label;
        html += "<p class=\"note\">Pareto front (no other configuration has both a lower median GPU time and a higher " +
                q.brief() + "): " + esc(list) + ". Only the front is labelled (every point has a tooltip). " +
                esc(roles.reference) +
                (q.jod ? "'s JOD is 10 (it is the reference): higher is better, up to no visible difference.</p>"
                       : "'s PSNR is infinite (it is the reference); it and anything above 50 dB sit on the lane above "
                         "the plot.</p>");
    }
    return html + "</section>";
}

std::string tableSection(const std::vector<SweepPoint>& points, const VariantRoles& roles) {
    std::string html = "<section id=\"table\"><h2>Configurations</h2><div class=\"scroll\"><table><tr>";
    const bool jod = sweepRanksByJod(points);  // sweeps from before ColorVideoVDP: no column
    std::vector<const char*> head = {"config", "status", "GPU ms", "95% CI", "speed-up [95% CI]", "PSNR dB", "SSIM",
                                     "ECI", "reused %", "occluded %"};
    if (jod) head.insert(head.begin() + 5, "ColorVideoVDP");
    for (const char* h : head) html += std::string("<th") + (h == head[0] || h == head[1] ? ">" : " class=\"num\">") + h + "</th>";
    html += "</tr>";
    const std::vector<std::string> variants = variantsOf(points);
    for (const auto& p : points) {
        html += "<tr><td class=\"variant\" style=\"color:" + variantColor(variants, p.variant, roles.reference) + "\">" + esc(p.config) +
                "</td><td>" + esc(p.status) + "</td><td class=\"num\">" + fmt(p.gpu_ms, 2) + "</td><td class=\"num\">" +
                (p.gpu_ms_low ? fmt(p.gpu_ms_low, 2) + "\u2013" + fmt(p.gpu_ms_high, 2) : std::string(kDash)) +
                "</td><td class=\"num\">" + speedupText(p.speedup, kDash) +
                (jod ? "</td><td class=\"num\">" + jodText(p.jod, kDash) : std::string()) + "</td><td class=\"num\">" +
                fmt(p.psnr_db, 2) +
                "</td><td class=\"num\">" + fmt(p.ssim, 4) + "</td><td class=\"num\">" + fmt(p.eci, 4) +
                "</td><td class=\"num\">" + fmtPct(classShare(p, rundir::pixels::kReused), 1) + "</td><td class=\"num\">" +
                fmtPct(classShare(p, rundir::pixels::kOccluded), 1) + "</td></tr>";
    }
    return html + "</table></div><p class=\"note\">From sweep.csv. GPU ms: median over all frames and repetitions; the "
                  "interval is a 95% bootstrap interval of the median over repetitions. Speed-up: the median of paired "
                  "per-frame ratios against the full configuration at the same shading cost, with its 95% interval. A configuration whose route or feature the device "
                  "lacks is `skipped`, with the reason in sweep.csv's note.</p></section>";
}

std::string runTitle(const nlohmann::json& run) {
    std::string where = jsonString(run, rundir::pointer(run_json::kScene, run_json::scene::kName)) + " / " +
                        jsonString(run, rundir::pointer(run_json::kPath, run_json::path::kName)) + " at " +
                        jsonString(run, rundir::pointer(run_json::kSettings, run_json::settings::kWidth)) + "\u00d7" +
                        jsonString(run, rundir::pointer(run_json::kSettings, run_json::settings::kHeight));
    std::string pipeline;
    for (const auto& v : run.value(run_json::kVariants, nlohmann::json::array()))
        if (v.is_object() && v.contains(run_json::variant::kPipeline) && v[run_json::variant::kPipeline].is_string())
            pipeline = v[run_json::variant::kPipeline];
    return "cbrbench sweep: " + where + (pipeline.empty() ? "" : " (" + pipeline + ")");
}

}  // namespace

std::string sweepHtml(const std::filesystem::path& dir, const VariantRoles& roles) {
    const SweepData d = loadSweep(dir);
    const std::string title = runTitle(d.run);
    std::string html = pageStart(title);
    html += "<h1>" + esc(title) + "</h1><div class=\"sub\">" + esc(jsonString(d.run, rundir::pointer(run_json::kDevice, run_json::device::kName))) + " \u00b7 " +
            esc(jsonString(d.run, rundir::pointer(run_json::kDate))) + " \u00b7 commit " +
            esc(jsonString(d.run, rundir::pointer(run_json::kTool, run_json::tool::kCommit))) + " \u00b7 " +
            std::to_string(d.points.size()) + " configurations, interleaved in one process \u00b7 <a href=\"report.html\">"
            "the run's full report</a></div>";
    if (auto note = jsonString(d.run, rundir::pointer(run_json::kDevice, run_json::device::kTimingNote)); !note.empty())
        html += "<p class=\"callout\"><b>Timing note:</b> " + esc(note) + "</p>";
    html += "<nav><a href=\"#answer\">answer</a><a href=\"#equal\">equal cost</a><a href=\"#plane\">error vs time</a>"
            "<a href=\"#params\">settings</a><a href=\"#table\">configurations</a></nav>";
    html += answerSection(d.points, roles) + equalSection(d.points, roles) + planeSection(d.points, roles) +
            paramsSection(d.points, roles) + tableSection(d.points, roles);
    return html + pageEnd();
}

std::string sweepIndexHtml(const std::filesystem::path& dir, const VariantRoles& roles) {
    const SweepData d = loadSweep(dir);
    const auto gs = groups(d.points);
    const bool paths_vary = pathsVary(gs), refs_vary = referencesVary(gs);
    nlohmann::json first_run;
    if (!gs.empty()) first_run = loadSweep(dir / sweepGroupDir(gs[0].path, gs[0].reference, paths_vary, refs_vary)).run;
    std::string title = "cbrbench sweep: " + jsonString(first_run, rundir::pointer(run_json::kScene, run_json::scene::kName)) + " over " + std::to_string(gs.size()) +
                        " sweeps (" + (paths_vary ? "paths" : "") + (paths_vary && refs_vary ? " \u00d7 " : "") +
                        (refs_vary ? "reference kinds" : "") + ")";
    std::string html = pageStart(title) + "<h1>" + esc(title) + "</h1><div class=\"sub\">" +
                       esc(jsonString(first_run, rundir::pointer(run_json::kDevice, run_json::device::kName))) + " \u00b7 " +
                       esc(jsonString(first_run, rundir::pointer(run_json::kDate))) +
                       " \u00b7 each sweep a run of its own (its reference rendered once), one after another</div>";
    const auto choices = recommendSettings(d.points, roles);
    for (const auto& w : pathDisagreements(choices))
        html += "<p class=\"callout\"><b>Warning:</b> " + esc(w) + ".</p>";
    html += "<section id=\"answer\"><h2>Recommended values</h2><div class=\"scroll\"><table><tr><th>setting</th>"
            "<th class=\"num\">cost</th>";
    for (const auto& g : gs) html += "<th>" + esc(groupName(g, paths_vary, refs_vary)) + "</th>";
    html += "</tr>";
    std::vector<std::pair<std::string, double>> rows;
    for (const auto& c : choices)
        if (std::find(rows.begin(), rows.end(), std::make_pair(c.setting, c.shading_cost)) == rows.end())
            rows.emplace_back(c.setting, c.shading_cost);
    for (const auto& [setting, cost] : rows) {
        html += "<tr><td>" + esc(setting) + "</td><td class=\"num\">" + fmtShort(cost) + "</td>";
        for (const auto& g : gs) {
            std::string cell(kDash), why;
            for (const auto& c : choices)
                if (c.setting == setting && c.shading_cost == cost && c.path == g.path && c.reference == g.reference)
                    cell = c.value.empty() ? std::string(kDash) : c.value, why = c.sentence;
            html += "<td title=\"" + esc(why) + "\">" + esc(cell) + "</td>";
        }
        html += "</tr>";
    }
    std::string rule = settingRule(roles, sweepRanksByJod(d.points));
    rule[0] = char(std::toupper(static_cast<unsigned char>(rule[0])));
    html += "</table></div><p class=\"note\">Rule: " + esc(rule) + ". Hover a value for its sentence.</p>";
    for (const auto& g : gs) {
        const std::string sub = sweepGroupDir(g.path, g.reference, paths_vary, refs_vary);
        html += "<h3>" + esc(groupName(g, paths_vary, refs_vary)) + ": <a href=\"" + esc(sub) + "/" + rundir::kSweepHtml + "\">" + rundir::kSweepHtml +
                "</a> \u00b7 <a href=\"" + esc(sub) + "/" + rundir::kReportHtml + "\">" + rundir::kReportHtml + "</a></h3>";
        for (const auto& c : choices)
            if (c.path == g.path && c.reference == g.reference) html += "<p class=\"answer\">" + esc(c.sentence) + "</p>";
    }
    html += "</section>" + paramsSection(d.points, roles);
    html += "<p class=\"note\">From sweep.csv: every sweep's rows, each naming its path and reference.</p>";
    return html + pageEnd();
}

void writeSweepReport(const std::filesystem::path& dir, const VariantRoles& roles) {
    const bool index = groups(loadSweep(dir).points).size() > 1;
    const std::string html = index ? sweepIndexHtml(dir, roles) : sweepHtml(dir, roles);
    writeTextAtomically(dir / rundir::kSweepHtml, html);
}

}  // namespace cbr::reports
