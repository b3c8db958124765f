// The run's files: frames.csv, summary.csv, run.json, and the summary printed at the end.
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "camera_paths/path.h"
#include "harness/jobs/builtin_context.h"
#include "harness/jobs/options.h"
#include "harness/figures/results.h"
#include "harness/base/wall_account.h"
#include "renderer/scene/scene.h"

namespace cbr::vk {
class Context;
}

namespace cbr::harness {

struct RunContext {
    const RunOptions& options;
    const render::Settings& settings;
    const scene::Scene& scene;
    const paths::CameraPath& path;
    const std::vector<double>& times;
    const std::vector<paths::CameraPose>& poses;
    vk::Context& ctx;
    const RunResults& results;
    const PathPlacement* placement = nullptr;  // run.json path.placement, when known
    const WallAccount* wall = nullptr;         // run.json wall, when the run kept one
};

// One row per variant, computed from the frame rows (also used by the printed summary).
struct VariantSummary {
    std::string variant;
    std::string status;
    std::string note;
    int frames = 0;
    double gpu_ms_median = 0, gpu_ms_p5 = 0, gpu_ms_p95 = 0, gpu_ms_p99 = 0, gpu_ms_mean = 0;
    double noise_cv = 0;  // across repetitions, of each repetition's median
    std::optional<double> gpu_ms_ci_low, gpu_ms_ci_high;  // 95% bootstrap interval of the median over repetitions
    std::optional<double> speedup, speedup_low, speedup_high;
    std::optional<double> psnr_db, psnr_db_min, psnr_db_p5, ssim_mean, ssim_min, ssim_luma_mean;
    std::optional<double> eci, eci_p95, eci_max, flicker_ratio_mean;
    std::optional<double> flip_mean;  // mean of the per-frame FLIP means
    std::optional<double> cvvdp_jod;  // ColorVideoVDP of the sequence: the frames' q pooled, in JOD
    std::optional<double> fs_invocations_median;
    uint32_t render_width = 0, render_height = 0;
    std::vector<std::pair<std::string, double>> pass_ms_median;
    std::vector<std::pair<std::string, double>> stats_mean;  // e.g. px_reused over all frames
};

std::vector<VariantSummary> summarize(const RunResults& results);
void writeOutputs(const std::filesystem::path& dir, const RunContext& rc);
// Rewrites run.json's wall account (and wall_seconds) once the report is written.
void updateRunJsonWall(const std::filesystem::path& dir, const RunContext& rc);
// sweep.csv: one row per configuration (rundir/sweep_csv.h columns()).
void writeSweepCsv(const std::filesystem::path& dir, const RunContext& rc);
void printSummary(std::ostream& out, const std::filesystem::path& dir, const RunContext& rc);

}  // namespace cbr::harness
