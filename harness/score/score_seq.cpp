// `cbrbench score-seq`: two image sequences scored frame by frame with the run's own scorer
// (PSNR, SSIM, FLIP, edge crawl and flicker), into a run-shaped folder with a report.
#include "harness/base/process.h"
#include "harness/score/score_seq.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <cstdio>
#include <set>
#include <thread>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "harness/jobs/options.h"
#include "harness/output/outputs.h"
#include "harness/output/output_cells.h"
#include "harness/base/progress.h"
#include "harness/quality/quality.h"
#include "harness/score/sequence_files.h"
#include "metrics/cvvdp.h"
#include "metrics/image_io.h"
#include "metrics/temporal.h"
#include "renderer/variants/variants.h"
#include "settings/table.h"
#include "reports/csv.h"
#include "reports/output_dir.h"
#include "reports/report.h"
#include "reports/report_data.h"
#include "rundir/files.h"
#include "rundir/frames_csv.h"
#include "rundir/run_json_sequence.h"
#include "rundir/setting_columns.h"
#include "rundir/summary_csv.h"

namespace cbr::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// What score-seq reads, matched up before anything is scored or written.
struct SeqInputs {
    Sequence reference, test;
    std::vector<fs::path> test_files, motion_files;  // per reference frame
    double motion_sx = 1, motion_sy = 1;
    std::string name;
};

// Per frame beyond the FrameRow: where it came from and how its motion was found.
struct SeqFrameInfo {
    long number = 0;
    fs::path reference, test;
    double shift_dx = 0, shift_dy = 0, shift_response = 0;
    bool shift_rejected = false;  // the estimate explained less than no motion: 0 used
    bool cut = false;
};

void parseMotionScale(const std::string& spec, double& sx, double& sy) {
    double x = 0, y = 0;
    char tail = 0;
    const int n = std::sscanf(spec.c_str(), "%lf,%lf%c", &x, &y, &tail);
    if (n == 1 && spec.find(',') == std::string::npos) y = x;
    else if (n != 2) x = NAN;
    if (!std::isfinite(x) || !std::isfinite(y) || x == 0 || y == 0)
        throw SequenceError(kSeqBadOption, "--motion-scale " + spec +
                                               ": accepted: SX,SY or S, finite and non-zero (e.g. -1,-1 when the "
                                               "files hold current-minus-previous, or 960,540 for UV units)");
    sx = x;
    sy = y;
}

// A pattern's file-name stem before the number (frames/cbr-aso_%04d.png: cbr-aso), else
// the folder's name; "test" when neither gives a usable label.
std::string defaultName(const std::string& spec, bool pattern) {
    const fs::path t(spec);
    std::string name;
    if (pattern) {
        name = t.filename().string();
        name = name.substr(0, name.find('%'));
        while (!name.empty() && std::string("_-. ").find(name.back()) != std::string::npos) name.pop_back();
    }
    if (name.empty()) {
        const fs::path dir = fs::absolute(pattern ? t.parent_path() : t).lexically_normal();
        name = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
    }
    if (name.empty() || name == variants::referenceVariant().name || name.find_first_of("/\\,\"") != std::string::npos) name = "test";
    return name;
}

SeqInputs planInputs(const ScoreSeqOptions& o) {
    SeqInputs in;
    in.reference = listSequence(o.reference, "REFERENCE");
    in.test = listSequence(o.test, "TEST");
    in.test_files = matchSequence(in.reference, in.test, "TEST");
    if (!o.motion.empty()) {
        parseMotionScale(o.motion_scale, in.motion_sx, in.motion_sy);
        in.motion_files = matchSequence(in.reference, listSequence(o.motion, "--motion"), "--motion");
    } else if (o.motion_scale != "1,1") {
        throw SequenceError(kSeqBadOption, "--motion-scale without --motion: it scales the motion files' vectors");
    }
    in.name = o.name.empty() ? defaultName(o.test, in.test.pattern) : o.name;
    if (in.name.find_first_of("/\\,\"") != std::string::npos || in.name == variants::referenceVariant().name)
        throw SequenceError(kSeqBadOption, "--name " + in.name + ": accepted: a label without / \\ , \" (and not " +
                                               std::string(variants::referenceVariant().name) + ")");
    return in;
}

