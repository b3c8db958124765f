// `cbrbench calibrate --settle`: A/A and injected-slowdown pairs through `cbrbench ab`, each
// run to its whole budget and replayed by the sequential rule with both sample units, so the
// false-alarm and detection rates of settling are measured, not assumed.
#include "harness/calibrate/calibrate_settle.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/base/exit_codes.h"
#include "harness/base/process.h"
#include "harness/figures/settle.h"
#include "harness/figures/stats.h"
#include "reports/csv.h"
#include "reports/report_data.h"

namespace cbr::harness {
namespace {

namespace fs = std::filesystem;

// calibrate's own options (with a value, and flags): the rest of its command line are run
// options, which every `ab` side takes.
const std::set<std::string> kOwnWithValue = {"--pairs", "--slow-pairs", "--slowdown", "--repeats", "--threshold",
                                             "--alpha", "--from",       "--out",      "--max-runs"};
const std::set<std::string> kOwnFlags = {"--settle", "--quiet"};

std::vector<std::string> runArgsOf(const std::vector<std::string>& argv) {
    std::vector<std::string> out;
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (i == 0 || a == "calibrate") continue;
        const std::string name = a.substr(0, a.find('='));
        if (kOwnFlags.count(a)) continue;
        if (kOwnWithValue.count(name)) {
            if (name == a) ++i;  // "--pairs 20": skip the value too
            continue;
        }
        out.push_back(a);
    }
    return out;
}

struct Pair {
    std::string kind;  // aa or the slowdown's spec
    double injected = 0;
    int index = 0;
    std::string name;  // aa-000, slow-opaque-20-000
    std::vector<std::string> variants;
    std::vector<CellRuns> cells;
    std::vector<std::string> ab_verdicts;  // ab.csv's time_verdict per variant (unit run)
    double seconds = 0;
};

// `self ab --quiet --no-stop ...` into DIR/settles/NAME, read back.
Pair settlePair(const SettleCalibration& c, const fs::path& dir, const std::string& kind, double injected, int index,
                const std::string& b_args) {
    Pair pr{kind, injected, index, "", {}, {}, {}, 0};
    char id[16];
    std::snprintf(id, sizeof id, "%03d", index);
    pr.name = (kind == "aa" ? std::string("aa") : "slow-" + kind.substr(0, kind.find('=')) + "-" +
                                                       reports::Cell(injected).text()) + "-" + id;
    const fs::path out = dir / "settles" / pr.name;
    std::vector<std::string> argv = {fs::read_symlink("/proc/self/exe").string(), "ab", "--quiet", "--no-stop",
                                     "--threshold", c.threshold, "--alpha", reports::Cell(c.alpha).text(),
                                     "--max-runs", std::to_string(c.max_runs), "--repeat", std::to_string(c.repeat),
                                     "--out", out.string()};
    if (!b_args.empty()) argv.insert(argv.end(), {"--b-args", b_args});
    argv.push_back("--");
    const auto run_args = runArgsOf(c.argv);
    argv.insert(argv.end(), run_args.begin(), run_args.end());
    // calibrate's default variant list (the reference alone) is not run's (all of them).
    if (std::none_of(run_args.begin(), run_args.end(), [](const std::string& a) { return a.rfind("--variants", 0) == 0; }))
        argv.insert(argv.end(), {"--variants", c.variants});
    std::printf("calibrate --settle: %s\n", pr.name.c_str());
    std::fflush(stdout);
    const ChildExit end = runChildProcess(argv, out.string() + ".stdout.txt", out.string() + ".stderr.txt");
    if (end.code != kAbSettled && end.code != kAbRegression && end.code != kAbUndecided)
        throw std::runtime_error("calibrate: ab " + pr.name + " exited " + std::to_string(end.code) + " (see " +
                                 out.string() + ".stderr.txt)");
    const auto csv = reports::readCsv(out / "ab.csv", [](const std::string&) { return false; }, {"variant"});
    for (size_t r = 0; r < csv.size(); ++r) {
        pr.variants.push_back(csv.text(r, "variant"));
        pr.ab_verdicts.push_back(csv.text(r, "time_verdict"));
    }
    pr.cells.resize(pr.variants.size());
    for (char side : {'a', 'b'})
        for (int i = 0;; ++i) {
            char run[16];
            std::snprintf(run, sizeof run, "%c-%02d", side, i);
            if (!fs::is_directory(out / "runs" / run)) break;
            const auto data = reports::loadRun(out / "runs" / run);
            for (size_t v = 0; v < pr.variants.size(); ++v)
                (side == 'a' ? pr.cells[v].a : pr.cells[v].b).push_back(runSampleOf(data, pr.variants[v]));
        }
    pr.seconds = nlohmann::json::parse(std::ifstream(out / "ab.json")).value("seconds", 0.0);
    return pr;
}

const std::vector<std::string> kSettleRateColumns = {
    "unit", "kind", "injected_pct", "pairs", "settled_pairs", "exit1_pairs", "wrong_pairs", "undecided_pairs",
    "rate", "rate_low", "rate_high", "wrong_rate", "median_runs_to_settle", "max_runs", "alpha_per_look"};
const std::vector<std::string> kSettlePairColumns = {"unit", "kind", "injected_pct", "pair", "variant", "verdict",
                                               "ab_verdict", "decided_at_runs", "stopped_at_runs", "change_pct",
                                               "change_low_pct", "change_high_pct", "resolvable_change_pct",
                                               "ab_seconds"};

// Rates per unit and kind: a pair exits 1 when a cell is SLOWER; an A/A pair is wrong when a
// cell is SLOWER or FASTER.
void writeSettleTables(const SettleCalibration& c, const std::vector<Pair>& pairs, const fs::path& dir) {
    reports::CsvTable rates(kSettleRateColumns), rows(kSettlePairColumns);
    std::printf("%-11s %-14s %6s %8s %7s %7s %10s %20s %14s\n", "unit", "kind", "pairs", "settled", "exit 1", "wrong",
                "undecided", "rate [95% Wilson]", "runs to settle");
    for (SampleUnit unit : {SampleUnit::Run, SampleUnit::Repetition}) {
        const LookPlan plan = planLooks(c.max_runs, 2, c.repeat, unit, c.alpha);
        std::map<std::string, std::vector<const Pair*>> by_kind;
        for (const auto& p : pairs) by_kind[p.kind].push_back(&p);
        for (const auto& [kind, list] : by_kind) {
            int settled = 0, exit1 = 0, wrong = 0;
            std::vector<double> runs_to_settle;
            for (const Pair* p : list) {
                const SettleReplay r = replaySettle(p->cells, plan, c.threshold_fraction, unit);
                bool slower = false, any_wrong = false;
                for (size_t v = 0; v < r.cells.size(); ++v) {
                    const CellSettle& cs = r.cells[v];
                    const auto& ci = cs.time.interval;
                    const bool b = ci && ci->bounded();
                    slower |= cs.time.verdict == "SLOWER";
                    any_wrong |= cs.time.verdict == "SLOWER" || cs.time.verdict == "FASTER";
                    auto pct = [](std::optional<double> x) { return x ? reports::Cell(*x * 100) : reports::Cell(); };
                    rows.addRow({{"unit", sampleUnitName(unit)}, {"kind", kind}, {"injected_pct", p->injected},
                                 {"pair", p->index}, {"variant", p->variants[v]}, {"verdict", cs.time.verdict},
                                 {"ab_verdict", unit == SampleUnit::Run ? p->ab_verdicts[v] : std::string()},
                                 {"decided_at_runs", cs.decided() ? reports::Cell(cs.at_runs) : reports::Cell()},
                                 {"stopped_at_runs", r.stopped_at_runs},
                                 {"change_pct", pct(ci ? std::optional(ci->estimate) : std::nullopt)},
                                 {"change_low_pct", pct(b ? std::optional(ci->low) : std::nullopt)},
                                 {"change_high_pct", pct(b ? std::optional(ci->high) : std::nullopt)},
                                 {"resolvable_change_pct", pct(cs.time.resolution)}, {"ab_seconds", p->seconds}});
                }
                const bool all = allDecided(r.cells) && !r.cells.empty();
                settled += all;
                exit1 += slower;
                wrong += kind == "aa" && any_wrong;
                if (all) runs_to_settle.push_back(r.stopped_at_runs);
            }
            const int n = int(list.size());
            const auto [lo, hi] = wilsonInterval(exit1, n);
            rates.addRow({{"unit", sampleUnitName(unit)}, {"kind", kind}, {"injected_pct", list.front()->injected},
                          {"pairs", n}, {"settled_pairs", settled}, {"exit1_pairs", exit1},
                          {"wrong_pairs", kind == "aa" ? reports::Cell(wrong) : reports::Cell()},
                          {"undecided_pairs", n - settled}, {"rate", double(exit1) / n}, {"rate_low", lo},
                          {"rate_high", hi},
                          {"wrong_rate", kind == "aa" ? reports::Cell(double(wrong) / n) : reports::Cell()},
                          {"median_runs_to_settle", runs_to_settle.empty() ? reports::Cell() : reports::Cell(median(runs_to_settle))},
                          {"max_runs", c.max_runs}, {"alpha_per_look", plan.alpha_per_look}});
            char rate[64];
            std::snprintf(rate, sizeof rate, "%.2f [%.2f, %.2f]", double(exit1) / n, lo, hi);
            std::printf("%-11s %-14s %6d %8d %7d %7s %10d %20s %14s\n", sampleUnitName(unit),
                        kind == "aa" ? "A/A" : kind.c_str(), n, settled, exit1,
                        kind == "aa" ? std::to_string(wrong).c_str() : "-", n - settled, rate,
                        runs_to_settle.empty() ? "-" : reports::Cell(median(runs_to_settle)).text().c_str());
        }
    }
    reports::writeTextAtomically(dir / "calibrate_settle.csv", rates.str());
    reports::writeTextAtomically(dir / "calibrate_settle_pairs.csv", rows.str());
}

}  // namespace

int runSettleCalibration(const SettleCalibration& c, const fs::path& dir) {
    fs::create_directories(dir / "settles");
    std::vector<Pair> pairs;
    const int n = std::max(c.pairs, c.slowdowns.empty() ? 0 : c.slow_pairs);
    for (int i = 0; i < n; ++i) {
        if (i < c.pairs) pairs.push_back(settlePair(c, dir, "aa", 0, i, ""));
        if (i < c.slow_pairs)
            for (const auto& s : c.slowdowns)
                pairs.push_back(settlePair(c, dir, s.spec(), s.pct, i, "--debug-slowdown " + s.spec()));
    }
    writeSettleTables(c, pairs, dir);
    return 0;
}

}  // namespace cbr::harness
