// sweep.csv -> the recommended CSO tolerance, quality at equal cost, and sweep.html.
#include "reports/sweep.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <stdexcept>

#include "reports/csv.h"
#include "reports/csv_read.h"
#include "reports/html.h"
#include "reports/report_sections.h"
#include "reports/svg.h"

namespace cbr::reports {
namespace {

const char* kTextColumns[] = {"config", "variant", "pipeline", "status", "note"};

bool isSweepNumeric(const std::string& name) {
    return std::find(std::begin(kTextColumns), std::end(kTextColumns), name) == std::end(kTextColumns);
}

std::string fmtMs(double ms) { return fmtShort(ms, 4) + " ms"; }
std::string fmtDb(std::optional<double> v) { return v ? fmt(v, 2) + " dB" : std::string(kDash); }

// Groups by shading cost, in ascending order.
std::vector<double> shadingCosts(const std::vector<SweepPoint>& points) {
    std::set<double> costs;
    for (const auto& p : points) costs.insert(p.shading_cost);
    return {costs.begin(), costs.end()};
}

const SweepPoint* findVariant(const std::vector<SweepPoint>& points, const std::string& variant, double cost) {
    for (const auto& p : points)
        if (p.variant == variant && p.shading_cost == cost && p.status == "ok" && p.gpu_ms) return &p;
    return nullptr;
}

double psnrKey(const SweepPoint& p) { return p.psnr_db ? *p.psnr_db : -1e300; }

std::string costSuffix(const std::vector<SweepPoint>& points, double cost) {
    return shadingCosts(points).size() > 1 ? " at shading cost " + fmtShort(cost) : "";
}

std::optional<double> lerp(std::optional<double> a, std::optional<double> b, double f) {
    if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b)) return std::nullopt;
    return *a + f * (*b - *a);
}

}  // namespace

const std::vector<std::string>& sweepColumns() {
    static const std::vector<std::string> cols = {
        "config", "variant", "pipeline", "shading_cost", "drr_scale", "cso_tolerance", "status", "note", "frames",
        "repeats", "gpu_ms_median", "gpu_ms_ci_low", "gpu_ms_ci_high", "noise_cv", "speedup_vs_full",
        "speedup_ci_low", "speedup_ci_high", "psnr_db", "ssim", "eci", "flicker_ratio", "px_shaded", "px_reused",
        "px_missing_parity", "px_occluded", "px_offscreen", "px_reset"};
    return cols;
}

SweepData loadSweep(const std::filesystem::path& dir) {
    SweepData d;
    d.dir = dir;
    CsvData csv = readCsv(dir / "sweep.csv", isSweepNumeric,
                          {"config", "variant", "status", "shading_cost", "gpu_ms_median", "psnr_db", "ssim", "eci"});
    for (size_t r = 0; r < csv.rows.size(); ++r) {
        SweepPoint p;
        p.config = csv.text(r, "config");
        p.variant = csv.text(r, "variant");
        p.status = csv.text(r, "status");
        if (p.config.empty() || p.variant.empty())
            throw std::invalid_argument((dir / "sweep.csv").string() + ": line " + std::to_string(csv.row_lines[r]) +
                                        ": empty config or variant; expected a configuration label and a variant name");
        p.shading_cost = csv.num(r, "shading_cost").value_or(1);
        p.drr_scale = csv.num(r, "drr_scale");
        p.cso_tolerance = csv.num(r, "cso_tolerance");
        p.gpu_ms = csv.num(r, "gpu_ms_median");
        p.gpu_ms_low = csv.num(r, "gpu_ms_ci_low");
        p.gpu_ms_high = csv.num(r, "gpu_ms_ci_high");
        p.speedup = csv.num(r, "speedup_vs_full");
        p.speedup_low = csv.num(r, "speedup_ci_low");
        p.speedup_high = csv.num(r, "speedup_ci_high");
        p.psnr_db = csv.num(r, "psnr_db");
        p.ssim = csv.num(r, "ssim");
        p.eci = csv.num(r, "eci");
        p.flicker = csv.num(r, "flicker_ratio");
        for (const auto& pc : kPixelClasses)
            if (auto v = csv.num(r, pc.column)) p.classes[pc.column] = *v;
        d.points.push_back(std::move(p));
    }
    auto run_file = dir / "run.json";
    if (std::filesystem::exists(run_file)) {
        std::ifstream in(run_file);
        d.run = nlohmann::json::parse(in, nullptr, false);
        if (d.run.is_discarded() || !d.run.is_object())
            throw std::invalid_argument(run_file.string() + ": not a JSON object; expected the run's run.json");
    }
    return d;
}