metrics::DisplayImage readFrame(const fs::path& file, float exposure, const char* what, long number) {
    try {
        return metrics::readDisplayImage(file, exposure);
    } catch (const std::invalid_argument& e) {
        if (std::string(e.what()).rfind("--exposure", 0) == 0) throw SequenceError(kSeqBadOption, e.what());
        throw SequenceError(kSeqFile, std::string(what) + " frame " + std::to_string(number) + ": " + e.what());
    }
}

void checkSize(const metrics::Rgba8Image& img, int w, int h, const fs::path& file, const char* what) {
    if (img.width != w || img.height != h)
        throw SequenceError(kSeqSize, std::string(what) + " " + file.string() + ": " + std::to_string(img.width) + "x" +
                                          std::to_string(img.height) + "; the reference's first frame is " +
                                          std::to_string(w) + "x" + std::to_string(h) +
                                          " (accepted: every frame of both sequences the same size)");
}

// motion.xy, depth, previous depth per pixel: QualityFrame::analysis's layout.
std::shared_ptr<std::vector<float>> motionFromFile(const fs::path& file, int w, int h, double sx, double sy) {
    metrics::FloatImage m;
    try {
        m = metrics::readFloatImage(file);
    } catch (const std::invalid_argument& e) {
        throw SequenceError(kSeqFile, std::string("--motion ") + e.what());
    }
    if (m.width != w || m.height != h)
        throw SequenceError(kSeqSize, "--motion " + file.string() + ": " + std::to_string(m.width) + "x" +
                                          std::to_string(m.height) + "; the reference's frames are " +
                                          std::to_string(w) + "x" + std::to_string(h));
    if (m.channels < 2)
        throw SequenceError(kSeqFile, "--motion " + file.string() + ": " + std::to_string(m.channels) +
                                          " channel; accepted: 2 or more (the first two are the motion in x and y)");
    const size_t n = size_t(w) * size_t(h);
    auto out = std::make_shared<std::vector<float>>(n * 4, 1.0f);
    for (size_t i = 0; i < n; ++i) {
        (*out)[4 * i] = float(m.data[i * size_t(m.channels)] * sx);
        (*out)[4 * i + 1] = float(m.data[i * size_t(m.channels) + 1] * sy);
    }
    return out;
}

std::shared_ptr<std::vector<float>> uniformAnalysis(int w, int h, double dx, double dy) {
    const size_t n = size_t(w) * size_t(h);
    auto out = std::make_shared<std::vector<float>>(n * 4, 1.0f);
    for (size_t i = 0; i < n; ++i) {
        (*out)[4 * i] = float(dx);
        (*out)[4 * i + 1] = float(dy);
    }
    return out;
}

// Every frame pair, in order; rows and infos are filled, the scorer keeps the worst frames.
struct Scored {
    int width = 0, height = 0;
    std::vector<std::string> conversions;  // how inputs were made display images (once per kind)
};

// `rows`: a deque, so each row keeps its address while the scorer's workers fill it in.
using SeqRows = std::deque<FrameRow>;

