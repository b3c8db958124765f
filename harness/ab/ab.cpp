// `cbrbench ab`: the checks, the ABBA loop and the child runs (ab.h).
#include "harness/ab/ab.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "harness/ab/ab_internal.h"
#include "harness/base/interrupt.h"
#include "harness/jobs/options.h"
#include "harness/base/process.h"
#include "reports/output_dir.h"
#include "reports/report_data.h"
#include "rundir/summary_csv.h"

namespace cbr::harness {
namespace ab {
namespace {

std::vector<std::string> splitWords(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

std::string readFirstLine(const fs::path& p) {
    std::ifstream in(p);
    std::string line;
    std::getline(in, line);
    return line;
}

// The binary of a side: this cbrbench when not given, else an executable file.
fs::path sideBinary(const std::string& given, const char* option) {
    if (given.empty()) return fs::read_symlink("/proc/self/exe");
    if (!fs::is_regular_file(given) || ::access(given.c_str(), X_OK) != 0)
        throw std::invalid_argument(std::string("ab: ") + option + " " + given +
                                    ": no such executable file; accepted: a cbrbench binary (default: this one)");
    return fs::absolute(given);
}

// ab sets these itself on every run.
void refuseOwnOptions(const std::vector<std::string>& args, const std::string& where) {
    for (const auto& a : args)
        for (const char* own : {"--out", "--repeat", "--quiet", "--shard"})
            if (a == own || a.rfind(std::string(own) + "=", 0) == 0)
                throw std::invalid_argument("ab: " + where + ": " + own + " is set by ab itself (--out DIR, --repeat N); "
                                            "accepted: run's other options");
}

// `BIN plan ARGS`: the side's own binary checks its run arguments without rendering; a
// matrix (comma lists) is refused: ab compares one job.
void checkSideArgs(const Side& s, const std::string& role) {
    const fs::path tmp = fs::temp_directory_path() / ("cbrbench-ab-plan-" + std::to_string(::getpid()));
    std::vector<std::string> argv = {s.bin.string(), "plan"};
    argv.insert(argv.end(), s.args.begin(), s.args.end());
    const ChildExit end = runChildProcess(argv, tmp.string() + ".out", tmp.string() + ".err");
    std::string first = readFirstLine(tmp.string() + ".out"), err = readFirstLine(tmp.string() + ".err");
    fs::remove(tmp.string() + ".out");
    fs::remove(tmp.string() + ".err");
    if (end.code != 0) {
        if (err.rfind("cbrbench: ", 0) == 0) err = err.substr(10);
        throw std::invalid_argument("ab: side " + role + "'s run arguments (" + s.bin.string() + " plan): " +
                                    (err.empty() ? "exit " + std::to_string(end.code) : err));
    }
    if (first.find(": 1 job ") == std::string::npos)
        throw std::invalid_argument("ab: side " + role + "'s run arguments make a job matrix (" + first +
                                    "); accepted: one scene, path, pipeline and resolution");
}

void checkNumbers(const AbOptions& o) {
    if (!(o.alpha > 0 && o.alpha < 1))
        throw std::invalid_argument("ab: --alpha " + std::to_string(o.alpha) + ": accepted: 0 < alpha < 1");
    if (o.repeat < 1) throw std::invalid_argument("ab: --repeat " + std::to_string(o.repeat) + ": accepted: >= 1");
    if (o.max_runs < 2 || o.max_runs % 2 != 0)
        throw std::invalid_argument("ab: --max-runs " + std::to_string(o.max_runs) +
                                    ": accepted: an even count >= 2 of runs per side (ABBA blocks add 2 per side)");
    if (!(o.max_seconds >= 0))
        throw std::invalid_argument("ab: --max-seconds " + std::to_string(o.max_seconds) + ": accepted: >= 0 (0: no limit)");
    if (!(o.psnr_db >= 0) || !(o.ssim >= 0))
        throw std::invalid_argument("ab: --psnr-threshold and --ssim-threshold: accepted: >= 0");
    if (!o.junit.empty()) {
        fs::path dir = fs::absolute(o.junit).parent_path();
        if (!fs::is_directory(dir) || fs::is_directory(o.junit))
            throw std::invalid_argument("ab: --junit " + o.junit + ": accepted: a file path in an existing directory");
    }
}

Plan makePlan(const AbOptions& o) {
    Plan p;
    p.o = o;
    p.threshold = parseFraction(o.threshold, "ab", "--threshold");
    if (!(p.threshold > 0)) throw std::invalid_argument("ab: --threshold " + o.threshold + ": accepted: a change > 0, e.g. 3%");
    p.eci = parseFraction(o.eci, "ab", "--eci-threshold");
    p.unit = parseSampleUnit(o.unit, "ab");
    checkNumbers(o);
    refuseOwnOptions(o.run_args, "run arguments");
    refuseOwnOptions(splitWords(o.a_args), "--a-args");
    refuseOwnOptions(splitWords(o.b_args), "--b-args");
    p.a = {'a', sideBinary(o.a_bin, "--a-bin"), o.run_args};
    p.b = {'b', sideBinary(o.b_bin, "--b-bin"), o.run_args};
    for (const auto& w : splitWords(o.a_args)) p.a.args.push_back(w);
    for (const auto& w : splitWords(o.b_args)) p.b.args.push_back(w);
    p.looks = planLooks(o.max_runs, 2, o.repeat, p.unit, o.alpha);
    if (p.looks.runs.empty()) {
        int least = o.max_runs;
        while (least < 1000 && planLooks(least, 2, o.repeat, p.unit, o.alpha).runs.empty()) least += 2;
        throw std::invalid_argument("ab: --max-runs " + std::to_string(o.max_runs) + ": too few runs for any verdict (" +
                                    std::string(sampleUnitName(p.unit)) + " samples, --repeat " +
                                    std::to_string(o.repeat) + ", alpha " + std::to_string(o.alpha).substr(0, 6) +
                                    "); accepted: --max-runs >= " + std::to_string(least));
    }
    p.out = o.out.empty() ? fs::path("out") / ("ab-" + timestampForName()) : fs::path(o.out);
    if (fs::exists(p.out))
        throw std::invalid_argument("ab: --out " + p.out.string() + ": already exists; accepted: a new directory");
    checkSideArgs(p.a, "A");
    checkSideArgs(p.b, "B");
    return p;
}

std::string runName(char side, int index) {
    char b[16];
    std::snprintf(b, sizeof b, "%c-%02d", side, index);
    return b;
}

// One child `BIN run ARGS --repeat R --quiet --out DIR/runs/NAME`, read back.
reports::RunData runSide(const Plan& p, const Side& s, int index, const fs::path& dir, State& st) {
    const std::string name = runName(s.letter, index);
    const fs::path run_dir = dir / "runs" / name;
    std::vector<std::string> argv = {s.bin.string(), "run"};
    argv.insert(argv.end(), s.args.begin(), s.args.end());
    argv.insert(argv.end(), {"--repeat", std::to_string(p.o.repeat), "--quiet", "--out", run_dir.string()});
    {
        std::ofstream cmd(run_dir.string() + ".command.txt");
        for (const auto& a : argv) cmd << a << ' ';
        cmd << '\n';
    }
    if (!p.o.quiet) std::printf("ab: %s\n", name.c_str()), std::fflush(stdout);
    const ChildExit end = runChildProcess(argv, run_dir.string() + ".stdout.txt", run_dir.string() + ".stderr.txt");
    throwIfInterrupted();
    if (end.code == kExitInterrupted) throw Interrupted();
    if (end.code != 0 || end.signal != 0)
        throw std::runtime_error("ab: run " + name + " " +
                                 (end.signal ? "was killed by signal " + std::to_string(end.signal)
                                             : "exited " + std::to_string(end.code)) +
                                 ": " + readFirstLine(run_dir.string() + ".stderr.txt") + " (" +
                                 (p.out / "runs" / name).string() + ".stderr.txt)");
    st.runs.push_back(name);
    return reports::loadRun(run_dir);
}

// After the first block: the cells (variants both sides ran), the device, the quality verdicts.
void setUpCells(const Plan& p, State& st, const reports::RunData& a, const reports::RunData& b) {
    if (reports::deviceText(a) != reports::deviceText(b))
        throw std::invalid_argument("ab: the sides ran on different devices or drivers: A " + reports::deviceText(a) + ", B " +
                                    reports::deviceText(b) + "; accepted: one device (the same --device on both sides)");
    st.device = reports::deviceText(a);
    for (const auto& v : a.variants)
        if (std::find(b.variants.begin(), b.variants.end(), v) != b.variants.end()) st.variants.push_back(v);
    st.cells.resize(st.variants.size());
    st.quality.resize(st.variants.size());
    for (size_t i = 0; i < st.variants.size(); ++i) {
        const std::string& v = st.variants[i];
        CellQuality& q = st.quality[i];
        auto read = [&](QualityVerdict& x, const char* column) {
            x.base = reports::summaryNum(a, v, column);
            x.cur = reports::summaryNum(b, v, column);
        };
        read(q.psnr, rundir::summary::kPsnrDbMean);
        read(q.ssim, rundir::summary::kSsimMean);
        read(q.eci, rundir::summary::kEci);
        judgeQuality(q.psnr, true, p.o.psnr_db, false);
        judgeQuality(q.ssim, true, p.o.ssim, false);
        judgeQuality(q.eci, false, p.eci, true);
    }
}

void printLook(const State& st, int look) {
    std::printf("ab: look %d at %d runs per side (%.0f s):", look, st.runs_per_side, st.seconds);
    for (size_t i = 0; i < st.variants.size(); ++i)
        std::printf("%s %s %s %s", i ? "," : "", st.variants[i].c_str(), st.settle[i].time.verdict.c_str(),
                    changeText(st.settle[i].time).c_str());
    std::printf("\n");
    std::fflush(stdout);
}

// One block A B B A: two runs per side, appended to every cell.
void runBlock(const Plan& p, State& st, const fs::path& dir) {
    const int first = st.runs_per_side;
    const Side* order[] = {&p.a, &p.b, &p.b, &p.a};
    int next[2] = {first, first};
    for (const Side* s : order) {
        const int side = s->letter == 'a' ? 0 : 1;
        reports::RunData d = runSide(p, *s, next[side]++, dir, st);
        if (st.runs.size() == 2 && side == 1) {  // a-00 then b-00: the cells can be set up
            const reports::RunData a0 = reports::loadRun(dir / "runs" / st.runs[0]);
            setUpCells(p, st, a0, d);
            for (size_t i = 0; i < st.variants.size(); ++i) st.cells[i].a.push_back(runSampleOf(a0, st.variants[i]));
        }
        for (size_t i = 0; i < st.variants.size(); ++i)
            (side == 0 ? st.cells[i].a : st.cells[i].b).push_back(runSampleOf(d, st.variants[i]));
    }
    st.runs_per_side += 2;
}

// A block at a time until every cell is decided or the budget is spent.
void settle(const Plan& p, State& st, const fs::path& dir) {
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    double last_block = 0;
    for (size_t look = 0;; st.seconds = elapsed()) {
        if (st.runs_per_side >= p.o.max_runs) return void(st.stop = st.stop.empty() ? "budget: runs" : st.stop);
        if (p.o.max_seconds > 0 && st.runs_per_side > 0 && elapsed() + last_block > p.o.max_seconds)
            return void(st.stop = st.stop.empty() ? "budget: seconds" : st.stop);
        const double block_start = elapsed();
        runBlock(p, st, dir);
        if (st.variants.empty())
            throw std::invalid_argument("ab: the sides ran no variant in common; accepted: --variants both sides run");
        last_block = elapsed() - block_start;
        st.seconds = elapsed();
        if (look < p.looks.runs.size() && p.looks.runs[look] == st.runs_per_side) {
            judgeLook(st.settle, st.cells, st.runs_per_side, int(++look), p.looks, p.threshold, p.unit);
            st.looks_taken = int(look);
            printLook(st, st.looks_taken);
            if (allDecided(st.settle) && st.stop.empty()) st.stop = "settled";
            if (allDecided(st.settle) && !p.o.no_stop) return;
        }
    }
}

}  // namespace

void tallyRunsOf(State& st, size_t cell) { tallyRuns(st.settle[cell], st.cells[cell], st.runs_per_side); }

}  // namespace ab

int runAb(const AbOptions& options) {
    namespace fs = std::filesystem;
    const ab::Plan p = ab::makePlan(options);
    reports::OutputDir out(p.out);
    fs::create_directories(out.path() / "runs");
    ab::State st;
    try {
        ab::settle(p, st, out.path());
    } catch (const std::runtime_error& e) {
        if (dynamic_cast<const Interrupted*>(&e)) throw;
        std::fprintf(stderr, "cbrbench: %s\n", e.what());
        out.commit();
        std::fprintf(stderr, "cbrbench: ab: the runs so far are in %s\n", p.out.c_str());
        return kAbRunFailed;
    }
    st.settle.resize(st.variants.size());
    for (size_t i = 0; i < st.variants.size(); ++i)  // never judged (the budget ended first): the runs it had
        if (st.settle[i].at_runs == 0) ab::tallyRunsOf(st, i);
    const int code = ab::writeAbOutputs(p, st, out.path());
    out.commit();
    return code;
}

}  // namespace cbr::harness
