// `cbrbench ab`'s outputs: ab.csv, ab.html (compare's page), ab.json, JUnit, the table.
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "harness/ab/ab_internal.h"
#include "harness/output/output_cells.h"
#include "harness/figures/stats.h"
#include "reports/compare_html.h"
#include "reports/csv.h"
#include "reports/junit.h"

namespace cbr::harness::ab {
namespace {

const std::vector<std::string> kAbColumns = {
    "variant",        "time_verdict",    "runs_a",          "runs_b",          "reps_a",
    "reps_b",         "unsteady_runs_a", "unsteady_runs_b", "decided_at_look", "a_gpu_ms",
    "b_gpu_ms",       "hl_change_pct",   "change_low_pct",  "change_high_pct", "interval_confidence_pct",
    "detectable_change_pct", "resolvable_change_pct", "runs_to_settle", "noise_cv_pct", "p_value",
    "q_value",        "alpha_per_look",  "psnr_delta_db",   "psnr_verdict",    "ssim_delta",
    "ssim_verdict",   "eci_change_pct",  "eci_verdict",     "note"};

// "A: ARGS | B: ARGS" (the binaries' file names where they differ), or "A/A" for twin sides.
std::string sidesText(const Plan& p) {
    auto side = [&](const char* name, const Side& s, const std::string& args) {
        std::string t = std::string(name) + ":";
        if (p.a.bin != p.b.bin) t += " " + s.bin.string();
        return t + (args.empty() ? "" : " " + args);
    };
    if (p.a.bin == p.b.bin && p.o.a_args == p.o.b_args) return "A/A: one binary, the same options";
    return side("A", p.a, p.o.a_args) + " | " + side("B", p.b, p.o.b_args);
}

reports::Cell opt(std::optional<double> v, double scale = 1) { return v ? reports::Cell(*v * scale) : reports::Cell(); }

std::optional<double> medianOf(const std::vector<double>& v) {
    if (v.empty()) return std::nullopt;
    return median(v);
}

// Runs per side likely to settle an undecided cell (judgeTimes counts samples).
std::optional<int> runsToSettle(const Plan& p, const CellSettle& c) {
    if (c.decided() || !c.time.reps_needed) return std::nullopt;
    const int per_run = p.unit == SampleUnit::Run ? 1 : p.o.repeat;
    return (*c.time.reps_needed + per_run - 1) / per_run;
}

// The note of a cell: unsteady runs left out, how an undecided one would settle, the SAME note.
std::string noteOf(const Plan& p, const CellSettle& c) {
    std::string note;
    if (c.unsteady_a + c.unsteady_b > 0)
        note = std::to_string(c.unsteady_a) + " / " + std::to_string(c.unsteady_b) +
               " unsteady runs (A / B) left out: an unsteady run is never SAME";
    std::string why = c.time.note;
    if (!c.decided() && c.at_runs == 0) {
        why = "budget spent before the first look (at " + std::to_string(p.looks.runs.front()) + " runs per side)";
    } else if (!c.decided()) {
        auto runs = runsToSettle(p, c);
        why = "budget spent undecided" + (runs ? ": about " + std::to_string(*runs) + " runs per side would likely settle it"
                                               : std::string(c.time.reps_needed ? "" : ": " + c.time.note));
    }
    if (!why.empty()) note += (note.empty() ? "" : "; ") + why;
    return note;
}

std::string abCsv(const Plan& p, const State& s) {
    reports::CsvTable csv(kAbColumns);
    for (size_t i = 0; i < s.variants.size(); ++i) {
        const CellSettle& c = s.settle[i];
        const TimeVerdict& t = c.time;
        const TimeSamples samples = samplesOf(s.cells[i], c.at_runs, p.unit);
        const auto& ci = t.interval;
        const bool b = ci && ci->bounded();
        const auto runs = runsToSettle(p, c);
        const CellQuality& q = s.quality[i];
        csv.addRow({{"variant", s.variants[i]}, {"time_verdict", t.verdict}, {"runs_a", c.runs_a}, {"runs_b", c.runs_b},
                    {"reps_a", c.reps_a}, {"reps_b", c.reps_b}, {"unsteady_runs_a", c.unsteady_a},
                    {"unsteady_runs_b", c.unsteady_b}, {"decided_at_look", c.look},
                    {"a_gpu_ms", opt(medianOf(samples.baseline))}, {"b_gpu_ms", opt(medianOf(samples.current))},
                    {"hl_change_pct", opt(ci ? std::optional(ci->estimate) : std::nullopt, 100)},
                    {"change_low_pct", opt(b ? std::optional(ci->low) : std::nullopt, 100)},
                    {"change_high_pct", opt(b ? std::optional(ci->high) : std::nullopt, 100)},
                    {"interval_confidence_pct", opt(b ? std::optional(ci->confidence) : std::nullopt, 100)},
                    {"detectable_change_pct", opt(t.detectable, 100)}, {"resolvable_change_pct", opt(t.resolution, 100)},
                    {"runs_to_settle", runs ? reports::Cell(*runs) : reports::Cell()},
                    {"noise_cv_pct", opt(t.noise, 100)}, {"p_value", opt(t.p)}, {"q_value", opt(t.q)},
                    {"alpha_per_look", p.looks.alpha_per_look}, {"psnr_delta_db", opt(q.psnr.delta)},
                    {"psnr_verdict", q.psnr.verdict}, {"ssim_delta", opt(q.ssim.delta)}, {"ssim_verdict", q.ssim.verdict},
                    {"eci_change_pct", opt(q.eci.delta, 100)}, {"eci_verdict", q.eci.verdict}, {"note", noteOf(p, c)}});
    }
    return csv.str();
}

std::string intervalText(const TimeVerdict& t) {
    if (!t.interval || !t.interval->bounded()) return "-";
    char b[64];
    std::snprintf(b, sizeof b, "[%+.1f%%, %+.1f%%] %.1f%%", t.interval->low * 100, t.interval->high * 100,
                  t.interval->confidence * 100);
    return b;
}

reports::ComparePage abPage(const Plan& p, const State& s, const std::string& outcome) {
    reports::ComparePage page{.command = "ab", .outcome = outcome, .baseline_dir = p.a.bin.string(),
                              .current_dir = p.b.bin.string(), .device = s.device, .threshold = p.threshold,
                              .alpha = p.o.alpha, .psnr_db = p.o.psnr_db, .ssim = p.o.ssim, .eci_threshold = p.eci,
                              .time_rule = kTimeRule, .settle_rule = kSettleRule, .rows = {}};
    char b[200];
    std::snprintf(b, sizeof b, "Exit code 1 for any SLOWER or WORSE cell, 3 when the budget (%d runs per side%s) was "
                  "spent with a cell UNKNOWN; alpha %.3g per look at %zu looks.", p.o.max_runs,
                  p.o.max_seconds > 0 ? (", " + std::to_string(int(p.o.max_seconds)) + " s").c_str() : "",
                  p.looks.alpha_per_look, p.looks.runs.size());
    page.exit_rule = b;
    for (size_t i = 0; i < s.variants.size(); ++i) {
        const CellSettle& c = s.settle[i];
        const TimeVerdict& t = c.time;
        const TimeSamples samples = samplesOf(s.cells[i], c.at_runs, p.unit);
        const CellQuality& q = s.quality[i];
        page.rows.push_back({.variant = s.variants[i], .context = sidesText(p),
                             .base_reps = size_t(c.reps_a), .cur_reps = size_t(c.reps_b),
                             .base_ms = medianOf(samples.baseline), .cur_ms = medianOf(samples.current),
                             .reps_text = std::to_string(c.runs_a) + " / " + std::to_string(c.runs_b) + " runs",
                             .change = t.interval ? std::optional(t.interval->estimate) : std::nullopt,
                             .detectable = t.detectable, .resolution = t.resolution, .noise = t.noise, .p = t.p,
                             .q = t.q, .interval = intervalText(t), .time_verdict = t.verdict,
                             .psnr_delta = q.psnr.delta, .ssim_delta = q.ssim.delta, .eci_change = q.eci.delta,
                             .psnr_verdict = q.psnr.verdict, .ssim_verdict = q.ssim.verdict,
                             .eci_verdict = q.eci.verdict, .note = noteOf(p, c)});
    }
    return page;
}

std::string abJunit(const Plan& p, const State& s) {
    reports::JUnitSuite suite{"cbrbench ab " + sidesText(p), {}};
    for (size_t i = 0; i < s.variants.size(); ++i) {
        const CellSettle& c = s.settle[i];
        const CellQuality& q = s.quality[i];
        reports::JUnitCase jc;
        jc.classname = "cbrbench.ab";
        jc.name = s.variants[i];
        const std::string evidence = c.time.verdict + " " + changeText(c.time) + " at " + std::to_string(c.runs_a) +
                                     " / " + std::to_string(c.runs_b) + " runs";
        jc.detail = "time " + evidence + "; PSNR " + q.psnr.verdict + ", SSIM " + q.ssim.verdict + ", ECI " +
                    q.eci.verdict + "; " + noteOf(p, c);
        const bool worse = q.psnr.verdict == "WORSE" || q.ssim.verdict == "WORSE" || q.eci.verdict == "WORSE";
        if (c.time.verdict == "SLOWER" || worse) {
            jc.failure_type = c.time.verdict == "SLOWER" ? "SLOWER" : "WORSE";
            jc.failure_message = c.time.verdict == "SLOWER" ? "SLOWER: frame time " + evidence : "quality WORSE";
        } else if (!c.decided()) {
            // Undecided fails the check (exit 3): a failure, not a skip, so CI shows it red.
            jc.failure_type = "UNDECIDED";
            jc.failure_message = "UNKNOWN when the budget was spent: " + evidence + "; " + noteOf(p, c);
        }
        suite.cases.push_back(std::move(jc));
    }
    return reports::junitXml("cbrbench ab", {suite}, isoDate());
}

void printTable(const Plan& p, const State& s) {
    std::printf("%-10s %-8s %9s %-30s %11s %8s %-7s %-7s %-7s\n", "variant", "time", "runs A/B", "change [interval]",
                "resolution", "noise", "psnr", "ssim", "eci");
    for (size_t i = 0; i < s.variants.size(); ++i) {
        const CellSettle& c = s.settle[i];
        char res[32] = "-", noise[32] = "-";
        if (c.time.resolution) std::snprintf(res, sizeof res, "+-%.2f%%", *c.time.resolution * 100);
        if (c.time.noise) std::snprintf(noise, sizeof noise, "%.1f%%", *c.time.noise * 100);
        const std::string runs = std::to_string(c.runs_a) + "/" + std::to_string(c.runs_b), note = noteOf(p, c);
        std::printf("%-10s %-8s %9s %-30s %11s %8s %-7s %-7s %-7s%s%s\n", s.variants[i].c_str(), c.time.verdict.c_str(),
                    runs.c_str(), changeText(c.time).c_str(), res, noise, s.quality[i].psnr.verdict.c_str(),
                    s.quality[i].ssim.verdict.c_str(), s.quality[i].eci.verdict.c_str(), note.empty() ? "" : "  ",
                    note.c_str());
    }
}

}  // namespace

std::string changeText(const TimeVerdict& t) {
    if (!t.interval) return "-";
    char b[64];
    std::snprintf(b, sizeof b, "%+.2f%% ", t.interval->estimate * 100);
    return b + intervalText(t);
}

int writeAbOutputs(const Plan& p, const State& s, const fs::path& dir) {
    bool regression = false, undecided = s.variants.empty();
    for (size_t i = 0; i < s.variants.size(); ++i) {
        const CellQuality& q = s.quality[i];
        regression |= s.settle[i].time.verdict == "SLOWER" || q.psnr.verdict == "WORSE" || q.ssim.verdict == "WORSE" ||
                      q.eci.verdict == "WORSE";
        undecided |= !s.settle[i].decided();
    }
    const int code = regression ? kAbRegression : undecided ? kAbUndecided : kAbSettled;
    const std::string outcome = regression ? "regression" : undecided ? "undecided: the budget was spent" : "settled";
    reports::writeTextAtomically(dir / "ab.csv", abCsv(p, s));
    reports::writeTextAtomically(dir / "ab.html", reports::compareHtml(abPage(p, s, outcome)));
    if (!p.o.junit.empty()) reports::writeTextAtomically(p.o.junit, abJunit(p, s));
    nlohmann::json j;
    j["command"] = "ab";
    j["argv"] = p.o.argv;
    j["sides"] = {{"a", {{"bin", p.a.bin.string()}, {"args", p.a.args}}}, {"b", {{"bin", p.b.bin.string()}, {"args", p.b.args}}}};
    j["device"] = s.device;
    j["threshold"] = p.threshold;
    j["alpha"] = p.o.alpha;
    j["alpha_per_look"] = p.looks.alpha_per_look;
    j["looks_planned_at_runs"] = p.looks.runs;
    j["looks_taken"] = s.looks_taken;
    j["unit"] = sampleUnitName(p.unit);
    j["repeat"] = p.o.repeat;
    j["budget"] = {{"max_runs", p.o.max_runs}, {"max_seconds", p.o.max_seconds}};
    j["runs_per_side"] = s.runs_per_side;
    j["runs"] = s.runs;
    j["seconds"] = s.seconds;
    j["stop"] = s.stop;
    j["outcome"] = outcome;
    j["exit_code"] = code;
    j["rule"] = kTimeRule;
    j["settle_rule"] = kSettleRule;
    reports::writeTextAtomically(dir / "ab.json", j.dump(2) + "\n");
    printTable(p, s);
    std::printf("ab: %s (%s) after %d runs per side, %.0f s (exit %d); %s, %s\n", outcome.c_str(), s.stop.c_str(),
                s.runs_per_side, s.seconds, code, (p.out / "ab.csv").c_str(), (p.out / "ab.html").c_str());
    return code;
}

}  // namespace cbr::harness::ab