Scored scoreFrames(const ScoreSeqOptions& o, const SeqInputs& in, SeqRows& rows, std::vector<SeqFrameInfo>& infos,
                   std::unique_ptr<QualityScorer>& scorer, WorkerPool& workers) {
    Scored s;
    const size_t n = in.reference.frames.size();
    const std::set<long> cuts(o.cuts.begin(), o.cuts.end());
    std::set<std::string> seen_conversions;
    std::optional<metrics::Image> previous_reference;
    ProgressBar bar("frames", int(n));
    for (size_t i = 0; i < n; ++i) {
        const auto& rf = in.reference.frames[i];
        auto ref = readFrame(rf.file, o.exposure, "REFERENCE", rf.number);
        auto img = readFrame(in.test_files[i], o.exposure, "TEST", rf.number);
        if (i == 0) {
            s.width = ref.image.width;
            s.height = ref.image.height;
            scorer = std::make_unique<QualityScorer>(s.width, s.height, settings::flipPpd(o.tune), workers);
            scorer->enableCvvdp(o.tune.display, n > 1 ? o.fps : 0.0);
        }
        checkSize(ref.image, s.width, s.height, rf.file, "REFERENCE");
        checkSize(img.image, s.width, s.height, in.test_files[i], "TEST");
        for (const auto* c : {&ref.conversion, &img.conversion}) {
            // One note per kind of conversion, not per file: drop the file name.
            const std::string kind = c->empty() ? std::string() : c->substr(c->find(' ') + 1);
            if (!kind.empty() && seen_conversions.insert(kind).second) s.conversions.push_back(*c);
        }
        SeqFrameInfo info;
        info.number = rf.number;
        info.reference = rf.file;
        info.test = in.test_files[i];
        info.cut = i == 0 || cuts.count(rf.number) > 0;
        std::shared_ptr<std::vector<float>> analysis;
        if (!in.motion_files.empty()) {
            analysis = motionFromFile(in.motion_files[i], s.width, s.height, in.motion_sx, in.motion_sy);
        } else {
            auto cur = metrics::fromRgba8(ref.image.pixels.data(), s.width, s.height, size_t(s.width) * 4);
            if (previous_reference && !info.cut) {
                auto shift = metrics::estimateGlobalShift(*previous_reference, cur);
                info.shift_dx = shift.dx;
                info.shift_dy = shift.dy;
                info.shift_response = shift.response;
                info.shift_rejected = shift.rejected;
            }
            analysis = uniformAnalysis(s.width, s.height, info.shift_dx, info.shift_dy);
            previous_reference = std::move(cur);
        }
        FrameRow& row = rows.emplace_back();
        row.variant = in.name;
        row.frame = int(i);
        row.render_width = uint32_t(s.width);
        row.render_height = uint32_t(s.height);
        infos.push_back(info);
        scorer->setReference(i, std::make_shared<const std::vector<uint8_t>>(std::move(ref.image.pixels)), 1);
        QualityFrame qf;
        qf.index = int(i);
        qf.rgba = std::make_shared<const std::vector<uint8_t>>(std::move(img.image.pixels));
        qf.analysis = std::move(analysis);
        qf.cut = info.cut;
        scorer->score(in.name, false, row, std::move(qf));
        // Read ahead only as far as the workers keep up: memory stays a few frames deep.
        workers.waitUntilAtMost(size_t(2 * std::max(1u, std::thread::hardware_concurrency())));
        bar.step(in.name + " " + rf.file.filename().string());
    }
    return s;
}

}  // namespace

SeqThreshold parseSeqThreshold(const std::string& spec, const std::string& option) {
    struct Known {
        const char* metric;
        const char* column;
        bool higher_is_worse;
    };
    namespace f = rundir::frames;
    static const Known kKnown[] = {{"psnr", f::kPsnrDb, false}, {"ssim", f::kSsim, false}, {"jod", f::kCvvdpJod, false},
                                   {"flip", f::kFlipMean, true},
                                   {"eci", f::kEci, true},       {"flicker", f::kFlickerRatio, true}};
    const auto eq = spec.find('=');
    SeqThreshold t;
    t.metric = spec.substr(0, eq);
    const Known* k = nullptr;
    for (const auto& c : kKnown)
        if (t.metric == c.metric) k = &c;
    double v = NAN;
    if (eq != std::string::npos) {
        char* end = nullptr;
        const std::string value = spec.substr(eq + 1);
        v = std::strtod(value.c_str(), &end);
        if (value.empty() || *end) v = NAN;
    }
    if (!k || !std::isfinite(v))
        throw SequenceError(kSeqBadOption, option + " " + spec +
                                               ": accepted: METRIC=VALUE with METRIC psnr (dB; crossed below), ssim "
                                               "or jod (below), flip, eci or flicker (above), e.g. " + option +
                                               " psnr=30");
    t.column = k->column;
    t.value = v;
    t.higher_is_worse = k->higher_is_worse;
    return t;
}

