// summary.csv and sweep.csv, on the run directory's schema (rundir/), documented in
// docs/reference/outputs.md; frames.csv is frame_rows.cpp's.
#include <cstdio>
#include <map>

#include "harness/output/outputs_internal.h"
#include "harness/jobs/sweep_configs.h"
#include "renderer/variants/variants.h"
#include "rundir/files.h"
#include "rundir/setting_columns.h"
#include "rundir/summary_csv.h"
#include "rundir/sweep_csv.h"
#include "settings/table.h"

namespace cbr::harness {

using reports::Cell;

size_t reportNaNs(size_t count, const std::vector<std::string>& where, const char* file) {
    if (count == 0) return 0;
    std::string list;
    for (const auto& w : where) list += (list.empty() ? "" : ", ") + w;
    std::fprintf(stderr, "cbrbench: warning: %zu non-finite value(s) written as empty cells in %s (%s)\n", count, file,
                 list.c_str());
    return count;
}

size_t reportNaNs(const reports::CsvTable& table, const char* file) {
    return reportNaNs(table.nanCells(), table.nanWhere(), file);
}

void summaryQualityCells(std::map<std::string, reports::Cell>& m, const VariantSummary& s) {
    using namespace rundir::summary;
    m[kPsnrDbMean] = optional(s.psnr_db);
    m[kPsnrDbMin] = optional(s.psnr_db_min);
    m[kPsnrDbP5] = optional(s.psnr_db_p5);
    m[kSsimMean] = optional(s.ssim_mean);
    m[kSsimMin] = optional(s.ssim_min);
    m[kSsimLumaMean] = optional(s.ssim_luma_mean);
    m[kFlipMean] = optional(s.flip_mean);
    m[kCvvdpJod] = optional(s.cvvdp_jod);
    m[kEci] = optional(s.eci);
    m[kEciP95] = optional(s.eci_p95);
    m[kEciMax] = optional(s.eci_max);
    m[kFlickerRatioMean] = optional(s.flicker_ratio_mean);
}

size_t writeSummaryCsv(const std::filesystem::path& file, const RunResults& r,
                       const std::vector<VariantSummary>& summaries) {
    using namespace rundir::summary;
    reports::CsvTable table(columns(r.digest.columns.passes, r.digest.columns.stats));
    for (const auto& s : summaries) {
        std::map<std::string, Cell> m;
        m[kVariant] = s.variant;
        m[kStatus] = s.status;
        m[kNote] = s.note;
        m[kRepeats] = r.repeats;
        if (s.frames > 0) {
            m[kFrames] = s.frames;
            m[kRenderWidth] = unsigned(s.render_width);
            m[kRenderHeight] = unsigned(s.render_height);
            m[kGpuMsMedian] = s.gpu_ms_median;
            m[kGpuMsP5] = s.gpu_ms_p5;
            m[kGpuMsP95] = s.gpu_ms_p95;
            m[kGpuMsP99] = s.gpu_ms_p99;
            m[kGpuMsMean] = s.gpu_ms_mean;
            m[kGpuMsCv] = s.noise_cv;
            m[kSpeedup] = optional(s.speedup);
            m[kSpeedupLow] = optional(s.speedup_low);
            m[kSpeedupHigh] = optional(s.speedup_high);
            summaryQualityCells(m, s);
            m[kFsInvocationsMedian] = optional(s.fs_invocations_median);
            for (const auto& [name, v] : s.pass_ms_median) m[passMedian(name)] = v;
            for (const auto& [name, v] : s.stats_mean) m[statMean(name)] = v;
        }
        table.addRow(m);
    }
    table.write(file);
    return reportNaNs(table, rundir::kSummaryCsv);
}

namespace {

// The settings of the variants they change: the swept value, else the run's own.
void sweepSettingCells(std::map<std::string, Cell>& row, const VariantRun& vr, const RunContext& rc) {
    // The swept rows of the variants they name (shading cost, for all, has a column of its own).
    for (const settings::Row* r : rundir::sweep::settingRows())
        if (settings::appliesTo(*r, vr.variant))
            row[r->column] = r->type == settings::Type::Word || r->type == settings::Type::Text
                                 ? Cell(settings::text(*r, rc.settings))
                                 : Cell(r->field.get(rc.settings));
    // A variant that keeps the full history whatever --cbr-history asks (the variant table).
    if (variants::findVariant(vr.variant).full_history) {
        const auto* history = settings::find("cbr-history");
        row[history->column] = std::string(history->words.at(size_t(settings::CbrHistory::Full)));
    }
    for (const auto& st : vr.settings) row[rundir::settingColumn(st.name)] = st.word.empty() ? Cell(st.value) : Cell(st.word);
}

}  // namespace

void writeSweepCsv(const std::filesystem::path& dir, const RunContext& rc) {
    using namespace rundir::sweep;
    const RunResults& r = rc.results;
    auto summaries = summarize(r);
    reports::CsvTable table(columns());
    for (size_t i = 0; i < r.variants.size(); ++i) {
        const auto& vr = r.variants[i];
        const auto& sm = summaries[i];
        std::map<std::string, Cell> row{{kConfig, vr.name},
                                        {kVariant, vr.variant},
                                        {kPath, sweepPathName(rc.options.path)},
                                        {referenceColumn(), settings::text(*settings::find("reference"), rc.options.tune)},
                                        {kPipeline, rc.settings.deferred ? "deferred" : "forward"},
                                        {shadingCostColumn(), rc.settings.shading_cost},
                                        {kStatus, sm.status},
                                        {kNote, sm.note},
                                        {kFrames, sm.frames},
                                        {kRepeats, r.repeats}};
        sweepSettingCells(row, vr, rc);
        if (sm.frames > 0) {
            row[kGpuMsMedian] = sm.gpu_ms_median;
            row[kGpuMsCiLow] = optional(sm.gpu_ms_ci_low);
            row[kGpuMsCiHigh] = optional(sm.gpu_ms_ci_high);
            row[kNoiseCv] = sm.noise_cv;
            row[kSpeedup] = optional(sm.speedup);
            row[kSpeedupLow] = optional(sm.speedup_low);
            row[kSpeedupHigh] = optional(sm.speedup_high);
            row[kPsnrDb] = optional(sm.psnr_db);
            row[kSsim] = optional(sm.ssim_mean);
            row[kCvvdpJod] = optional(sm.cvvdp_jod);
            row[kEci] = optional(sm.eci);
            row[kFlickerRatio] = optional(sm.flicker_ratio_mean);
            for (const auto& [name, value] : sm.stats_mean)
                for (const auto& col : columns())
                    if (col == name) row[name] = value;
        }
        table.addRow(row);
    }
    reportNaNs(table, rundir::kSweepCsv);
    table.write(dir / rundir::kSweepCsv);
}

}  // namespace cbr::harness
