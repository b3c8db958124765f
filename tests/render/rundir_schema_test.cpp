// The run directory's schema (rundir/) against real runs on lavapipe (validation on): a run, a
// sweep and score-seq on the run's saved frames. Every column of frames.csv, summary.csv and
// sweep.csv is the schema's, in its order, and every schema column is written; every run.json
// key written is the schema's and every schema key is written by a run that meets its
// condition; and each reader finds what it reads: report_data's summary and frame queries, the
// sweep's points, gbench's counters and compare's cells give back the values written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "reports/gbench.h"
#include "reports/report_data.h"
#include "reports/sweep.h"
#include "rundir/files.h"
#include "rundir/frames_csv.h"
#include "rundir/pixel_classes.h"
#include "rundir/run_json_keys.h"
#include "rundir/summary_csv.h"
#include "rundir/sweep_csv.h"
#include "settings/table.h"
#include "tests/render/bench_runner.h"

namespace fs = std::filesystem;
using cbr::test::Csv;
using cbr::test::readCsv;
using cbr::test::readJson;
using cbr::test::runBench;
namespace rundir = cbr::rundir;

namespace {

const std::vector<std::string> kSmall = {"--res", "64x48", "--frames", "3", "--repeat", "2", "--warmup", "0",
                                         "--quiet", "--validate"};

struct Runs {
    fs::path work, run, sweep, seq;
    cbr::test::BenchResult run_result, sweep_result, seq_result;
};

// A run with every variant (the blocks scene's orbit: placed on a grid, passes left out), an
// ssaa reference and the CPU scorer; a sweep; score-seq of one variant's saved frames against
// the reference's, with thresholds it crosses.
const Runs& runs() {
    static Runs r = [] {
        Runs x;
        x.work = cbr::test::scratchDir("rundir-schema");
        x.run = x.work / "run";
        x.sweep = x.work / "sweep";
        x.seq = x.work / "seq";
        std::vector<std::string> run = {"run", "--scene", "blocks", "--path", "orbit", "--reference", "ssaa", "--ssaa",
                                        "2", "--scorer", "cpu", "--save-frames", "--out", x.run.string()};
        run.insert(run.end(), kSmall.begin(), kSmall.end());
        x.run_result = runBench(run, x.work);
        std::vector<std::string> sweep = {"sweep", "--variants", "cbr-cso,drr", "--param", "cso-tolerance=0.01,0.1",
                                          "--param", "drr-scale=0.5,0.75", "--out", x.sweep.string()};
        sweep.insert(sweep.end(), kSmall.begin(), kSmall.end());
        x.sweep_result = runBench(sweep, x.work);
        const fs::path frames = x.run / rundir::kFramesDir;
        x.seq_result = runBench({"score-seq", (frames / "reference_%04d.png").string(), (frames / "drr_%04d.png").string(),
                                 "--warn", "psnr=99", "--fail", "ssim=0.1", "--quiet", "--out", x.seq.string()},
                                x.work);
        return x;
    }();
    return r;
}

void expectRan(const Runs& r) {
    ASSERT_EQ(r.run_result.exit_code, 0) << r.run_result.err;
    ASSERT_EQ(r.sweep_result.exit_code, 0) << r.sweep_result.err;
    ASSERT_EQ(r.seq_result.exit_code, 1) << "a --warn crossed: " << r.seq_result.err;
    for (const fs::path& dir : {r.run, r.sweep}) {
        const auto run = readJson(dir / rundir::kRunJson);
        EXPECT_EQ(run["validation"]["errors"], 0) << run["validation"]["first_messages"].dump(1);
        EXPECT_EQ(run["validation"]["warnings"], 0) << run["validation"]["first_messages"].dump(1);
    }
}

// A frames.csv header's frame statistics (pixel classes), passes and passes with invocations.
struct FrameParts {
    std::vector<std::string> stats, passes;
    std::set<std::string> invoked;
};

FrameParts frameParts(const std::vector<std::string>& header) {
    FrameParts p;
    for (const auto& h : header) {
        if (std::find(std::begin(rundir::pixels::kClasses), std::end(rundir::pixels::kClasses), h) !=
            std::end(rundir::pixels::kClasses))
            p.stats.push_back(h);
        if (auto pass = rundir::frames::passOfColumn(h); !pass.empty()) p.passes.push_back(pass);
    }
    for (const auto& pass : p.passes)
        if (std::find(header.begin(), header.end(), rundir::frames::passInvocations(pass)) != header.end())
            p.invoked.insert(pass);
    return p;
}

// A cell as the readers take it: empty is no value.
std::optional<double> number(const std::string& cell) {
    if (cell.empty()) return std::nullopt;
    return std::stod(cell);
}

void expectSameNumber(const std::optional<double>& read, const std::string& written, const std::string& what) {
    const auto w = number(written);
    ASSERT_EQ(read.has_value(), w.has_value()) << what << ": written '" << written << "'";
    if (w && !(std::isnan(*w) && std::isnan(*read))) {
        EXPECT_EQ(*read, *w) << what;
    }
}

}  // namespace