namespace {

// frames.csv of a sequence: the run's quality columns plus where each frame came from.
void writeSeqFramesCsv(const fs::path& file, const SeqRows& rows, const std::vector<SeqFrameInfo>& infos,
                       bool motion_files) {
    using namespace rundir::frames;
    reports::CsvTable t(sequenceColumns());
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        const auto& q = row.quality;
        const auto& info = infos[i];
        std::map<std::string, reports::Cell> m;
        m[kVariant] = row.variant;
        m[kRepeat] = 0;
        m[kFrame] = row.frame;
        m[kFrameNumber] = info.number;
        m[kReferenceFile] = info.reference.string();
        m[kTestFile] = info.test.string();
        m[kPsnrDb] = optional(q.psnr_db);
        m[kMse] = optional(q.mse);
        m[kSsim] = optional(q.ssim);
        m[kSsimLuma] = optional(q.ssim_luma);
        m[kFlipMean] = optional(q.flip_mean);
        m[kFlipQ1] = optional(q.flip_q1);
        m[kFlipMedian] = optional(q.flip_median);
        m[kFlipQ3] = optional(q.flip_q3);
        if (q.cvvdp_q) m[kCvvdpJod] = metrics::cvvdpJod(*q.cvvdp_q);
        m[kEci] = optional(q.eci);
        m[kFlickerRatio] = optional(q.flicker_ratio);
        m[kCrawlValidFraction] = optional(q.crawl_valid_fraction);
        m[kMotion] = motion_files ? "files" : "global shift";
        if (!motion_files && !info.cut) {
            m[kShiftDx] = info.shift_dx;
            m[kShiftDy] = info.shift_dy;
            m[kShiftResponse] = info.shift_response;
            m[kGlobalShiftRejected] = info.shift_rejected;
        }
        m[kCut] = info.cut;
        m[kNote] = q.note + row.note;
        t.addRow(m);
    }
    t.write(file);
    reportNaNs(t, rundir::kFramesCsv);
}

void writeSeqSummaryCsv(const fs::path& file, const VariantSummary& s, int width, int height) {
    using namespace rundir::summary;
    reports::CsvTable t(sequenceColumns());
    std::map<std::string, reports::Cell> m;
    m[kVariant] = s.variant;
    m[kStatus] = "ok";
    m[kFrames] = s.frames;
    m[kRepeats] = 1;
    m[kWidth] = width;
    m[kHeight] = height;
    summaryQualityCells(m, s);
    m[kNote] = s.note;
    t.addRow(m);
    t.write(file);
    reportNaNs(t, rundir::kSummaryCsv);
}

json finiteOrNull(const std::optional<double>& v) { return v && std::isfinite(*v) ? json(*v) : json(nullptr); }

// A threshold crossed: the worst frame's value against it.
struct Crossing {
    const SeqThreshold* threshold;
    bool fail;
    int frame;
    long number;
    double value;
};

std::vector<Crossing> judge(const std::vector<SeqThreshold>& warn, const std::vector<SeqThreshold>& fail,
                            const SeqRows& rows, const std::vector<SeqFrameInfo>& infos) {
    std::vector<Crossing> out;
    auto value = [](const Quality& q, const std::string& column) -> std::optional<double> {
        namespace f = rundir::frames;
        if (column == f::kPsnrDb) return q.psnr_db;
        if (column == f::kSsim) return q.ssim;
        if (column == f::kFlipMean) return q.flip_mean;
        if (column == f::kCvvdpJod) return q.cvvdp_q ? std::optional<double>(metrics::cvvdpJod(*q.cvvdp_q)) : std::nullopt;
        if (column == f::kEci) return q.eci;
        return q.flicker_ratio;
    };
    for (bool is_fail : {true, false})
        for (const auto& t : is_fail ? fail : warn) {
            std::optional<Crossing> worst;
            for (size_t i = 0; i < rows.size(); ++i) {
                auto v = value(rows[i].quality, t.column);
                if (!v || std::isnan(*v)) continue;
                const bool crossed = t.higher_is_worse ? *v > t.value : *v < t.value;
                const bool worse = !worst || (t.higher_is_worse ? *v > worst->value : *v < worst->value);
                if (crossed && worse) worst = Crossing{&t, is_fail, int(i), infos[i].number, *v};
            }
            if (worst) out.push_back(*worst);
        }
    return out;
}

// run.json sequence: the two sequences, how frames were matched, and the motion the crawl took.
json sequenceJson(const ScoreSeqOptions& o, const SeqInputs& in, const Scored& s) {
    namespace k = rundir::run::sequence;
    namespace km = k::motion;
    json motion = {{km::kSource, in.motion_files.empty() ? "global shift" : "files"}};
    if (in.motion_files.empty())
        motion[km::kMethod] = "one translation per frame pair: phase correlation of the reference's luma (OpenCV "
                              "phaseCorrelate, Hann window), refined by Gauss-Newton steps on the sigma-1 blurred luma, "
                              "kept where it explains the reference's change better than no motion (else 0); no "
                              "disocclusion test (no depth)";
    else
        motion.update({{km::kFiles, o.motion}, {km::kScale, {in.motion_sx, in.motion_sy}},
                       {km::kConvention, "the first two channels x scale: the surface at pixel p of frame t was at p + "
                                         "motion in frame t-1, in pixels; no disocclusion test (no depth)"}});
    return {{k::kReference, o.reference},
            {k::kTest, o.test},
            {k::kFrames, in.reference.frames.size()},
            {k::kMatchedBy, in.reference.pattern && in.test.pattern ? "frame number" : "sorted name"},
            {k::kMotion, motion},
            {k::kCuts, o.cuts},
            {k::kConversions, s.conversions}};
}