std::vector<ToleranceChoice> recommendTolerance(const std::vector<SweepPoint>& points, double margin) {
    std::vector<ToleranceChoice> out;
    for (double cost : shadingCosts(points)) {
        std::vector<const SweepPoint*> cso;
        for (const auto& p : points)
            if (p.variant == "cbr-cso" && p.shading_cost == cost && p.status == "ok" && p.gpu_ms && p.cso_tolerance)
                cso.push_back(&p);
        if (cso.empty()) continue;
        ToleranceChoice c;
        c.shading_cost = cost;
        const SweepPoint* aso = findVariant(points, "cbr-aso", cost);
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
            if (p->eci.value_or(1e300) <= low_eci + 1e-4 && (!best || *p->cso_tolerance > *best->cso_tolerance)) best = p;
        const SweepPoint* worst = cso.front();
        for (const auto* p : cso)
            if (psnrKey(*p) < psnrKey(*worst)) worst = p;
        c.tolerance = best->cso_tolerance;
        std::string s = "cso-tolerance " + fmtShort(*best->cso_tolerance) + costSuffix(points, cost) + ": ";
        const bool on_plateau = plateau.size() > 1;
        const std::string n = std::to_string(cso.size());
        if (aso && none_within) {
            s += "every one of the " + n + " tolerances costs more than " + fmtShort(margin * 100) +
                 "% above cbr-aso's " + fmtMs(*aso->gpu_ms) + ", and this one has the best sequence PSNR, " +
                 fmtDb(best->psnr_db) + " (cbr-aso " + fmtDb(aso->psnr_db) + ")";
        } else if (aso) {
            s += std::string(on_plateau ? "the loosest tolerance within 0.02 dB of the best sequence PSNR, "
                                        : "the best sequence PSNR, ") +
                 fmtDb(best->psnr_db) + " against cbr-aso's " + fmtDb(aso->psnr_db) + ", among the " +
                 std::to_string(within.size()) + " of " + n + " tolerances whose median GPU time stays within " +
                 fmtShort(margin * 100) + "% of cbr-aso's (" + fmtMs(*best->gpu_ms) + " vs " + fmtMs(*aso->gpu_ms) + ")";
        } else {
            s += "the best sequence PSNR of the " + n + " tolerances, " + fmtDb(best->psnr_db) +
                 " (no cbr-aso configuration to bound the cost)";
        }
        s += ", with ECI " + fmt(best->eci, 4) + (aso ? " (cbr-aso " + fmt(aso->eci, 4) + ")" : std::string());
        if (worst != best && best->psnr_db && worst->psnr_db && *best->psnr_db - *worst->psnr_db >= 0.01)
            s += ", while tolerance " + fmtShort(*worst->cso_tolerance) + " loses " +
                 fmt(*best->psnr_db - *worst->psnr_db, 2) + " dB";
        else
            s += "; PSNR varies less than 0.01 dB across the tolerances";
        c.sentence = s + ".";
        out.push_back(c);
    }
    return out;
}

