// A/A pairs and injected slowdowns through compare's verdict rule: false-alarm and
// detection rates per repetition count, with intervals.
#include "harness/calibrate/calibrate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/calibrate/calibrate_settle.h"
#include "harness/base/progress.h"
#include "harness/run/run.h"
#include "harness/figures/settle.h"
#include "harness/figures/stats.h"
#include "harness/figures/verdict.h"
#include "reports/csv.h"
#include "reports/output_dir.h"
#include "reports/report_data.h"

namespace cbr::harness {
namespace {

namespace fs = std::filesystem;

struct Plan {
    CalibrateOptions o;
    std::vector<Slowdown> slowdowns;
    std::vector<int> repeats;  // ascending
    VerdictRule rule;
    fs::path out;
};

int parseCount(const std::string& text, const std::string& what) {
    size_t used = 0;
    int v = 0;
    try {
        v = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || v < 1)
        throw std::invalid_argument("calibrate: " + what + " '" + text + "': expected a positive integer");
    return v;
}

Plan plan(const CalibrateOptions& o) {
    Plan p;
    p.o = o;
    if (o.pairs < 1 || o.slow_pairs < 0)
        throw std::invalid_argument("calibrate: --pairs must be >= 1 and --slow-pairs >= 0");
    for (const auto& r : splitList(o.repeats)) p.repeats.push_back(parseCount(r, "--repeats"));
    std::sort(p.repeats.begin(), p.repeats.end());
    p.repeats.erase(std::unique(p.repeats.begin(), p.repeats.end()), p.repeats.end());
    if (p.repeats.empty() || p.repeats.front() < 3)
        throw std::invalid_argument("calibrate: --repeats '" + o.repeats + "': expected counts >= 3 (a verdict needs 3)");
    size_t eq = o.slowdowns.find('=');
    if (!o.slowdowns.empty()) {
        if (eq == std::string::npos || eq == 0)
            throw std::invalid_argument("calibrate: --slowdown '" + o.slowdowns + "': expected PASS=PCT[,PCT...], e.g. opaque=3,10");
        for (const auto& pct : splitList(o.slowdowns.substr(eq + 1))) {
            double v = parseFraction(pct + (pct.empty() || pct.back() == '%' ? "" : "%"), "calibrate", "--slowdown") * 100;
            if (!(v > 0)) throw std::invalid_argument("calibrate: --slowdown " + pct + ": expected a percentage > 0");
            p.slowdowns.push_back({o.slowdowns.substr(0, eq), v});
        }
    }
    p.rule.threshold = parseFraction(o.threshold, "calibrate", "--threshold");
    p.rule.alpha = o.alpha;
    if (!(o.alpha > 0 && o.alpha < 1)) throw std::invalid_argument("calibrate: --alpha: expected 0 < alpha < 1");
    const auto& r = o.run;
    p.out = o.out.empty() ? fs::path("out") / ("calibrate-" + specStem(r.scene) + "-" + specStem(r.path) + "-" +
                                                timestampForName())
                          : fs::path(o.out);
    if (fs::exists(p.out)) throw std::invalid_argument("--out " + p.out.string() + ": already exists; expected a new directory");
    if (o.settle && !o.from.empty()) throw std::invalid_argument("calibrate: --settle and --from: accepted: one of them");
    if (o.settle && planLooks(o.max_runs, 2, p.repeats.front(), SampleUnit::Run, o.alpha).runs.empty())
        throw std::invalid_argument("calibrate: --max-runs " + std::to_string(o.max_runs) +
                                    ": too few runs per side for any settled verdict; accepted: an even count >= 4");
    if (o.settle && (o.max_runs % 2 != 0))
        throw std::invalid_argument("calibrate: --max-runs " + std::to_string(o.max_runs) + ": accepted: an even count >= 4");
    if (!o.from.empty()) return p;  // judged from existing runs: nothing renders
    // The runs' own checks (scene, path, settings, and the slowdown's pass) before any output.
    RunOptions check = r;
    check.repeat = p.repeats.back();
    check.out = (p.out / "check").string();
    if (!p.slowdowns.empty()) check.debug_slowdown = p.slowdowns.front();
    checkRunOptions(check);
    return p;
}

struct PairVerdicts {
    std::string kind;  // aa or the slowdown's spec
    int pair = 0;
    int repeats = 0;
    std::vector<std::string> variants;
    std::vector<TimeVerdict> verdicts;
    bool slower() const {  // compare's exit 1 from time alone (the images are the same)
        for (const auto& v : verdicts)
            if (v.verdict == "SLOWER") return true;
        return false;
    }
};

PairVerdicts judgePair(const reports::RunData& base, const reports::RunData& cur, const std::string& kind, int pair,
                       int repeats, const VerdictRule& rule) {
    PairVerdicts out{kind, pair, repeats, base.variants, {}};
    std::vector<TimeSamples> cells;
    for (const auto& v : base.variants) cells.push_back({repetitionMedians(base, v, repeats), repetitionMedians(cur, v, repeats)});
    out.verdicts = judgeTimes(cells, rule);
    return out;
}

reports::RunData runOnce(const Plan& p, const std::string& name, const Slowdown& slowdown) {
    RunOptions r = p.o.run;
    r.repeat = p.repeats.back();
    r.debug_slowdown = slowdown;
    r.control.silent = true;
    r.control.sweep = false;
    r.out = (p.out / "runs" / name).string();
    std::printf("calibrate: %s%s\n", name.c_str(), slowdown.empty() ? "" : (" (" + slowdown.spec() + ")").c_str());
    std::fflush(stdout);
    int code = runBenchmark(r);
    if (code != 0) throw std::runtime_error("calibrate: run " + name + " exited " + std::to_string(code));
    return reports::loadRun(p.out / "runs" / name);
}

// A slowdown of a pass no variant runs would measure nothing: refused after the first run
// (the output directory is removed with the exception).
void checkSlowdownPasses(const Plan& p, const reports::RunData& base) {
    std::set<std::string> ran;
    if (const auto* variants = reports::jsonAt(base.run, "/variants"); variants && variants->is_array())
        for (const auto& v : *variants)
            if (v.contains("passes") && v["passes"].is_array())
                for (const auto& pass : v["passes"])
                    if (pass.contains("name") && pass["name"].is_string()) ran.insert(pass["name"].get<std::string>());
    for (const auto& s : p.slowdowns)
        if (!ran.count(s.pass)) {
            std::string names;
            for (const auto& n : ran) names += (names.empty() ? "" : ", ") + n;
            throw std::invalid_argument("calibrate: --slowdown " + s.spec() + ": no variant runs a pass '" + s.pass +
                                        "'; passes of these variants: " + names);
        }
}

const std::vector<std::string> kRateColumns = {
    "kind", "injected_pct", "repeats", "pairs", "exit1_pairs", "rate", "rate_low", "rate_high",
    "median_change_pct", "median_detectable_pct", "median_noise_cv_pct", "unknown_cells", "same_cells"};
const std::vector<std::string> kPairColumns = {"kind", "injected_pct", "pair", "repeats", "variant", "verdict",
                                               "change_pct", "hl_change_pct", "change_low_pct", "change_high_pct",
                                               "noise_cv_pct", "q_value"};

// Every pair judged at every count: kind -> repeats -> pairs.
struct Judged {
    std::map<std::string, std::map<int, std::vector<PairVerdicts>>> by_kind;
    std::map<std::string, double> injected = {{"aa", 0.0}};
    std::string device, setup;  // from the first baseline's run.json
    void add(const reports::RunData& base, const reports::RunData& cur, const std::string& kind, int pair,
             const Plan& p) {
        for (int r : p.repeats) by_kind[kind][r].push_back(judgePair(base, cur, kind, pair, r, p.rule));
    }
    void describe(const reports::RunData& base) {
        auto text = [&](const char* ptr) {
            const auto* j = reports::jsonAt(base.run, ptr);
            return !j ? std::string() : j->is_string() ? j->get<std::string>() : j->dump();
        };
        device = text("/device/name");
        setup = text("/settings/width") + "x" + text("/settings/height") + " " + text("/scene/name") + " " +
                text("/path/name") + ", " + text("/settings/frames") + " frames";
    }
};

std::string pairId(int i) {
    char id[16];
    std::snprintf(id, sizeof id, "%03d", i);
    return id;
}

// Renders the pairs into DIR/runs, in time order per pair: baseline, A/A twin, slowdowns.
Judged renderPairs(const Plan& p, const fs::path& dir) {
    Plan in_dir = p;
    in_dir.out = dir;
    Judged j;
    const int pairs = std::max(p.o.pairs, p.slowdowns.empty() ? 0 : p.o.slow_pairs);
    ProgressBar bar("runs", pairs + p.o.pairs + p.o.slow_pairs * int(p.slowdowns.size()));
    auto run = [&](const std::string& name, const Slowdown& slowdown) {
        bar.step("calibrate " + name, 0);
        auto data = runOnce(in_dir, name, slowdown);
        bar.step("calibrate " + name);
        return data;
    };
    for (int i = 0; i < pairs; ++i) {
        auto base = run("base-" + pairId(i), {});
        if (i == 0) checkSlowdownPasses(p, base), j.describe(base);
        if (i < p.o.pairs) j.add(base, run("aa-" + pairId(i), {}), "aa", i, p);
        if (i < p.o.slow_pairs)
            for (const auto& s : p.slowdowns) {
                j.injected[s.spec()] = s.pct;
                j.add(base, run("slow-" + s.pass + "-" + reports::Cell(s.pct).text() + "-" + pairId(i), s),
                      s.spec(), i, p);
            }
    }
    return j;
}

// `--from DIR`: the runs of an earlier calibration judged again (another threshold, alpha
// or counts) without rendering. Runs are matched by name: base-I, aa-I, slow-PASS-PCT-I.
Judged judgeExisting(const Plan& p) {
    const fs::path runs = fs::path(p.o.from) / "runs";
    auto bad = [&](const std::string& why) {
        return std::invalid_argument("calibrate: --from " + p.o.from + ": " + why +
                                     "; expected an earlier calibrate's output directory (runs/base-000, ...)");
    };
    if (!fs::is_directory(runs)) throw bad("no runs/ directory");
    auto load = [&](const fs::path& d) {
        auto data = reports::loadRun(d);
        if (data.repeats < p.repeats.back())
            throw bad(d.filename().string() + " has " + std::to_string(data.repeats) + " repetitions, --repeats asks " +
                      std::to_string(p.repeats.back()));
        return data;
    };
    Judged j;
    for (int i = 0; fs::is_directory(runs / ("base-" + pairId(i))); ++i) {
        auto base = load(runs / ("base-" + pairId(i)));
        if (i == 0) j.describe(base);
        for (const auto& e : fs::directory_iterator(runs)) {
            const std::string name = e.path().filename().string(), suffix = "-" + pairId(i);
            if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
            const std::string stem = name.substr(0, name.size() - suffix.size());
            if (stem == "aa") j.add(base, load(e.path()), "aa", i, p);
            if (stem.rfind("slow-", 0) != 0) continue;
            size_t dash = stem.rfind('-');
            std::string pass = stem.substr(5, dash - 5), pct = stem.substr(dash + 1);
            std::string kind = pass + "=" + pct;
            j.injected[kind] = std::stod(pct);
            j.add(base, load(e.path()), kind, i, p);
        }
    }
    if (j.by_kind.empty()) throw bad("no pairs (base-000 with aa-000 or slow-...-000)");
    return j;
}

// calibrate.csv, calibrate_pairs.csv and the printed table.
void writeTables(const Plan& p, const Judged& judged, const fs::path& dir) {
    auto injected = judged.injected;
    const std::string& device = judged.device;
    reports::CsvTable rates(kRateColumns), pair_rows(kPairColumns);
    std::string variants;
    for (const auto& v : judged.by_kind.begin()->second.begin()->second.front().variants) variants += (variants.empty() ? "" : ",") + v;
    std::printf("calibrate on %s: threshold %s, alpha %g, %s, variants %s\n", device.c_str(), p.o.threshold.c_str(),
                p.rule.alpha, judged.setup.c_str(), variants.c_str());
    std::printf("%-14s %7s %6s %7s %20s %10s %10s %8s\n", "kind", "repeats", "pairs", "exit 1", "rate [95% Wilson]",
                "change", "detectable", "noise");
    for (const auto& [kind, by_reps] : judged.by_kind)
        for (const auto& [reps, list] : by_reps) {
            int exit1 = 0, unknown = 0, same = 0;
            std::vector<double> changes, detectable, noise;
            for (const auto& pv : list) {
                exit1 += pv.slower();
                for (size_t v = 0; v < pv.verdicts.size(); ++v) {
                    const auto& t = pv.verdicts[v];
                    unknown += t.verdict == "UNKNOWN";
                    same += t.verdict == "SAME";
                    if (t.interval) changes.push_back(t.interval->estimate);
                    if (t.detectable) detectable.push_back(*t.detectable);
                    if (t.noise) noise.push_back(*t.noise);
                    auto opt = [](std::optional<double> x) { return x ? reports::Cell(*x * 100) : reports::Cell(); };
                    const auto& ci = t.interval;
                    bool b = ci && ci->bounded();
                    pair_rows.addRow({{"kind", kind}, {"injected_pct", injected[kind]}, {"pair", pv.pair},
                                      {"repeats", reps}, {"variant", pv.variants[v]}, {"verdict", t.verdict},
                                      {"change_pct", opt(t.change)},
                                      {"hl_change_pct", opt(ci ? std::optional(ci->estimate) : std::nullopt)},
                                      {"change_low_pct", opt(b ? std::optional(ci->low) : std::nullopt)},
                                      {"change_high_pct", opt(b ? std::optional(ci->high) : std::nullopt)},
                                      {"noise_cv_pct", opt(t.noise)},
                                      {"q_value", t.q ? reports::Cell(*t.q) : reports::Cell()}});
                }
            }
            const int n = int(list.size());
            auto [lo, hi] = wilsonInterval(exit1, n);
            double med_change = changes.empty() ? NAN : median(changes), med_det = detectable.empty() ? NAN : median(detectable);
            rates.addRow({{"kind", kind}, {"injected_pct", injected[kind]}, {"repeats", reps},
                          {"pairs", n}, {"exit1_pairs", exit1}, {"rate", double(exit1) / n}, {"rate_low", lo},
                          {"rate_high", hi}, {"median_change_pct", changes.empty() ? reports::Cell() : reports::Cell(med_change * 100)},
                          {"median_detectable_pct", detectable.empty() ? reports::Cell() : reports::Cell(med_det * 100)},
                          {"unknown_cells", unknown}, {"same_cells", same},
                          {"median_noise_cv_pct", noise.empty() ? reports::Cell() : reports::Cell(median(noise) * 100)}});
            char rate[64];
            std::snprintf(rate, sizeof rate, "%.2f [%.2f, %.2f]", double(exit1) / n, lo, hi);
            std::printf("%-14s %7d %6d %7d %20s %9.1f%% %9.1f%% %7.1f%%\n", kind == "aa" ? "A/A" : kind.c_str(), reps, n,
                        exit1, rate, med_change * 100, med_det * 100, noise.empty() ? NAN : median(noise) * 100);
        }
    reports::writeTextAtomically(dir / "calibrate.csv", rates.str());
    reports::writeTextAtomically(dir / "calibrate_pairs.csv", pair_rows.str());
}

// calibrate.json: what was measured and by which rule.
void writeJson(const Plan& p, const fs::path& dir, std::chrono::steady_clock::time_point start,
               const std::string& device, const std::string& setup) {
    nlohmann::json j;
    j["command"] = "calibrate";
    j["argv"] = p.o.run.control.argv;
    j["device"] = device;
    j["setup"] = setup;
    if (!p.o.from.empty()) j["from"] = p.o.from;
    j["threshold"] = p.rule.threshold;
    j["alpha"] = p.rule.alpha;
    j["repeats"] = p.repeats;
    j["pairs"] = p.o.pairs;
    j["slow_pairs"] = p.o.slow_pairs;
    j["slowdowns"] = p.o.slowdowns;
    j["rule"] = kTimeRule;
    j["rate_interval"] = "Wilson score, 95%";
    j["exit1"] = "a pair exits 1 when any of its cells is SLOWER (the images are equal, so quality never fails it)";
    j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (p.o.settle) {
        j["settle"] = {{"max_runs", p.o.max_runs}, {"repeat", p.repeats.front()}, {"rule", kSettleRule}};
        j["exit1"] = "a pair exits 1 when any of its cells is SLOWER; an A/A pair is wrong when any is SLOWER or FASTER";
    }
    reports::writeTextAtomically(dir / "calibrate.json", j.dump(2) + "\n");
}

}  // namespace

int runCalibrate(const CalibrateOptions& options) {
    const Plan p = plan(options);
    const auto start = std::chrono::steady_clock::now();
    reports::OutputDir out(p.out);
    if (p.o.from.empty() && !p.o.settle) fs::create_directories(out.path() / "runs");
    if (p.o.settle) {
        std::string variants;
        for (const auto& v : p.o.run.variants) variants += (variants.empty() ? "" : ",") + v;
        const SettleCalibration c{.argv = p.o.run.control.argv, .variants = variants, .pairs = p.o.pairs, .slow_pairs = p.o.slow_pairs,
                                  .slowdowns = p.slowdowns, .threshold = p.o.threshold,
                                  .threshold_fraction = p.rule.threshold, .alpha = p.rule.alpha,
                                  .max_runs = p.o.max_runs, .repeat = p.repeats.front()};
        runSettleCalibration(c, out.path());
        writeJson(p, out.path(), start, "", "");
        out.commit();
        std::printf("calibrate --settle: %s (rates), %s (every cell); ab directories under %s\n",
                    (p.out / "calibrate_settle.csv").c_str(), (p.out / "calibrate_settle_pairs.csv").c_str(),
                    (p.out / "settles").c_str());
        return 0;
    }
    const Judged judged = p.o.from.empty() ? renderPairs(p, out.path()) : judgeExisting(p);
    writeTables(p, judged, out.path());
    writeJson(p, out.path(), start, judged.device, judged.setup);
    out.commit();
    std::printf("calibrate: %s (rates), %s (every verdict); run directories under %s\n",
                (p.out / "calibrate.csv").c_str(), (p.out / "calibrate_pairs.csv").c_str(),
                (p.o.from.empty() ? p.out / "runs" : fs::path(p.o.from) / "runs").c_str());
    return 0;
}

}  // namespace cbr::harness