// run.json thresholds: those given, those crossed, and the verdict.
json thresholdsJson(const std::vector<Crossing>& crossings, const std::vector<SeqThreshold>& warn,
                    const std::vector<SeqThreshold>& fail) {
    namespace k = rundir::run::thresholds;
    json th = {{k::kWarn, json::array()}, {k::kFail, json::array()}};
    for (const auto& t : warn) th[k::kWarn].push_back({{k::kMetric, t.metric}, {k::kValue, t.value}});
    for (const auto& t : fail) th[k::kFail].push_back({{k::kMetric, t.metric}, {k::kValue, t.value}});
    th[k::kCrossed] = json::array();
    for (const auto& c : crossings)
        th[k::kCrossed].push_back({{k::kMetric, c.threshold->metric}, {k::crossed::kThreshold, c.threshold->value},
                                   {k::crossed::kLevel, c.fail ? k::kFail : k::kWarn}, {k::crossed::kFrame, c.frame},
                                   {k::crossed::kFrameNumber, c.number}, {k::kValue, finiteOrNull(c.value)}});
    bool any_fail = false, any_warn = false;
    for (const auto& c : crossings) (c.fail ? any_fail : any_warn) = true;
    th[k::kVerdict] = any_fail ? "FAILURE" : any_warn ? "WARNING" : "PASS";
    return th;
}

json runJson(const ScoreSeqOptions& o, const SeqInputs& in, const Scored& s, const VariantSummary& sum,
             const std::vector<Crossing>& crossings, const std::vector<SeqThreshold>& warn,
             const std::vector<SeqThreshold>& fail, double seconds, const std::vector<WorstFrame>& worst) {
    using namespace rundir::run;
    namespace ks = rundir::run::settings;
    json j;
    j[kKind] = kScoreSeqKind;
    j[kTool] = {{tool::kName, "cbrbench"}, {tool::kVersion, CBR_VERSION}, {tool::kCommit, CBR_GIT_COMMIT}};
    j[kDate] = isoDate();
    j[kCommandLine] = o.argv;
    j[kHost] = hostJson();
    j[kWallSeconds] = seconds;
    const cbr::settings::Row& display = *cbr::settings::find("display");
    j[kSettings] = {{ks::kWidth, s.width},
                    {ks::kHeight, s.height},
                    {rundir::settingColumn("flip-ppd"), cbr::settings::flipPpd(o.tune)},
                    {display.column, cbr::settings::toJson(display, o.tune)},
                    {ks::kCvvdpFps, in.reference.frames.size() > 1 ? o.fps : 0.0},
                    {rundir::settingColumn("exposure"), o.exposure}};
    j[kScene] = {{rundir::run::scene::kName, "captured sequence"}};
    j[kPath] = {{rundir::run::path::kName, in.name}};
    j[kSequence] = sequenceJson(o, in, s);
    j[kThresholds] = thresholdsJson(crossings, warn, fail);
    namespace sum_k = sequence_summary;
    j[kSummary] = {{sum_k::kPsnrDb, finiteOrNull(sum.psnr_db)},
                   {sum_k::kPsnrDbIsInf, sum.psnr_db && std::isinf(*sum.psnr_db)},
                   {sum_k::kSsimMean, finiteOrNull(sum.ssim_mean)},
                   {sum_k::kFlipMean, finiteOrNull(sum.flip_mean)},
                   {sum_k::kCvvdpJod, finiteOrNull(sum.cvvdp_jod)},
                   {sum_k::kEci, finiteOrNull(sum.eci)},
                   {sum_k::kFlickerRatioMean, finiteOrNull(sum.flicker_ratio_mean)}};
    j[kVariants] = json::array({{{variant::kName, in.name}, {variant::kStatus, "ok"}}});
    j[kWorst] = worstJson(worst);
    return j;
}

std::string fmtValue(const std::optional<double>& v, int digits) {
    if (!v) return "-";
    if (std::isinf(*v)) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, *v);
    return b;
}

}  // namespace