std::vector<EqualCost> equalCost(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices) {
    std::vector<EqualCost> out;
    for (double cost : shadingCosts(points)) {
        std::vector<const SweepPoint*> drr;
        for (const auto& p : points)
            if (p.variant == "drr" && p.shading_cost == cost && p.status == "ok" && p.gpu_ms) drr.push_back(&p);
        std::sort(drr.begin(), drr.end(), [](auto* a, auto* b) { return *a->gpu_ms < *b->gpu_ms; });
        std::vector<const SweepPoint*> cbr;
        if (const auto* aso = findVariant(points, "cbr-aso", cost)) cbr.push_back(aso);
        for (const auto& ch : choices)
            if (ch.shading_cost == cost && ch.tolerance)
                for (const auto& p : points)
                    if (p.variant == "cbr-cso" && p.shading_cost == cost && p.status == "ok" && p.gpu_ms &&
                        p.cso_tolerance && fmtShort(*p.cso_tolerance) == fmtShort(*ch.tolerance))
                        cbr.push_back(&p);
        if (choices.empty())
            if (const auto* cso = findVariant(points, "cbr-cso", cost)) cbr.push_back(cso);
        for (const auto* c : cbr) {
            EqualCost e;
            e.config = c->config;
            e.shading_cost = cost;
            e.cbr_ms = *c->gpu_ms;
            e.cbr_psnr = c->psnr_db;
            e.cbr_ssim = c->ssim;
            e.cbr_eci = c->eci;
            const std::string who = c->variant == "cbr-cso" ? "cbr-cso (tolerance " + fmtShort(*c->cso_tolerance) + ")"
                                                            : c->variant;
            if (drr.empty()) {
                e.verdict = who + ": no drr configuration ran" + costSuffix(points, cost) + ", so there is nothing to "
                            "match its cost with (add --param drr-scale=LO:HI:lin:N).";
                out.push_back(e);
                continue;
            }
            const SweepPoint* lo = nullptr;
            const SweepPoint* hi = nullptr;
            for (size_t i = 0; i + 1 < drr.size(); ++i)
                if (*drr[i]->gpu_ms <= e.cbr_ms && e.cbr_ms <= *drr[i + 1]->gpu_ms) lo = drr[i], hi = drr[i + 1];
            if (drr.size() == 1 && *drr[0]->gpu_ms == e.cbr_ms) lo = hi = drr[0];
            if (lo) {
                double span = *hi->gpu_ms - *lo->gpu_ms;
                double f = span > 0 ? (e.cbr_ms - *lo->gpu_ms) / span : 0.0;
                e.matched = true;
                e.drr_ms = e.cbr_ms;
                e.drr_scale = lerp(lo->drr_scale, hi->drr_scale, f);
                e.drr_psnr = lerp(lo->psnr_db, hi->psnr_db, f);
                e.drr_ssim = lerp(lo->ssim, hi->ssim, f);
                e.drr_eci = lerp(lo->eci, hi->eci, f);
            } else {
                const SweepPoint* near = e.cbr_ms < *drr.front()->gpu_ms ? drr.front() : drr.back();
                e.drr_scale = near->drr_scale;
                e.drr_ms = near->gpu_ms;
                e.drr_psnr = near->psnr_db;
                e.drr_ssim = near->ssim;
                e.drr_eci = near->eci;
            }
            std::string s = who + " at " + fmtMs(e.cbr_ms) + costSuffix(points, cost) + ": ";
            if (e.matched) {
                s += "drr at the same cost renders at scale " + fmt(e.drr_scale, 3) + " with PSNR " + fmtDb(e.drr_psnr) +
                     ", SSIM " + fmt(e.drr_ssim, 4) + ", ECI " + fmt(e.drr_eci, 4) + ", against " + fmtDb(e.cbr_psnr) +
                     ", " + fmt(e.cbr_ssim, 4) + ", " + fmt(e.cbr_eci, 4);
                if (e.drr_psnr && e.cbr_psnr) {
                    double d = *e.cbr_psnr - *e.drr_psnr;
                    s += std::abs(d) < 0.05 ? ": the same PSNR at equal cost"
                                            : std::string(": checkerboard is ") + (d > 0 ? "better" : "worse") + " by " +
                                                  fmt(std::abs(d), 2) + " dB at equal cost";
                }
            } else if (e.cbr_ms < *e.drr_ms) {
                s += "cheaper than every drr scale swept (the cheapest, scale " + fmt(e.drr_scale, 3) + ", takes " +
                     fmtMs(*e.drr_ms) + " with PSNR " + fmtDb(e.drr_psnr) + " against " + fmtDb(e.cbr_psnr) +
                     "); no equal-cost drr scale in the range";
            } else {
                s += "dearer than every drr scale swept (the dearest, scale " + fmt(e.drr_scale, 3) + ", takes " +
                     fmtMs(*e.drr_ms) + " with PSNR " + fmtDb(e.drr_psnr) + " against " + fmtDb(e.cbr_psnr) +
                     "); at its cost drr renders at scale " + fmt(e.drr_scale, 3) + " or more";
            }
            e.verdict = s + ".";
            out.push_back(e);
        }
    }
    return out;
}

