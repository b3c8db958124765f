// frames.csv, summary.csv and sweep.csv: one schema each, documented in docs/reference/outputs.md.
#include <algorithm>
#include <cstdio>
#include <map>

#include "harness/output/outputs_internal.h"
#include "harness/jobs/sweep_configs.h"
#include "renderer/variants/variants.h"
#include "reports/sweep.h"
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
    m["psnr_db_mean"] = optional(s.psnr_db);
    m["psnr_db_min"] = optional(s.psnr_db_min);
    m["psnr_db_p5"] = optional(s.psnr_db_p5);
    m["ssim_mean"] = optional(s.ssim_mean);
    m["ssim_min"] = optional(s.ssim_min);
    m["ssim_luma_mean"] = optional(s.ssim_luma_mean);
    m["flip_mean"] = optional(s.flip_mean);
    m["cvvdp_jod"] = optional(s.cvvdp_jod);
    m["eci"] = optional(s.eci);
    m["eci_p95"] = optional(s.eci_p95);
    m["eci_max"] = optional(s.eci_max);
    m["flicker_ratio_mean"] = optional(s.flicker_ratio_mean);
}

size_t writeSummaryCsv(const std::filesystem::path& file, const RunResults& r,
                       const std::vector<VariantSummary>& summaries) {
    const std::vector<std::string>& passes = r.digest.columns.passes;
    std::vector<std::string> cols = {"variant",        "status",         "frames",          "repeats",
                                     "render_width",   "render_height",  "gpu_ms_median",   "gpu_ms_p5",
                                     "gpu_ms_p95",     "gpu_ms_p99",     "gpu_ms_mean",     "gpu_ms_cv",
                                     "speedup_vs_full", "speedup_ci_low", "speedup_ci_high", "psnr_db_mean",
                                     "psnr_db_min",    "psnr_db_p5",     "ssim_mean",       "ssim_min",
                                     "ssim_luma_mean", "flip_mean",      "cvvdp_jod",       "eci",
                                     "eci_p95",
                                     "eci_max",
                                     "flicker_ratio_mean", "fs_invocations_median", "note"};
    for (const auto& p : passes) cols.push_back("gpu_ms_" + p + "_median");
    for (const auto& st : r.digest.columns.stats) cols.push_back(st + "_mean");
    reports::CsvTable table(cols);
    for (const auto& s : summaries) {
        std::map<std::string, Cell> m;
        m["variant"] = s.variant;
        m["status"] = s.status;
        m["note"] = s.note;
        m["repeats"] = r.repeats;
        if (s.frames > 0) {
            m["frames"] = s.frames;
            m["render_width"] = unsigned(s.render_width);
            m["render_height"] = unsigned(s.render_height);
            m["gpu_ms_median"] = s.gpu_ms_median;
            m["gpu_ms_p5"] = s.gpu_ms_p5;
            m["gpu_ms_p95"] = s.gpu_ms_p95;
            m["gpu_ms_p99"] = s.gpu_ms_p99;
            m["gpu_ms_mean"] = s.gpu_ms_mean;
            m["gpu_ms_cv"] = s.noise_cv;
            m["speedup_vs_full"] = optional(s.speedup);
            m["speedup_ci_low"] = optional(s.speedup_low);
            m["speedup_ci_high"] = optional(s.speedup_high);
            summaryQualityCells(m, s);
            m["fs_invocations_median"] = optional(s.fs_invocations_median);
            for (const auto& [name, v] : s.pass_ms_median) m["gpu_ms_" + name + "_median"] = v;
            for (const auto& [name, v] : s.stats_mean) m[name + "_mean"] = v;
        }
        table.addRow(m);
    }
    table.write(file);
    return reportNaNs(table, "summary.csv");
}

namespace {

// The settings of the variants they change: the swept value, else the run's own.
void sweepSettingCells(std::map<std::string, Cell>& row, const VariantRun& vr, const RunContext& rc) {
    // The swept rows of the variants they name (shading cost, for all, has a column of its own).
    for (const auto& r : settings::table())
        if (r.sweep && !r.variants.empty() && settings::appliesTo(r, vr.variant))
            row[r.column] = r.type == settings::Type::Word || r.type == settings::Type::Text ? Cell(settings::text(r, rc.settings)) : Cell(r.field.get(rc.settings));
    // A variant that keeps the full history whatever --cbr-history asks (the variant table).
    if (variants::findVariant(vr.variant).full_history) row["cbr_history"] = std::string("full");
    for (const auto& st : vr.settings) {
        std::string column = st.name;
        std::replace(column.begin(), column.end(), '-', '_');
        row[column] = st.word.empty() ? Cell(st.value) : Cell(st.word);
    }
}


}  // namespace

void writeSweepCsv(const std::filesystem::path& dir, const RunContext& rc) {
    const RunResults& r = rc.results;
    auto summaries = summarize(r);
    reports::CsvTable table(reports::sweepColumns());
    for (size_t i = 0; i < r.variants.size(); ++i) {
        const auto& vr = r.variants[i];
        const auto& sm = summaries[i];
        std::map<std::string, Cell> row{{"config", vr.name},
                                        {"variant", vr.variant},
                                        {"path", sweepPathName(rc.options.path)},
                                        {"reference", settings::text(*settings::find("reference"), rc.options.tune)},
                                        {"pipeline", rc.settings.deferred ? "deferred" : "forward"},
                                        {"shading_cost", rc.settings.shading_cost},
                                        {"status", sm.status},
                                        {"note", sm.note},
                                        {"frames", sm.frames},
                                        {"repeats", r.repeats}};
        sweepSettingCells(row, vr, rc);
        if (sm.frames > 0) {
            row["gpu_ms_median"] = sm.gpu_ms_median;
            row["gpu_ms_ci_low"] = optional(sm.gpu_ms_ci_low);
            row["gpu_ms_ci_high"] = optional(sm.gpu_ms_ci_high);
            row["noise_cv"] = sm.noise_cv;
            row["speedup_vs_full"] = optional(sm.speedup);
            row["speedup_ci_low"] = optional(sm.speedup_low);
            row["speedup_ci_high"] = optional(sm.speedup_high);
            row["psnr_db"] = optional(sm.psnr_db);
            row["ssim"] = optional(sm.ssim_mean);
            row["cvvdp_jod"] = optional(sm.cvvdp_jod);
            row["eci"] = optional(sm.eci);
            row["flicker_ratio"] = optional(sm.flicker_ratio_mean);
            for (const auto& [name, value] : sm.stats_mean)
                for (const auto& col : reports::sweepColumns())
                    if (col == name) row[name] = value;
        }
        table.addRow(row);
    }
    reportNaNs(table, "sweep.csv");
    table.write(dir / "sweep.csv");
}

}  // namespace cbr::harness