int runScoreSeq(const ScoreSeqOptions& given) {
    ScoreSeqOptions o = given;
    const auto start = std::chrono::steady_clock::now();
    checkFlipPpd(o.flip_ppd);
    if (!(o.fps > 0 && std::isfinite(o.fps)))
        throw SequenceError(kSeqBadOption, "--fps " + std::to_string(o.fps) + ": accepted: a number > 0 (frames per second)");
    try {
        settings::setText(*settings::find("display"), o.tune, o.display);
    } catch (const std::invalid_argument& e) {
        throw SequenceError(kSeqBadOption, e.what());
    }
    o.tune.flip_ppd = o.flip_ppd;
    std::vector<SeqThreshold> warn, fail;
    for (const auto& w : o.warn) warn.push_back(parseSeqThreshold(w, "--warn"));
    for (const auto& f : o.fail) fail.push_back(parseSeqThreshold(f, "--fail"));
    const SeqInputs in = planInputs(o);
    const fs::path final_dir = o.out.empty() ? fs::path("out") / ("score-seq-" + timestampForName()) : fs::path(o.out);
    reports::OutputDir out(final_dir, o.replace);

    RunResults results;
    std::vector<SeqFrameInfo> infos;
    // The rows outlive the scorer and its workers: a frame that fails mid-sequence unwinds with
    // jobs still writing into rows, and the scorer's destructor waits for them first.
    SeqRows rows;
    WorkerPool workers(std::max(1u, std::thread::hardware_concurrency()));
    std::unique_ptr<QualityScorer> scorer;
    const Scored s = scoreFrames(o, in, rows, infos, scorer, workers);
    results.worst = scorer->finish(out.path());
    results.worst_files = worstFiles(results.worst);
    results.frames = int(rows.size());
    for (const auto& row : rows) results.digest.add(row);
    results.repeats = 1;
    VariantRun vr;
    vr.name = vr.variant = in.name;
    results.variants.push_back(vr);
    results.order = {in.name};
    const VariantSummary sum = summarize(results).at(0);
    const auto crossings = judge(warn, fail, rows, infos);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    writeSeqFramesCsv(out.path() / rundir::kFramesCsv, rows, infos, !in.motion_files.empty());
    writeSeqSummaryCsv(out.path() / rundir::kSummaryCsv, sum, s.width, s.height);
    reports::writeTextAtomically(out.path() / rundir::kRunJson,
                                 runJson(o, in, s, sum, crossings, warn, fail, seconds, results.worst).dump(2) + "\n");
    reports::writeReport(out.path());
    out.commit();

    std::printf("score-seq: %zu frames of %dx%d, %s against %s\n", rows.size(), s.width, s.height,
                in.name.c_str(), o.reference.c_str());
    std::printf("psnr_db %s (min %s)\nssim %s (min %s)\ncvvdp_jod %s\nflip_mean %s\neci %s (p95 %s, max %s)\n"
                "flicker_ratio %s\n",
                fmtValue(sum.psnr_db, 3).c_str(), fmtValue(sum.psnr_db_min, 3).c_str(),
                fmtValue(sum.ssim_mean, 5).c_str(), fmtValue(sum.ssim_min, 5).c_str(), fmtValue(sum.cvvdp_jod, 4).c_str(),
                fmtValue(sum.flip_mean, 5).c_str(), fmtValue(sum.eci, 5).c_str(), fmtValue(sum.eci_p95, 5).c_str(),
                fmtValue(sum.eci_max, 5).c_str(), fmtValue(sum.flicker_ratio_mean, 4).c_str());
    bool any_fail = false, any_warn = false;
    for (const auto& c : crossings) {
        (c.fail ? any_fail : any_warn) = true;
        std::printf("%s: %s %s at frame %ld beyond %s %s=%g\n", c.fail ? "FAILURE" : "WARNING", c.threshold->metric.c_str(),
                    fmtValue(c.value, 5).c_str(), c.number, c.fail ? "--fail" : "--warn", c.threshold->metric.c_str(),
                    c.threshold->value);
    }
    if (!warn.empty() || !fail.empty()) std::printf("%s\n", any_fail ? "FAILURE" : any_warn ? "WARNING" : "PASS");
    std::printf("output: %s\nreport: %s\n", out.finalPath().c_str(), (out.finalPath() / rundir::kReportHtml).c_str());
    return any_fail ? kSeqFail : any_warn ? kSeqWarn : kSeqPass;
}

}  // namespace cbr::harness