namespace {

std::string variantColour(const std::string& v) {
    if (v == "full") return "#404040";
    if (v == "drr") return "#e69f00";
    if (v == "cbr-aso") return "#0072b2";
    if (v == "cbr-cso") return "#009e73";
    return "#cc79a7";
}
const char* kCostColours[] = {"#009e73", "#0072b2", "#d55e00", "#cc79a7", "#e69f00", "#56b4e9", "#a08c00"};

std::string jsonString(const nlohmann::json& j, const char* ptr) {
    try {
        const auto& v = j.at(nlohmann::json::json_pointer(ptr));
        return v.is_string() ? v.get<std::string>() : v.dump();
    } catch (const std::exception&) {
        return "";
    }
}

struct Metric {
    const char* label;
    std::optional<double> SweepPoint::*field;
};
const Metric kMetrics[] = {{"GPU frame time, median (ms)", &SweepPoint::gpu_ms},
                           {"sequence PSNR (dB)", &SweepPoint::psnr_db},
                           {"SSIM", &SweepPoint::ssim},
                           {"edge crawl index ECI", &SweepPoint::eci}};

// Charts of each metric against one swept parameter, one series per shading cost;
// `flat` (cbr-aso for the tolerance) is drawn as a constant line for reference.
std::string paramCharts(const std::vector<SweepPoint>& points, const std::string& variant,
                        std::optional<double> SweepPoint::*param, const std::string& param_name, const char* flat) {
    std::set<double> xs_set;
    for (const auto& p : points)
        if (p.variant == variant && p.*param) xs_set.insert(*(p.*param));
    if (xs_set.size() < 2) return "";
    std::vector<double> xs(xs_set.begin(), xs_set.end());
    const bool log_x = xs.front() > 0 && xs.back() / xs.front() >= 20;
    std::vector<double> x_plot;
    for (double x : xs) x_plot.push_back(log_x ? std::log10(x) : x);
    const auto costs = shadingCosts(points);
    std::string out = "<h3>" + esc(variant) + " against " + esc(param_name) + "</h3>";
    std::vector<Series> legend;
    for (size_t k = 0; k < costs.size(); ++k) {
        std::string name = variant + (costs.size() > 1 ? " cost " + fmtShort(costs[k]) : "");
        legend.push_back({name, kCostColours[k % 7], {}});
        if (flat) legend.push_back({std::string(flat) + (costs.size() > 1 ? " cost " + fmtShort(costs[k]) : ""), "#888", {}});
    }
    out += legendHtml(legend, flat ? std::string(flat) + ": grey, flat (it has no such parameter)." : "");
    out += "<div class=\"grid2\">";
    for (const auto& m : kMetrics) {
        LineChart c;
        c.y_label = m.label;
        c.x_label = log_x ? "log10 " + param_name : param_name;
        c.x = x_plot;
        c.x_integer = false;
        for (size_t k = 0; k < costs.size(); ++k) {
            Series s{variant, kCostColours[k % 7], {}};
            if (costs.size() > 1) s.name += " cost " + fmtShort(costs[k]);
            for (double x : xs) {
                std::optional<double> y;
                for (const auto& p : points)
                    if (p.variant == variant && p.shading_cost == costs[k] && p.*param && *(p.*param) == x &&
                        p.status == "ok")
                        y = p.*(m.field);
                s.y.push_back(y);
            }
            c.series.push_back(s);
            if (flat)
                if (const auto* f = findVariant(points, flat, costs[k])) {
                    Series fs{std::string(flat) + (costs.size() > 1 ? " cost " + fmtShort(costs[k]) : ""), "#888", {}};
                    fs.y.assign(xs.size(), f->*(m.field));
                    c.series.push_back(fs);
                }
        }
        out += "<div class=\"chart-block\">" + lineChartSvg(c) + "</div>";
    }
    // Where the reconstruction's pixels come from, against the parameter (checkerboard only).
    if (variant == "cbr-cso")
        for (const char* cls : {"px_reused", "px_occluded"}) {
            LineChart c;
            c.y_label = std::string(cls) + " share";
            c.x_label = log_x ? "log10 " + param_name : param_name;
            c.x = x_plot;
            c.x_integer = false;
            for (size_t k = 0; k < costs.size(); ++k) {
                Series s{variant + (costs.size() > 1 ? " cost " + fmtShort(costs[k]) : ""), kCostColours[k % 7], {}};
                for (double x : xs) {
                    std::optional<double> y;
                    for (const auto& p : points)
                        if (p.variant == variant && p.shading_cost == costs[k] && p.*param && *(p.*param) == x &&
                            p.classes.count(cls))
                            y = p.classes.at(cls);
                    s.y.push_back(y);
                }
                c.series.push_back(s);
            }
            out += "<div class=\"chart-block\">" + lineChartSvg(c) + "</div>";
        }
    return out + "</div>";
}

}  // namespace