// frames.csv: the fixed columns in order, then every pixel class, each pass's time and the
// invocations of the passes that count them; nothing else.
TEST(RundirSchema, FramesCsvColumnsAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    for (const fs::path& dir : {r.run, r.sweep}) {
        const Csv csv = readCsv(dir / rundir::kFramesCsv);
        const FrameParts p = frameParts(csv.header);
        EXPECT_EQ(csv.header, rundir::frames::columns(p.stats, p.passes, p.invoked)) << dir;
        EXPECT_FALSE(p.passes.empty()) << dir;
    }
    const FrameParts p = frameParts(readCsv(r.run / rundir::kFramesCsv).header);
    EXPECT_EQ(p.stats, std::vector<std::string>(std::begin(rundir::pixels::kClasses), std::end(rundir::pixels::kClasses)))
        << "every pixel class, in the class map's order (cbr-clip has the full history's clipped)";
    EXPECT_FALSE(p.invoked.empty()) << "lavapipe counts fragment-shader invocations";
    EXPECT_EQ(readCsv(r.seq / rundir::kFramesCsv).header, rundir::frames::sequenceColumns());
}

// summary.csv: the fixed columns, each pass's median and each statistic's mean, in order.
TEST(RundirSchema, SummaryCsvColumnsAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    for (const fs::path& dir : {r.run, r.sweep}) {
        const FrameParts p = frameParts(readCsv(dir / rundir::kFramesCsv).header);
        EXPECT_EQ(readCsv(dir / rundir::kSummaryCsv).header, rundir::summary::columns(p.passes, p.stats)) << dir;
    }
    EXPECT_EQ(readCsv(r.seq / rundir::kSummaryCsv).header, rundir::summary::sequenceColumns());
}

TEST(RundirSchema, SweepCsvColumnsAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    EXPECT_EQ(readCsv(r.sweep / rundir::kSweepCsv).header, rundir::sweep::columns());
}

// report_data reads back every summary.csv cell of every variant, and its queries find theirs.
TEST(RundirSchema, ReportDataReadsWhatWasWritten) {
    const Runs& r = runs();
    expectRan(r);
    for (const fs::path& dir : {r.run, r.sweep, r.seq}) {
        SCOPED_TRACE(dir.string());
        const auto d = cbr::reports::loadRun(dir);
        const Csv summary = readCsv(dir / rundir::kSummaryCsv), frames = readCsv(dir / rundir::kFramesCsv);
        ASSERT_EQ(d.variants.size(), summary.rows.size());
        for (size_t i = 0; i < summary.rows.size(); ++i) {
            const std::string v = summary.at(i, rundir::summary::kVariant);
            EXPECT_EQ(d.variants[i], v);
            for (const auto& column : summary.header)
                EXPECT_EQ(cbr::reports::summaryText(d, v, column), summary.at(i, column)) << v << " " << column;
            EXPECT_TRUE(cbr::reports::variantOk(d, v)) << v;
            if (dir == r.seq) continue;  // score-seq times nothing
            const auto s = cbr::reports::summarySpeedup(d, v);
            expectSameNumber(s.value, summary.at(i, rundir::summary::kSpeedup), v + " speed-up");
            expectSameNumber(s.low, summary.at(i, rundir::summary::kSpeedupLow), v + " speed-up low");
            expectSameNumber(s.high, summary.at(i, rundir::summary::kSpeedupHigh), v + " speed-up high");
        }
        EXPECT_EQ(cbr::reports::passNames(d), frameParts(frames.header).passes);
        EXPECT_EQ(d.repeats, dir == r.seq ? 1 : 2);
    }
}

