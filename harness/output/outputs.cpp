// The run's result files from its frame rows, and the summary printed at the end.
#include "harness/output/outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "harness/output/frame_rows.h"
#include "harness/output/outputs_internal.h"
#include "harness/figures/stats.h"
#include "metrics/cvvdp.h"
#include "metrics/metrics.h"
#include "renderer/vk/context.h"
#include "reports/speedup.h"
#include "rundir/files.h"

namespace cbr::harness {
namespace {

// One configuration's times per repetition, and its paired ratios baseline / time per
// repetition, in row order (the bootstrap draws whole repetitions).
struct Repetitions {
    std::vector<std::vector<double>> per_rep, ratios;
};

// `baseline_ms`: the configuration's baseline's time per (repeat, frame), for paired ratios.
Repetitions repetitions(const VariantSamples& c, int repeats, const std::map<std::pair<int, int>, double>& baseline_ms) {
    Repetitions r;
    r.per_rep.resize(size_t(repeats));
    r.ratios.resize(size_t(repeats));
    for (size_t i = 0; i < c.ms.size(); ++i) {
        const size_t rep = size_t(c.repeat[i]);
        r.per_rep[rep].push_back(c.ms[i]);
        auto f = baseline_ms.find({c.repeat[i], c.frame[i]});
        if (f != baseline_ms.end() && c.ms[i] > 0) r.ratios[rep].push_back(f->second / c.ms[i]);
    }
    return r;
}

// Times: percentiles, noise across repetitions, and the speedup with its interval.
void timeStats(VariantSummary& s, const VariantSamples& c, const Repetitions& r, int repeats) {
    const auto& ms = c.ms;
    s.frames = int(ms.size()) / std::max(1, repeats);
    s.gpu_ms_median = median(ms);
    s.gpu_ms_p5 = percentile(ms, 5);
    s.gpu_ms_p95 = percentile(ms, 95);
    s.gpu_ms_p99 = percentile(ms, 99);
    s.gpu_ms_mean = mean(ms);
    std::vector<double> rep_medians;
    for (const auto& rep : r.per_rep)
        if (!rep.empty()) rep_medians.push_back(median(rep));
    s.noise_cv = coefficientOfVariation(rep_medians);
    {
        std::vector<std::vector<double>> rep_ms;
        for (const auto& rep : r.per_rep)
            if (!rep.empty()) rep_ms.push_back(rep);
        if (rep_ms.size() >= 2) {
            Interval ci = bootstrapMedianOverRuns(rep_ms);
            s.gpu_ms_ci_low = ci.low;
            s.gpu_ms_ci_high = ci.high;
        }
    }
    std::vector<double> pooled;
    std::vector<std::vector<double>> runs;
    for (const auto& rr : r.ratios)
        if (!rr.empty()) {
            pooled.insert(pooled.end(), rr.begin(), rr.end());
            runs.push_back(rr);
        }
    if (!pooled.empty()) {
        s.speedup = median(pooled);
        if (runs.size() >= 2) {
            Interval ci = bootstrapMedianOverRuns(runs);
            s.speedup_low = ci.low;
            s.speedup_high = ci.high;
        }
    }
}

// Quality over the sequence, render size, per-pass times and per-frame statistics.
void qualityStats(VariantSummary& s, const VariantSamples& c) {
    const auto& psnr = c.psnr;
    const auto& ssim = c.ssim;
    const auto& eci = c.eci;
    if (!c.mse.empty()) {
        // Sequence PSNR from the mean of the per-frame MSEs (metrics.md).
        s.psnr_db = metrics::psnrFromMse(mean(c.mse));
        s.psnr_db_min = *std::min_element(psnr.begin(), psnr.end());
        s.psnr_db_p5 = percentile(psnr, 5);
    }
    if (!ssim.empty()) {
        s.ssim_mean = mean(ssim);
        s.ssim_min = *std::min_element(ssim.begin(), ssim.end());
    }
    if (!c.ssim_luma.empty()) s.ssim_luma_mean = mean(c.ssim_luma);
    if (!c.flip.empty()) s.flip_mean = mean(c.flip);
    if (!c.cvvdp_q.empty()) s.cvvdp_jod = metrics::cvvdpJod(metrics::cvvdpPoolFrames(c.cvvdp_q));
    if (!eci.empty()) {
        // Sequence ECI pools numerators and denominators (metrics.md); crawl comes in
        // bursts, so p95 and max besides.
        s.eci = c.crawl_den > 0 ? std::sqrt(c.crawl_num / c.crawl_den) : 0.0;
        s.eci_p95 = percentile(eci, 95);
        s.eci_max = *std::max_element(eci.begin(), eci.end());
    }
    if (!c.flicker.empty()) s.flicker_ratio_mean = mean(c.flicker);
    if (!c.fs.empty()) s.fs_invocations_median = median(c.fs);
    s.render_width = uint32_t(median(c.widths));
    s.render_height = uint32_t(median(c.heights));
    for (const auto& name : c.pass_order) s.pass_ms_median.push_back({name, median(c.pass_ms.at(name))});
    for (const auto& name : c.stat_order) s.stats_mean.push_back({name, mean(c.stat_values.at(name))});
}

}  // namespace

std::vector<VariantSummary> summarize(const RunResults& r) {
    std::vector<VariantSummary> out;
    // Each baseline's (full's) per-(repeat, frame) times, for paired ratios; a sweep pairs
    // each configuration with the full configuration at its shading cost.
    std::map<std::string, std::map<std::pair<int, int>, double>> baseline_ms;
    for (const auto& vr : r.variants) baseline_ms[vr.baseline];
    for (auto& [name, times] : baseline_ms)
        if (const VariantSamples* b = r.digest.find(name))
            for (size_t i = 0; i < b->ms.size(); ++i) times[{b->repeat[i], b->frame[i]}] = b->ms[i];
    static const VariantSamples kNoRows;

    for (const auto& vr : r.variants) {
        VariantSummary s;
        s.variant = vr.name;
        s.status = vr.status;
        s.note = vr.note;
        const VariantSamples* found = r.digest.find(vr.name);
        const VariantSamples& c = found ? *found : kNoRows;
        if (c.ms.empty()) {
            if (s.status == "ok") s.status = "failed", s.note = "no frame completed";
            out.push_back(s);
            continue;
        }
        timeStats(s, c, repetitions(c, r.repeats, baseline_ms[vr.baseline]), r.repeats);
        qualityStats(s, c);
        out.push_back(s);
    }
    return out;
}

// frames.csv, summary.csv, run.json; the NaN cells of both tables are counted in run.json.
void writeOutputs(const std::filesystem::path& dir, const RunContext& rc) {
    const NanCells frames_nan = writeFramesCsv(dir / rundir::kFramesCsv, dir / kFramesSpill, rc.results.digest.columns);
    size_t nan_cells = reportNaNs(frames_nan.count, frames_nan.where, rundir::kFramesCsv);
    auto summaries = summarize(rc.results);
    nan_cells += writeSummaryCsv(dir / rundir::kSummaryCsv, rc.results, summaries);
    writeRunJson(dir / rundir::kRunJson, rc, summaries, nan_cells);
}

void printSummary(std::ostream& out, const std::filesystem::path& dir, const RunContext& rc) {
    auto summaries = summarize(rc.results);
    char line[512];
    int name_width = 10;  // a sweep's configuration labels are longer than variant names
    for (const auto& s : summaries) name_width = std::max(name_width, int(std::min<size_t>(s.variant.size(), 60)));
    // The speed-up as every output prints it, with its interval (reports/speedup.h).
    const char* kRow = "%-*s %-8s %9s %9s  %-18s %8s %7s %7s %7s %6s\n";
    std::snprintf(line, sizeof line, kRow, name_width, "variant", "status", "render", "gpu_ms", "speedup [95% CI]",
                  "psnr_db", "ssim", "flip", "eci", "jod");
    out << "cbrbench: " << rc.scene.name << " / " << rc.path.name << " at " << rc.settings.width << "x"
        << rc.settings.height << ", " << rc.results.frames << " frames x " << rc.results.repeats << " repeats on "
        << rc.ctx.description.name << "\n" << line;
    auto fmt = [](const std::optional<double>& v, const char* f) {
        if (!v) return std::string("-");
        if (std::isinf(*v)) return std::string("inf");
        char b[32];
        std::snprintf(b, sizeof b, f, *v);
        return std::string(b);
    };
    for (const auto& s : summaries) {
        std::string render = std::to_string(s.render_width) + "x" + std::to_string(s.render_height);
        const std::string speedup = reports::speedupText({s.speedup, s.speedup_low, s.speedup_high}, "-");
        std::snprintf(line, sizeof line, kRow, name_width, s.variant.c_str(), s.status.c_str(),
                      s.frames ? render.c_str() : "-",
                      s.frames ? fmt(s.gpu_ms_median, "%.3f").c_str() : "-", speedup.c_str(),
                      fmt(s.psnr_db, "%.2f").c_str(), fmt(s.ssim_mean, "%.4f").c_str(),
                      fmt(s.flip_mean, "%.4f").c_str(), fmt(s.eci, "%.4f").c_str(), fmt(s.cvvdp_jod, "%.2f").c_str());
        out << line;
    }
    auto& val = rc.ctx.validation;
    if (rc.ctx.validation_enabled)
        out << "validation messages: " << val.errors.load() + val.warnings.load() << " (" << val.errors.load()
            << " errors, " << val.warnings.load() << " warnings)\n";
    // A quiet run says nothing extra; a disturbed one says so in one line (run.json health).
    if (!rc.results.health.line.empty()) out << "cbrbench: " << rc.results.health.line << "\n";
    out << "report:  " << (dir / rundir::kReportHtml).string() << "\n";
    out << "results: " << dir.string() << "/ (summary.csv, frames.csv, run.json"
        << (rc.options.save_frames ? ", frames/" : "") << ")\n";
}

}  // namespace cbr::harness