std::string sweepHtml(const std::filesystem::path& dir) {
    const SweepData d = loadSweep(dir);
    const auto choices = recommendTolerance(d.points);
    const auto equal = equalCost(d.points, choices);
    std::string where = jsonString(d.run, "/scene/name") + " / " + jsonString(d.run, "/path/name") + " at " +
                        jsonString(d.run, "/settings/width") + "\u00d7" + jsonString(d.run, "/settings/height");
    std::string pipeline;
    for (const auto& v : d.run.value("variants", nlohmann::json::array()))
        if (v.is_object() && v.contains("pipeline") && v["pipeline"].is_string()) pipeline = v["pipeline"];
    const std::string title = "cbrbench sweep: " + where + (pipeline.empty() ? "" : " (" + pipeline + ")");
    std::string html = pageStart(title);
    html += "<h1>" + esc(title) + "</h1><div class=\"sub\">" + esc(jsonString(d.run, "/device/name")) + " \u00b7 " +
            esc(jsonString(d.run, "/date")) + " \u00b7 commit " + esc(jsonString(d.run, "/tool/commit")) + " \u00b7 " +
            std::to_string(d.points.size()) + " configurations, interleaved in one process \u00b7 <a href=\"report.html\">"
            "the run's full report</a></div>";
    if (auto note = jsonString(d.run, "/device/timing_note"); !note.empty())
        html += "<p class=\"callout\"><b>Timing note:</b> " + esc(note) + "</p>";
    html += "<nav><a href=\"#answer\">answer</a><a href=\"#equal\">equal cost</a><a href=\"#plane\">error vs time</a>"
            "<a href=\"#params\">parameters</a><a href=\"#table\">configurations</a></nav>";
    html += "<section id=\"answer\">";
    if (choices.empty())
        html += "<p class=\"answer\"><b>CSO tolerance:</b> no cbr-cso configuration ran, so none is recommended.</p>";
    for (const auto& c : choices) html += "<p class=\"answer\"><b>Recommended:</b> " + esc(c.sentence) + "</p>";
    html += "<p class=\"note\">Rule: among the cbr-cso tolerances whose median GPU time stays within " +
            fmtShort(kCostMargin * 100) + "% of cbr-aso's at the same shading cost, those within 0.02 dB of the best "
            "sequence PSNR; of these the lowest edge crawl index (within 1e-4); of these the loosest tolerance: the "
            "edge of the quality plateau, before more reuse starts to cost quality.</p></section>";

    html += "<section id=\"equal\"><h2>Quality at equal cost: checkerboard against dynamic resolution</h2>";
    for (const auto& e : equal) html += "<p class=\"answer\">" + esc(e.verdict) + "</p>";
    if (!equal.empty()) {
        html += "<div class=\"scroll\"><table><tr><th>checkerboard</th><th class=\"num\">cost</th><th class=\"num\">GPU ms"
                "</th><th class=\"num\">PSNR dB</th><th class=\"num\">SSIM</th><th class=\"num\">ECI</th><th>drr at that "
                "cost</th><th class=\"num\">scale</th><th class=\"num\">GPU ms</th><th class=\"num\">PSNR dB</th>"
                "<th class=\"num\">SSIM</th><th class=\"num\">ECI</th></tr>";
        for (const auto& e : equal)
            html += "<tr><td>" + esc(e.config) + "</td><td class=\"num\">" + fmtShort(e.shading_cost) +
                    "</td><td class=\"num\">" + fmt(e.cbr_ms, 2) + "</td><td class=\"num\">" + fmt(e.cbr_psnr, 2) +
                    "</td><td class=\"num\">" + fmt(e.cbr_ssim, 4) + "</td><td class=\"num\">" + fmt(e.cbr_eci, 4) +
                    "</td><td>" + (e.matched ? "interpolated" : "nearest (no match)") + "</td><td class=\"num\">" +
                    fmt(e.drr_scale, 3) + "</td><td class=\"num\">" + fmt(e.drr_ms, 2) + "</td><td class=\"num\">" +
                    fmt(e.drr_psnr, 2) + "</td><td class=\"num\">" + fmt(e.drr_ssim, 4) + "</td><td class=\"num\">" +
                    fmt(e.drr_eci, 4) + "</td></tr>";
        html += "</table></div>";
    }
    html += "<p class=\"note\">The drr scale whose median GPU time equals the checkerboard configuration's, with its "
            "quality, interpolated linearly in time between the two swept drr scales around it (the drr times sorted). "
            "Without a drr scale on both sides the nearest is shown and no equal-cost claim is made.</p></section>";

    html += "<section id=\"plane\"><h2>Error against run time</h2>";
    for (double cost : shadingCosts(d.points)) {
        ScatterChart sc;
        sc.title = "PSNR against GPU time" + costSuffix(d.points, cost);
        sc.width = 560;
        sc.label_front_only = true;
        sc.lane_above = 50.0;  // drr at scale 1 is nearly the reference: on the lane, not squashing the rest
        sc.x_label = "GPU frame time, median (ms)";
        sc.y_label = "sequence PSNR (dB)";
        sc.y_higher_is_better = true;
        for (const auto& p : d.points)
            if (p.shading_cost == cost && p.status == "ok" && p.gpu_ms)
                sc.points.push_back({p.config, variantColour(p.variant), *p.gpu_ms, p.psnr_db});
        html += "<h3>Sequence PSNR against median GPU time" + esc(costSuffix(d.points, cost)) + "</h3>" +
                legendHtml({{"full", variantColour("full"), {}}, {"drr", variantColour("drr"), {}},
                            {"cbr-aso", variantColour("cbr-aso"), {}}, {"cbr-cso", variantColour("cbr-cso"), {}}}) +
                "<div class=\"chart-block\" style=\"max-width:900px\">" + scatterChartSvg(sc) + "</div>";
        std::vector<std::string> front;
        for (size_t i : paretoFront(sc.points, true)) front.push_back(sc.points[i].label);
        std::string list;
        for (const auto& f : front) list += (list.empty() ? "" : ", ") + f;
        html += "<p class=\"note\">Pareto front (no other configuration is both faster and better): " + esc(list) +
                ". Only the front is labelled (every point has a tooltip). Full's PSNR is infinite (it is the "
                "reference); it and anything above 50 dB sit on the lane above the plot.</p>";
    }
    html += "</section><section id=\"params\"><h2>Metrics against each parameter</h2>";
    html += paramCharts(d.points, "cbr-cso", &SweepPoint::cso_tolerance, "cso-tolerance", "cbr-aso");
    html += paramCharts(d.points, "drr", &SweepPoint::drr_scale, "drr-scale", nullptr);
    if (shadingCosts(d.points).size() > 1) {
        html += "<h3>GPU time against shading cost</h3><div class=\"grid2\">";
        LineChart c;
        c.y_label = "GPU frame time, median (ms)";
        c.x_label = "shading cost";
        c.x = shadingCosts(d.points);
        c.x_integer = false;
        std::vector<Series> legend;
        for (const char* v : {"full", "drr", "cbr-aso", "cbr-cso"}) {
            // The first configuration of each variant per cost (the swept values' first).
            Series s{v, variantColour(v), {}};
            for (double cost : c.x) {
                const SweepPoint* p = findVariant(d.points, v, cost);
                s.y.push_back(p ? p->gpu_ms : std::nullopt);
            }
            c.series.push_back(s);
            legend.push_back({v, variantColour(v), {}});
        }
        html += legendHtml(legend) + "<div class=\"chart-block\">" + lineChartSvg(c) + "</div></div>";
    }
    html += "</section><section id=\"table\"><h2>Configurations</h2><div class=\"scroll\"><table><tr>";
    const char* head[] = {"config", "status", "GPU ms", "95% CI", "speedup", "PSNR dB", "SSIM", "ECI", "reused %",
                          "occluded %"};
    for (const char* h : head) html += std::string("<th") + (h == head[0] || h == head[1] ? ">" : " class=\"num\">") + h + "</th>";
    html += "</tr>";
    for (const auto& p : d.points) {
        auto cls = [&](const char* k) {
            return p.classes.count(k) ? std::optional<double>(p.classes.at(k)) : std::nullopt;
        };
        html += "<tr><td class=\"variant\" style=\"color:" + variantColour(p.variant) + "\">" + esc(p.config) +
                "</td><td>" + esc(p.status) + "</td><td class=\"num\">" + fmt(p.gpu_ms, 2) + "</td><td class=\"num\">" +
                (p.gpu_ms_low ? fmt(p.gpu_ms_low, 2) + "\u2013" + fmt(p.gpu_ms_high, 2) : std::string(kDash)) +
                "</td><td class=\"num\">" + fmt(p.speedup, 2) + "</td><td class=\"num\">" + fmt(p.psnr_db, 2) +
                "</td><td class=\"num\">" + fmt(p.ssim, 4) + "</td><td class=\"num\">" + fmt(p.eci, 4) +
                "</td><td class=\"num\">" + fmtPct(cls("px_reused"), 1) + "</td><td class=\"num\">" +
                fmtPct(cls("px_occluded"), 1) + "</td></tr>";
    }
    html += "</table></div><p class=\"note\">From sweep.csv. GPU ms: median over all frames and repetitions; the "
            "interval is a 95% bootstrap interval of the median over repetitions. Speedup: paired per frame against the "
            "full configuration at the same shading cost.</p></section>";
    return html + pageEnd();
}

void writeSweepReport(const std::filesystem::path& dir) {
    const std::string html = sweepHtml(dir);
    writeTextAtomically(dir / "sweep.html", html);
}

}  // namespace cbr::reports