// The frame queries: every status-ok row's time by repetition, and repetition 0's PSNR per frame.
TEST(RundirSchema, FrameQueriesReadWhatWasWritten) {
    const Runs& r = runs();
    expectRan(r);
    const auto d = cbr::reports::loadRun(r.run);
    const Csv frames = readCsv(r.run / rundir::kFramesCsv);
    namespace f = rundir::frames;
    for (const auto& v : d.variants) {
        size_t rows = 0, timed = 0;
        for (const auto& [rep, ms] : cbr::reports::gpuMsByRepetition(d, v)) timed += ms.size();
        const auto psnr = cbr::reports::perFrame(d, v, f::kPsnrDb, 0);
        for (size_t i = 0; i < frames.rows.size(); ++i) {
            if (frames.at(i, f::kVariant) != v) continue;
            rows += frames.at(i, f::kStatus) == "ok";
            if (frames.at(i, f::kRepeat) != "0") continue;
            const size_t k = size_t(std::stoi(frames.at(i, f::kFrame)));
            ASSERT_LT(k, psnr.size());
            expectSameNumber(psnr[k], frames.at(i, f::kPsnrDb), v + " psnr_db of frame " + std::to_string(k));
        }
        EXPECT_EQ(timed, rows) << v;
        EXPECT_GT(rows, 0u) << v;
        const bool checkerboard = v.rfind("cbr-", 0) == 0;
        EXPECT_EQ(cbr::reports::isCheckerboard(d, v), checkerboard) << v;
    }
}

// The sweep's reader: every point's fields are its sweep.csv row's cells.
TEST(RundirSchema, SweepReaderReadsWhatWasWritten) {
    const Runs& r = runs();
    expectRan(r);
    const auto data = cbr::reports::loadSweep(r.sweep);
    const Csv csv = readCsv(r.sweep / rundir::kSweepCsv);
    ASSERT_EQ(data.points.size(), csv.rows.size());
    namespace k = rundir::sweep;
    for (size_t i = 0; i < csv.rows.size(); ++i) {
        const auto& p = data.points[i];
        const std::string& c = p.config;
        EXPECT_EQ(c, csv.at(i, k::kConfig));
        EXPECT_EQ(p.variant, csv.at(i, k::kVariant));
        EXPECT_EQ(p.status, csv.at(i, k::kStatus));
        EXPECT_EQ(p.path, csv.at(i, k::kPath));
        EXPECT_EQ(p.reference, csv.at(i, k::referenceColumn()));
        expectSameNumber(p.shading_cost, csv.at(i, k::shadingCostColumn()), c);
        for (const auto* row : k::settingRows()) {
            if (row->type == cbr::settings::Type::Word) {
                const auto it = p.words.find(row->column);
                EXPECT_EQ(it == p.words.end() ? std::string() : it->second, csv.at(i, row->column)) << c;
            } else {
                expectSameNumber(p.number(row->column), csv.at(i, row->column), c + " " + row->column);
            }
        }
        const std::pair<std::optional<double>, const char*> figures[] = {
            {p.gpu_ms, k::kGpuMsMedian}, {p.gpu_ms_low, k::kGpuMsCiLow}, {p.gpu_ms_high, k::kGpuMsCiHigh},
            {p.speedup.value, k::kSpeedup}, {p.speedup.low, k::kSpeedupLow}, {p.speedup.high, k::kSpeedupHigh},
            {p.psnr_db, k::kPsnrDb}, {p.ssim, k::kSsim}, {p.eci, k::kEci}, {p.flicker, k::kFlickerRatio},
            {p.jod, k::kCvvdpJod}};
        for (const auto& [value, column] : figures) expectSameNumber(value, csv.at(i, column), c + " " + column);
        for (const char* pc : rundir::pixels::kClasses) {
            const auto it = p.classes.find(pc);
            expectSameNumber(it == p.classes.end() ? std::nullopt : std::optional(it->second), csv.at(i, pc), c + " " + pc);
        }
    }
}

