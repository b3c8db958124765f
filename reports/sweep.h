// The sweep's analysis and page: sweep.csv in, a recommended CSO tolerance, quality at
// equal cost, and sweep.html out.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cbr::reports {

// One row of sweep.csv: a configuration and what it measured.
struct SweepPoint {
    std::string config;   // label, e.g. cbr-cso_tol=0.01_cost=4
    std::string variant;  // full, drr, cbr-aso, cbr-cso
    std::string status;   // ok, failed, skipped
    double shading_cost = 1;
    std::optional<double> drr_scale, cso_tolerance;
    std::optional<double> gpu_ms, gpu_ms_low, gpu_ms_high, speedup, speedup_low, speedup_high;
    std::optional<double> psnr_db, ssim, eci, flicker;
    std::map<std::string, double> classes;  // px_* mean shares
};

// The columns of sweep.csv, in order (the pixel classes follow).
const std::vector<std::string>& sweepColumns();

// Reads DIR/sweep.csv (and the run's run.json for the page's title). Throws
// std::invalid_argument naming the file and line for anything missing or malformed.
struct SweepData {
    std::filesystem::path dir;
    std::vector<SweepPoint> points;
    nlohmann::json run;
};
SweepData loadSweep(const std::filesystem::path& dir);

// The recommended CSO tolerance at one shading cost, with one sentence why: of the cbr-cso
// tolerances whose median GPU time stays within `margin` of cbr-aso's, those within
// 0.02 dB of the best sequence PSNR, of these the lowest ECI (within 1e-4), of these the
// loosest tolerance (the edge of the quality plateau).
struct ToleranceChoice {
    double shading_cost = 1;
    std::optional<double> tolerance;  // nullopt: no cbr-cso configuration ran
    std::string sentence;
};
inline constexpr double kCostMargin = 0.05;
std::vector<ToleranceChoice> recommendTolerance(const std::vector<SweepPoint>& points, double margin = kCostMargin);

// Quality at equal cost: the drr scale whose GPU time matches a checkerboard
// configuration's, interpolated linearly in time between the two swept scales around it.
struct EqualCost {
    std::string config;  // the checkerboard configuration
    double shading_cost = 1;
    double cbr_ms = 0;
    std::optional<double> cbr_psnr, cbr_ssim, cbr_eci;
    bool matched = false;  // its time lies within the swept drr times
    std::optional<double> drr_scale, drr_ms, drr_psnr, drr_ssim, drr_eci;
    std::string verdict;   // one sentence
};
std::vector<EqualCost> equalCost(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices);

// Builds sweep.html from DIR (same offline rules as report.html) and writes it atomically.
std::string sweepHtml(const std::filesystem::path& dir);
void writeSweepReport(const std::filesystem::path& dir);

}  // namespace cbr::reports
