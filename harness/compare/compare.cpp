// `cbrbench compare`: per-cell time and quality verdicts between a baseline and a current run.
#include "harness/compare/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/figures/stats.h"
#include "harness/figures/verdict.h"
#include "reports/compare_html.h"
#include "reports/csv.h"
#include "reports/junit.h"
#include "reports/report_data.h"
#include "settings/table.h"
#include "rundir/files.h"
#include "rundir/pointer.h"
#include "rundir/run_json.h"
#include "rundir/setting_columns.h"
#include "rundir/summary_csv.h"

namespace cbr::harness {

namespace {

namespace fs = std::filesystem;
using reports::RunData;

// The settings in run.json that change timings or images: part of a cell's key.
// (debug_slowdown is left out on purpose: it is how a detector test makes a known regression.)
// The settings table's rows that say so, in their order.
const std::vector<std::string> kKeySettings = [] {
    std::vector<std::string> key;
    for (const settings::Row* row : settings::compareKey()) key.emplace_back(row->column);
    return key;
}();

struct Side {
    RunData data;
    std::string context;  // scene#hash|path#hash|pipeline|WxH|settings
    std::string scene, path, pipeline, resolution, settings;
    std::vector<std::string> key_values;  // per kKeySettings; empty where the run.json predates it
};

struct Cell {
    std::string variant;
    const Side* base = nullptr;
    const Side* cur = nullptr;
    std::vector<double> base_reps, cur_reps;  // per-repetition median gpu_ms
    std::optional<double> base_ms, cur_ms;
    TimeVerdict time;
    std::string note;  // unmatched cells
    using Quality = QualityVerdict;
    Quality psnr, ssim, eci;
    Quality jod;  // ColorVideoVDP (summary.csv cvvdp_jod); n/a where a side predates it
};


namespace rj = rundir::run;

// run.json's value at the schema's keys as text ("" where absent; numbers as JSON writes them).
template <typename... Keys>
std::string jsonString(const nlohmann::json& run, const Keys&... keys) {
    const nlohmann::json* j = reports::jsonAt(run, rundir::pointer(keys...));
    if (!j || j->is_null()) return "";
    if (j->is_string()) return j->get<std::string>();
    return j->dump();
}

Side loadSide(const std::string& dir, const std::string& role) {
    if (!fs::is_directory(dir))
        throw std::invalid_argument("compare: " + role + " " + dir + ": not a directory; expected a run's output directory");
    Side s;
    try {
        s.data = reports::loadRun(dir);
    } catch (const nlohmann::json::exception& e) {
        throw std::invalid_argument("compare: " + role + " " + (fs::path(dir) / rundir::kRunJson).string() + ": " + e.what());
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("compare: " + role + " " + e.what());
    }
    const auto& run = s.data.run;
    s.scene = jsonString(run, rj::kScene, rj::scene::kName) + "#" + jsonString(run, rj::kScene, rj::scene::kHash);
    s.path = jsonString(run, rj::kPath, rj::path::kName) + "#" + jsonString(run, rj::kPath, rj::path::kHash);
    s.pipeline = jsonString(run, rj::kSettings, rj::settings::kPipeline);
    if (s.pipeline.empty()) s.pipeline = "forward";
    s.resolution =
        jsonString(run, rj::kSettings, rj::settings::kWidth) + "x" + jsonString(run, rj::kSettings, rj::settings::kHeight);
    if (s.resolution == "x")
        throw std::invalid_argument("compare: " + role + " " + (fs::path(dir) / rundir::kRunJson).string() +
                                    ": /settings/width and /settings/height missing; expected a cbrbench run.json");
    for (const auto& k : kKeySettings) {
        std::string v = jsonString(run, rj::kSettings, k);
        // Older runs record the reference only under metrics.
        if (v.empty() && k == rundir::settingColumn("reference")) v = jsonString(run, rj::kMetrics, rj::metrics::kReferenceKind);
        s.key_values.push_back(v);
    }
    return s;
}

// The cells' key from the settings both runs record: a setting added to run.json after the
// baseline was made (cbr_history, taau_*) does not split every cell of an older baseline
// from the current run. A setting only one of them records is left out of the key (so a
// current run with a non-default value of it meets an older baseline's cell all the same).
void keySides(Side& a, Side& b) {
    for (Side* s : {&a, &b}) {
        s->settings.clear();
        for (size_t i = 0; i < kKeySettings.size(); ++i) {
            if (a.key_values[i].empty() != b.key_values[i].empty()) continue;
            s->settings += (s->settings.empty() ? "" : ";") + kKeySettings[i] + "=" + s->key_values[i];
        }
        s->context = s->scene + "|" + s->path + "|" + s->pipeline + "|" + s->resolution + "|" + s->settings;
    }
}

std::string num(std::optional<double> v) { return v ? reports::Cell(*v).text() : std::string(); }

const std::vector<std::string> kCsvColumns = {
    "scene",          "path",           "pipeline",      "variant",      "resolution",    "settings",
    "baseline_reps",  "current_reps",   "baseline_gpu_ms", "current_gpu_ms", "time_change_pct", "hl_change_pct",
    "change_low_pct", "change_high_pct", "interval_confidence_pct", "detectable_change_pct", "resolvable_change_pct", "reps_to_settle",
    "noise_cv_pct",   "p_value",        "q_value",        "time_verdict",  "baseline_psnr_db", "current_psnr_db", "psnr_delta_db",
    "psnr_verdict",   "baseline_ssim",  "current_ssim",  "ssim_delta",   "ssim_verdict",  "baseline_eci",
    "current_eci",    "eci_change_pct", "eci_verdict",   "baseline_cvvdp_jod", "current_cvvdp_jod", "jod_delta",
    "jod_verdict",    "note"};

// Some cell has JODs on both sides: the table, the page and the JUnit detail show them (a
// comparison of runs from before ColorVideoVDP reads as it did).
bool anyJod(const std::vector<Cell>& cells) {
    return std::any_of(cells.begin(), cells.end(), [](const Cell& c) { return c.jod.verdict != "n/a"; });
}

std::optional<double> pct(std::optional<double> fraction) {
    if (!fraction) return std::nullopt;
    return *fraction * 100.0;
}

const Side& sideOf(const Cell& c) { return c.cur ? *c.cur : *c.base; }

// "[+1.2%, +4.5%] 90%" (the estimate is in the CSV), or a dash without a bounded interval.
std::string intervalText(const TimeVerdict& t) {
    if (!t.interval || !t.interval->bounded()) return "-";
    char b[64];
    std::snprintf(b, sizeof b, "[%+.1f%%, %+.1f%%] %.0f%%", t.interval->low * 100, t.interval->high * 100,
                  t.interval->confidence * 100);
    return b;
}

std::string noteOf(const Cell& c) { return c.note.empty() ? c.time.note : c.note; }

// The page's data (reports/compare_html.h): the thresholds as judged and one row per cell.
reports::ComparePage comparePage(const CompareOptions& o, const Side& base, const Side& cur,
                                 const std::vector<Cell>& cells, double threshold, double eci_threshold,
                                 const std::string& outcome) {
    reports::ComparePage page{.outcome = outcome, .baseline_dir = base.data.dir.string(),
                              .current_dir = cur.data.dir.string(), .device = reports::deviceText(cur.data),
                              .threshold = threshold, .alpha = o.alpha, .psnr_db = o.psnr_db, .ssim = o.ssim,
                              .eci_threshold = eci_threshold, .jod = o.jod, .time_rule = kTimeRule};
    page.exit_rule = "Exit code 1 for any SLOWER or WORSE cell; 2 when no cell was decided (or, with --strict, any "
                     "cell is UNKNOWN).";
    for (const auto& c : cells) {
        const TimeVerdict& t = c.time;
        page.rows.push_back({.variant = c.variant, .context = sideOf(c).context, .base_reps = c.base_reps.size(),
                             .cur_reps = c.cur_reps.size(), .base_ms = c.base_ms, .cur_ms = c.cur_ms,
                             .change = t.change, .detectable = t.detectable, .resolution = t.resolution,
                             .noise = t.noise, .p = t.p, .q = t.q, .interval = intervalText(t),
                             .time_verdict = t.verdict, .psnr_delta = c.psnr.delta, .ssim_delta = c.ssim.delta,
                             .eci_change = c.eci.delta, .psnr_verdict = c.psnr.verdict,
                             .ssim_verdict = c.ssim.verdict, .eci_verdict = c.eci.verdict,
                             .jod_delta = c.jod.delta, .jod_verdict = c.jod.verdict, .note = noteOf(c)});
    }
    return page;
}

// "+5.2% [+3.1%, +7.4%] 90%, q 0.012": a time verdict's evidence in one line.
std::string timeEvidence(const TimeVerdict& t) {
    char b[96];
    std::string s = t.change ? (std::snprintf(b, sizeof b, "%+.2f%%", *t.change * 100), std::string(b)) : "no change";
    if (t.interval && t.interval->bounded()) s += " " + intervalText(t);
    if (t.q) s += (std::snprintf(b, sizeof b, ", q %.3g", *t.q), std::string(b));
    return s;
}

// One JUnit testcase per cell, one suite per context (scene, path, pipeline, resolution,
// settings): SLOWER and WORSE as the failure, UNKNOWN and unmatched cells as skipped.
std::string compareJunit(const std::vector<Cell>& cells, double threshold, const std::string& timestamp) {
    std::vector<reports::JUnitSuite> suites;
    char b[160];
    for (const auto& c : cells) {
        const Side& s = sideOf(c);
        const std::string suite = s.scene + " " + s.path + " " + s.pipeline + " " + s.resolution +
                                  (s.settings.empty() ? "" : " " + s.settings);
        auto it = std::find_if(suites.begin(), suites.end(), [&](const auto& x) { return x.name == suite; });
        if (it == suites.end()) it = suites.insert(suites.end(), {suite, {}});
        reports::JUnitCase jc;
        jc.classname = "cbrbench.compare." + s.pipeline + "." + s.resolution;
        jc.name = c.variant + (c.base && c.cur ? "" : c.base ? " (baseline only)" : " (current only)");
        const TimeVerdict& t = c.time;
        std::vector<std::string> failed;
        if (t.verdict == "SLOWER")
            failed.push_back("SLOWER: frame time " + timeEvidence(t) + " beyond +" +
                             (std::snprintf(b, sizeof b, "%g", threshold * 100), std::string(b)) + "%");
        auto quality = [&](const char* what, const Cell::Quality& q, const char* spec) {
            if (q.verdict != "WORSE") return;
            std::snprintf(b, sizeof b, spec, *q.base, *q.cur);
            failed.push_back(std::string(what) + " WORSE: " + b);
        };
        quality("PSNR", c.psnr, "%.3f -> %.3f dB");
        quality("SSIM", c.ssim, "%.5f -> %.5f");
        quality("ECI", c.eci, "%.5f -> %.5f");
        if (c.jod.verdict == "WORSE")
            failed.push_back("JOD WORSE: " + reports::jodText(c.jod.base, "-") + " -> " + reports::jodText(c.jod.cur, "-"));
        std::snprintf(b, sizeof b, "baseline %s ms (%zu reps), current %s ms (%zu reps)", num(c.base_ms).c_str(),
                      c.base_reps.size(), num(c.cur_ms).c_str(), c.cur_reps.size());
        jc.detail = std::string(b) + "; time " + t.verdict + " " + timeEvidence(t) + "; PSNR " + c.psnr.verdict +
                    ", SSIM " + c.ssim.verdict + ", ECI " + c.eci.verdict +
                    (c.jod.verdict == "n/a" ? "" : ", JOD " + c.jod.verdict);
        if (!noteOf(c).empty()) jc.detail += "; " + noteOf(c);
        if (!failed.empty()) {
            jc.failure_type = t.verdict == "SLOWER" ? "SLOWER" : "WORSE";
            for (const auto& f : failed) jc.failure_message += (jc.failure_message.empty() ? "" : "; ") + f;
        } else if (!c.base || !c.cur) {
            jc.skipped = "not compared: " + noteOf(c);
        } else if (t.verdict == "UNKNOWN") {
            jc.skipped = "UNKNOWN: frame time " + timeEvidence(t) + " straddles a boundary of +-" +
                         (std::snprintf(b, sizeof b, "%g", threshold * 100), std::string(b)) + "%";
            if (t.reps_needed) jc.skipped = *jc.skipped + "; about " + std::to_string(*t.reps_needed) +
                                            " repetitions per side would likely settle it";
        }
        it->cases.push_back(std::move(jc));
    }
    return reports::junitXml("cbrbench compare", suites, timestamp);
}

// compare.csv: one row per cell (kCsvColumns).
std::string compareCsv(const std::vector<Cell>& cells) {
    reports::CsvTable csv(kCsvColumns);
    for (const auto& c : cells) {
        const Side& s = sideOf(c);
        const TimeVerdict& t = c.time;
        const auto& ci = t.interval;
        const bool bounded = ci && ci->bounded();
        csv.addRow({{"scene", s.scene},
                    {"path", s.path},
                    {"pipeline", s.pipeline},
                    {"variant", c.variant},
                    {"resolution", s.resolution},
                    {"settings", s.settings},
                    {"baseline_reps", int(c.base_reps.size())},
                    {"current_reps", int(c.cur_reps.size())},
                    {"baseline_gpu_ms", num(c.base_ms)},
                    {"current_gpu_ms", num(c.cur_ms)},
                    {"time_change_pct", num(pct(t.change))},
                    {"hl_change_pct", num(pct(ci ? std::optional(ci->estimate) : std::nullopt))},
                    {"change_low_pct", num(pct(bounded ? std::optional(ci->low) : std::nullopt))},
                    {"change_high_pct", num(pct(bounded ? std::optional(ci->high) : std::nullopt))},
                    {"interval_confidence_pct", num(pct(bounded ? std::optional(ci->confidence) : std::nullopt))},
                    {"detectable_change_pct", num(pct(t.detectable))},
                    {"resolvable_change_pct", num(pct(t.resolution))},
                    {"reps_to_settle", t.reps_needed ? std::to_string(*t.reps_needed) : std::string()},
                    {"noise_cv_pct", num(pct(t.noise))},
                    {"p_value", num(t.p)},
                    {"q_value", num(t.q)},
                    {"time_verdict", t.verdict},
                    {"baseline_psnr_db", num(c.psnr.base)},
                    {"current_psnr_db", num(c.psnr.cur)},
                    {"psnr_delta_db", num(c.psnr.delta)},
                    {"psnr_verdict", c.psnr.verdict},
                    {"baseline_ssim", num(c.ssim.base)},
                    {"current_ssim", num(c.ssim.cur)},
                    {"ssim_delta", num(c.ssim.delta)},
                    {"ssim_verdict", c.ssim.verdict},
                    {"baseline_eci", num(c.eci.base)},
                    {"current_eci", num(c.eci.cur)},
                    {"eci_change_pct", num(pct(c.eci.delta))},
                    {"eci_verdict", c.eci.verdict},
                    {"baseline_cvvdp_jod", num(c.jod.base)},
                    {"current_cvvdp_jod", num(c.jod.cur)},
                    {"jod_delta", num(c.jod.delta)},
                    {"jod_verdict", c.jod.verdict},
                    {"note", noteOf(c)}});
    }
    return csv.str();
}

// The short table on stdout: a line per cell.
void printCompareTable(const std::vector<Cell>& cells) {
    const bool jod = anyJod(cells);  // the jod column only beside runs that scored it
    std::printf("%-10s %6s %10s %10s %8s %-22s %7s %7s %-8s %-7s %-7s %-7s%s\n", "variant", "reps", "base_ms", "cur_ms",
                "change", "interval", "noise", "q", "time", "psnr", "ssim", "eci", jod ? " jod    " : "");
    for (const auto& c : cells) {
        auto p2 = [](std::optional<double> v) {
            char b[32];
            if (!v) return std::string("-");
            std::snprintf(b, sizeof b, "%+.1f%%", *v * 100);
            return std::string(b);
        };
        auto f = [](std::optional<double> v, const char* spec) {
            char b[32];
            if (!v) return std::string("-");
            std::snprintf(b, sizeof b, spec, *v);
            return std::string(b);
        };
        std::string reps = std::to_string(c.base_reps.size()) + "/" + std::to_string(c.cur_reps.size());
        const TimeVerdict& t = c.time;
        const std::string note = noteOf(c);
        char jod_cell[16] = "";
        if (jod) std::snprintf(jod_cell, sizeof jod_cell, " %-7s", c.jod.verdict.c_str());
        std::printf("%-10s %6s %10s %10s %8s %-22s %7s %7s %-8s %-7s %-7s %-7s%s%s%s\n", c.variant.c_str(), reps.c_str(),
                    f(c.base_ms, "%.4f").c_str(), f(c.cur_ms, "%.4f").c_str(), p2(t.change).c_str(),
                    intervalText(t).c_str(), f(pct(t.noise), "%.1f%%").c_str(), f(t.q, "%.3f").c_str(),
                    t.verdict.c_str(), c.psnr.verdict.c_str(), c.ssim.verdict.c_str(), c.eci.verdict.c_str(), jod_cell,
                    note.empty() ? "" : "  ", note.c_str());
    }
}

// Writes compare.csv and compare.html into the current run's directory and prints a
// short table; returns the exit code.
int writeCompare(const CompareOptions& o, const Side& base, const Side& cur, const std::vector<Cell>& cells,
                 double threshold, double eci_threshold) {
    bool regression = false, unknown = false, matched = false, decided = false;
    for (const auto& c : cells) {
        regression |= c.time.verdict == "SLOWER" || c.psnr.verdict == "WORSE" || c.ssim.verdict == "WORSE" ||
                      c.eci.verdict == "WORSE" || c.jod.verdict == "WORSE";
        unknown |= c.time.verdict == "UNKNOWN";
        matched |= c.base && c.cur;
        decided |= c.base && c.cur && c.time.verdict != "UNKNOWN";
    }
    // A check that decided nothing does not pass: no cell with a time verdict is inconclusive
    // with or without --strict.
    int code = regression                        ? kCompareRegression
               : (unknown && o.strict) || !decided ? kCompareInconclusive
                                                   : kCompareSame;
    std::string outcome = regression ? "regression"
                          : !decided ? "inconclusive: no cell decided (every time verdict UNKNOWN or unmatched)"
                          : unknown  ? "no regression found, some cells UNKNOWN"
                                     : "no regression";

    fs::path out = o.current_dir;
    reports::writeTextAtomically(out / "compare.csv", compareCsv(cells));
    reports::writeTextAtomically(out / "compare.html",
                                 reports::compareHtml(comparePage(o, base, cur, cells, threshold, eci_threshold, outcome)));
    if (!o.junit.empty())
        reports::writeTextAtomically(o.junit, compareJunit(cells, threshold, jsonString(cur.data.run, rj::kDate)));

    if (!matched)
        std::fprintf(stderr, "cbrbench: compare: no cell matches (scene, path, pipeline, resolution or settings differ)\n");
    printCompareTable(cells);
    std::printf("compare: %s (exit %d); %s, %s\n", outcome.c_str(), code, (out / "compare.csv").c_str(),
                (out / "compare.html").c_str());
    return code;
}

// The thresholds' and --junit's checks (the fractions are parsed where they are used).
void checkCompareOptions(const CompareOptions& o) {
    if (!(o.alpha > 0 && o.alpha < 1))
        throw std::invalid_argument("compare: --alpha " + std::to_string(o.alpha) + ": accepted: 0 < alpha < 1");
    if (!(o.psnr_db >= 0) || !(o.ssim >= 0) || !(o.jod >= 0))
        throw std::invalid_argument("compare: --psnr-threshold, --ssim-threshold and --jod-threshold must be >= 0");
    if (!o.junit.empty()) {
        fs::path dir = fs::absolute(o.junit).parent_path();
        if (!fs::is_directory(dir) || fs::is_directory(o.junit))
            throw std::invalid_argument("compare: --junit " + o.junit +
                                        ": accepted: a file path in an existing directory");
    }
}

// Cells: baseline variants in order, then those only the current run has; the quality
// verdicts judged (the time verdicts are judged together afterwards).
std::vector<Cell> compareCells(const CompareOptions& o, const Side& base, const Side& cur, double eci_threshold) {
    std::vector<Cell> cells;
    std::vector<std::string> names = base.data.variants;
    for (const auto& v : cur.data.variants)
        if (std::find(names.begin(), names.end(), v) == names.end()) names.push_back(v);
    const bool same_context = base.context == cur.context;
    for (const auto& v : names) {
        bool in_base = std::find(base.data.variants.begin(), base.data.variants.end(), v) != base.data.variants.end();
        bool in_cur = std::find(cur.data.variants.begin(), cur.data.variants.end(), v) != cur.data.variants.end();
        // Different settings make different cells: each side then stands alone, unmatched.
        std::vector<std::pair<const Side*, const Side*>> pairs;
        if (same_context && in_base && in_cur) pairs.push_back({&base, &cur});
        else {
            if (in_base) pairs.push_back({&base, nullptr});
            if (in_cur) pairs.push_back({nullptr, &cur});
        }
        for (auto [b, c] : pairs) {
            Cell cell;
            cell.variant = v;
            cell.base = b;
            cell.cur = c;
            if (!b || !c) {
                cell.note = b ? "only in baseline" : "only in current";
                cells.push_back(cell);
                continue;
            }
            cell.base_reps = repetitionMedians(b->data, v);
            cell.cur_reps = repetitionMedians(c->data, v);
            if (!cell.base_reps.empty()) cell.base_ms = median(cell.base_reps);
            if (!cell.cur_reps.empty()) cell.cur_ms = median(cell.cur_reps);
            auto quality = [&, base_side = b, cur_side = c](Cell::Quality& q, const char* column) {
                q.base = reports::summaryNum(base_side->data, v, column);
                q.cur = reports::summaryNum(cur_side->data, v, column);
            };
            quality(cell.psnr, rundir::summary::kPsnrDbMean);
            quality(cell.ssim, rundir::summary::kSsimMean);
            quality(cell.eci, rundir::summary::kEci);
            quality(cell.jod, rundir::summary::kCvvdpJod);
            judgeQuality(cell.psnr, true, o.psnr_db, false);
            judgeQuality(cell.ssim, true, o.ssim, false);
            judgeQuality(cell.eci, false, eci_threshold, true);
            judgeQuality(cell.jod, true, o.jod, false);  // a drop beyond --jod-threshold is WORSE
            cells.push_back(cell);
        }
    }
    return cells;
}

// A run whose timed frames drifted (summary.csv status `unsteady`) cannot show that nothing
// changed: such a cell's SAME becomes UNKNOWN, saying which side and what drifted.
void neverSameIfUnsteady(Cell& c) {
    std::string why;
    for (auto [side, role] : {std::pair{c.base, "baseline"}, std::pair{c.cur, "current"}}) {
        if (reports::summaryText(side->data, c.variant, rundir::summary::kStatus) != kUnsteadyStatus) continue;
        const std::string note = reports::summaryText(side->data, c.variant, rundir::summary::kNote);
        why += std::string(why.empty() ? "" : "; ") + role + " unsteady" + (note.empty() ? "" : " (" + note + ")");
    }
    if (why.empty()) return;
    if (c.time.verdict == "SAME") c.time.verdict = "UNKNOWN";
    c.time.note = why + "; an unsteady run is never SAME" + (c.time.note.empty() ? "" : "; " + c.time.note);
}

}  // namespace

int runCompare(const CompareOptions& o) {
    double threshold = 0, eci_threshold = 0;
    Side base, cur;
    try {
        threshold = parseFraction(o.threshold, "compare", "--threshold");
        eci_threshold = parseFraction(o.eci, "compare", "--eci-threshold");
        checkCompareOptions(o);
        base = loadSide(o.baseline_dir, "baseline");
        cur = loadSide(o.current_dir, "current");
        keySides(base, cur);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "cbrbench: %s\n", e.what());
        return kCompareBadInput;
    }
    // Different devices or drivers are never a regression: refuse, naming both.
    if (reports::deviceText(base.data) != reports::deviceText(cur.data)) {
        std::fprintf(stderr,
                     "cbrbench: compare: refusing to compare different devices or drivers: baseline %s, current %s\n",
                     reports::deviceText(base.data).c_str(), reports::deviceText(cur.data).c_str());
        return kCompareBadInput;
    }

    std::vector<Cell> cells = compareCells(o, base, cur, eci_threshold);

    // Time verdicts of the matched cells, judged together (Benjamini-Hochberg across them).
    std::vector<TimeSamples> samples;
    std::vector<Cell*> matched;
    for (auto& c : cells)
        if (c.base && c.cur) samples.push_back({c.base_reps, c.cur_reps}), matched.push_back(&c);
    auto verdicts = judgeTimes(samples, {threshold, o.alpha});
    for (size_t i = 0; i < matched.size(); ++i) matched[i]->time = verdicts[i], neverSameIfUnsteady(*matched[i]);
    return writeCompare(o, base, cur, cells, threshold, eci_threshold);
}

}  // namespace cbr::harness