// gbench.json's counters are summary.csv's figures.
TEST(RundirSchema, GbenchReadsWhatWasWritten) {
    const Runs& r = runs();
    expectRan(r);
    const auto d = cbr::reports::loadRun(r.run);
    const auto g = cbr::reports::gbenchJson(d);
    const Csv summary = readCsv(r.run / rundir::kSummaryCsv);
    namespace sm = rundir::summary;
    const std::pair<const char*, const char*> counters[] = {
        {"psnr_db", sm::kPsnrDbMean}, {"ssim", sm::kSsimMean}, {"flip", sm::kFlipMean}, {sm::kCvvdpJod, sm::kCvvdpJod},
        {sm::kEci, sm::kEci}, {sm::kSpeedup, sm::kSpeedup}, {sm::kSpeedupLow, sm::kSpeedupLow},
        {sm::kSpeedupHigh, sm::kSpeedupHigh}};
    size_t checked = 0;
    for (const auto& b : g["benchmarks"]) {
        const std::string name = b["run_name"];
        const std::string v = name.substr(name.rfind('/') + 1);
        for (size_t i = 0; i < summary.rows.size(); ++i) {
            if (summary.at(i, sm::kVariant) != v) continue;
            for (const auto& [counter, column] : counters) {
                const auto written = number(summary.at(i, column));
                if (!written || !std::isfinite(*written)) continue;  // no JSON number for inf or none
                ASSERT_TRUE(b.contains(counter)) << name << " " << counter;
                EXPECT_EQ(b[counter].get<double>(), *written) << name << " " << counter;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 0u);
    EXPECT_EQ(g["context"]["device"], readJson(r.run / rundir::kRunJson)["device"]["name"]);
}

// compare reads summary.csv's quality and run.json's scene, path and settings: its cells of a
// run against its copy hold them.
TEST(RundirSchema, CompareReadsWhatWasWritten) {
    const Runs& r = runs();
    expectRan(r);
    const fs::path copy = r.work / "compare-copy";
    fs::remove_all(copy);
    fs::copy(r.run, copy, fs::copy_options::recursive);
    const auto c = runBench({"compare", r.run.string(), copy.string()}, r.work);
    ASSERT_TRUE(c.exit_code == 0 || c.exit_code == 2) << c.exit_code << c.err;
    const Csv cells = readCsv(copy / "compare.csv"), summary = readCsv(r.run / rundir::kSummaryCsv);
    const auto run = readJson(r.run / rundir::kRunJson);
    std::string key;
    for (const auto* row : cbr::settings::compareKey()) {
        const auto& value = run["settings"].contains(row->column) ? run["settings"][row->column] : run["metrics"]["reference_kind"];
        key += (key.empty() ? "" : ";") + std::string(row->column) + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
    }
    ASSERT_EQ(cells.rows.size(), summary.rows.size());
    namespace sm = rundir::summary;
    for (size_t i = 0; i < cells.rows.size(); ++i) {
        const std::string v = cells.at(i, "variant");
        EXPECT_EQ(cells.at(i, "scene"), run["scene"]["name"].get<std::string>() + "#" + run["scene"]["hash"].get<std::string>());
        EXPECT_EQ(cells.at(i, "path"), run["path"]["name"].get<std::string>() + "#" + run["path"]["hash"].get<std::string>());
        EXPECT_EQ(cells.at(i, "settings"), key) << v;
        for (size_t j = 0; j < summary.rows.size(); ++j) {
            if (summary.at(j, sm::kVariant) != v) continue;
            EXPECT_EQ(cells.at(i, "baseline_psnr_db"), summary.at(j, sm::kPsnrDbMean)) << v;
            EXPECT_EQ(cells.at(i, "current_ssim"), summary.at(j, sm::kSsimMean)) << v;
            EXPECT_EQ(cells.at(i, "baseline_eci"), summary.at(j, sm::kEci)) << v;
            EXPECT_EQ(cells.at(i, "current_cvvdp_jod"), summary.at(j, sm::kCvvdpJod)) << v;
        }
    }
}

namespace {

// Every key path of a JSON value: "a.b", "a[]" for an array (its elements under "a[]").
void flatten(const nlohmann::json& v, const std::string& prefix, std::set<std::string>& out) {
    if (v.is_object()) {
        for (const auto& [k, x] : v.items()) flatten(x, prefix.empty() ? k : prefix + "." + k, out);
    } else if (v.is_array()) {
        out.insert(prefix + "[]");
        for (const auto& x : v) flatten(x, prefix + "[]", out);
    } else {
        out.insert(prefix);
    }
}

// The conditions of the schema's keys (KeyPath::only_when) the run and the sweep meet, those
// score-seq's run meets, and every condition known; one this test does not know fails it, so
// that a new key's is judged here.
const std::set<std::string> kRunMet = {
    "an ssaa reference", "the CPU scorer", "a built-in path placed in the scene", "a path placed on a grid",
    "checkerboard variants", "cbr-cso", "taau", "checkerboard variants and taau",
    "checkerboard variants, not with --resolve-impl reference", "a pass that did not run", "a sweep",
    "ColorVideoVDP scored"};
const std::set<std::string> kSequenceMet = {"ColorVideoVDP scored", "the global shift",
                                            "thresholds given (crossed: and crossed)", "a threshold crossed"};
const std::set<std::string> kNeverMet = {"a variant that failed, was skipped or is unsteady", "--debug-slowdown",
                                         "the interior placement", "a glTF scene with animations",
                                         "a glTF scene with cameras", "--motion", "lavapipe"};

bool known(const std::string& condition) {
    return kRunMet.count(condition) || kSequenceMet.count(condition) || kNeverMet.count(condition);
}

// Written keys all in the schema; the schema's keys all written where the runs meet their condition.
void expectKeysAreTheSchemas(const std::vector<rundir::run::KeyPath>& schema, const std::vector<fs::path>& files,
                             std::set<std::string> met) {
    std::set<std::string> written;
    for (const auto& f : files) flatten(readJson(f), "", written);
    for (const auto& w : written)
        EXPECT_TRUE(std::any_of(schema.begin(), schema.end(), [&](const auto& k) { return rundir::run::matches(k.path, w); }))
            << "run.json key " << w << " is not in rundir/'s schema";
    for (const auto& k : schema) {
        if (k.only_when && !met.count(k.only_when)) {
            EXPECT_TRUE(known(k.only_when)) << k.path << ": a condition this test does not know: " << k.only_when;
            continue;
        }
        EXPECT_TRUE(std::any_of(written.begin(), written.end(), [&](const auto& w) { return rundir::run::matches(k.path, w); }))
            << "the schema's " << k.path << (k.only_when ? std::string(" (") + k.only_when + ")" : "") << " was not written";
    }
}

}  // namespace

TEST(RundirSchema, RunJsonKeysAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    std::set<std::string> met = kRunMet;
    if (readJson(r.run / rundir::kRunJson)["device"]["is_lavapipe"].get<bool>()) met.insert("lavapipe");
    expectKeysAreTheSchemas(rundir::run::runJsonKeys(), {r.run / rundir::kRunJson, r.sweep / rundir::kRunJson}, met);
}

TEST(RundirSchema, ScoreSeqRunJsonKeysAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    expectKeysAreTheSchemas(rundir::run::sequenceJsonKeys(), {r.seq / rundir::kRunJson}, kSequenceMet);
}

// The run directory holds the files its run.json lists, under the schema's names.
TEST(RundirSchema, FilesAreTheSchemas) {
    const Runs& r = runs();
    expectRan(r);
    for (const char* f : {rundir::kFramesCsv, rundir::kSummaryCsv, rundir::kRunJson, rundir::kReportHtml})
        EXPECT_TRUE(fs::exists(r.run / f)) << f;
    EXPECT_TRUE(fs::is_directory(r.run / rundir::kWorstDir / rundir::kWorstPageDir));
    EXPECT_TRUE(fs::is_directory(r.run / rundir::kFramesDir));
    for (const char* f : {rundir::kSweepCsv, rundir::kSweepHtml}) EXPECT_TRUE(fs::exists(r.sweep / f)) << f;
    for (const auto& f : readJson(r.run / rundir::kRunJson)["files"])
        EXPECT_TRUE(fs::exists(r.run / f.get<std::string>())) << f;
}
