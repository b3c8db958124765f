// The sweep's analysis and page: sweep.csv in, a recommended value per swept setting, quality
// at equal cost, and sweep.html out (or, for a sweep over outer dimensions, an index page).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/speedup.h"
#include "reports/status.h"
#include "reports/variant_roles.h"

namespace cbr::reports {

// One row of sweep.csv: a configuration and what it measured.
struct SweepPoint {
    std::string config;   // label, e.g. cbr-cso_tol=0.01_cost=4
    std::string variant;  // a row of the variant table: full, drr, cbr-aso, cbr-cso, taau
    std::string status;   // ok, unsteady, failed, skipped
    bool hasTimes() const { return statusHasTimes(status); }  // ran and has times (ok or unsteady)
    std::string path, reference;  // the outer dimensions: one sweep per (path, reference)
    double shading_cost = 1;
    // The settings of the variants they change, by sweep.csv column (absent on the others' rows):
    // every row of the settings table that sweeps per variant (sweepSettingFields()).
    std::map<std::string, double> numbers;
    std::map<std::string, std::string> words;
    std::optional<double> number(const std::string& column) const {
        auto it = numbers.find(column);
        return it == numbers.end() ? std::nullopt : std::optional<double>(it->second);
    }
    std::optional<double> gpu_ms, gpu_ms_low, gpu_ms_high;
    Speedup speedup;  // paired against the full configuration at its shading cost (reports/speedup.h)
    std::optional<double> psnr_db, ssim, eci, flicker;
    std::optional<double> jod;  // ColorVideoVDP's sequence JOD (cvvdp_jod, reports/jod.h); older sweeps: none
    std::map<std::string, double> classes;  // px_* mean shares
};

// The settings a sweep can vary per configuration (shading cost is the workload, not a
// choice): the settings table's rows that sweep and name their variants, in its order, with
// their sweep.csv column and whether they hold a number or a word.
struct SweepSettingField {
    const char* name;    // as --param names it, e.g. cbr-lod-bias
    const char* column;  // e.g. cbr_lod_bias
    bool number;         // a number (SweepPoint::numbers), else a word (SweepPoint::words)
};
const std::vector<SweepSettingField>& sweepSettingFields();
const SweepSettingField* findSweepSetting(const std::string& name);
// The point's value of a setting as labels write it; nullopt where the setting does not apply.
std::optional<std::string> settingText(const SweepPoint& p, const SweepSettingField& f);

// The subdirectory of one (path, reference) sweep of a sweep over outer dimensions:
// "orbit", "ref=ssaa" or "orbit_ref=ssaa", naming only the dimensions that vary.
std::string sweepGroupDir(const std::string& path, const std::string& reference, bool paths_vary, bool references_vary);

// Reads DIR/sweep.csv (and the run's run.json for the page's title). Throws
// std::invalid_argument naming the file and line for anything missing or malformed.
struct SweepData {
    std::filesystem::path dir;
    std::vector<SweepPoint> points;
    nlohmann::json run;
};
SweepData loadSweep(const std::filesystem::path& dir);

// The quality every recommendation and equal-cost comparison of a sweep ranks by, higher
// being better: ColorVideoVDP's JOD where any configuration has one (reports/jod.h), else
// the sequence PSNR (a sweep from before ColorVideoVDP, or one that did not score it).
bool sweepRanksByJod(const std::vector<SweepPoint>& points);

// The recommended CSO tolerance at one shading cost, with one sentence why: of the
// tolerances (cbr-cso's) whose median GPU time stays within `margin` of the time of the
// variant's cost bound (VariantRole::cost_bound, cbr-aso), those within
// 0.02 dB of the best sequence PSNR (0.02 JOD of the best JOD), of these the lowest ECI
// (within 1e-4), of these the loosest tolerance (the edge of the quality plateau).
struct ToleranceChoice {
    double shading_cost = 1;
    std::optional<double> tolerance;  // nullopt: no cbr-cso configuration ran
    std::string sentence;
};
inline constexpr double kCostMargin = 0.05;
std::vector<ToleranceChoice> recommendTolerance(const std::vector<SweepPoint>& points, const VariantRoles& roles,
                                                double margin = kCostMargin);

// The recommended value of every swept setting (two or more values among the rows it
// applies to), per path, reference and shading cost; kSettingRule says how, in one sentence.
struct SettingChoice {
    std::string path, reference;
    double shading_cost = 1;
    std::string setting;   // e.g. cbr-lod-bias
    std::string value;     // as labels write it, e.g. -1
    std::string config;    // the configuration it was read from
    std::string sentence;  // one sentence why
};
std::string settingRule(const VariantRoles& roles, bool jod = false);
std::vector<SettingChoice> recommendSettings(const std::vector<SweepPoint>& points, const VariantRoles& roles,
                                             double margin = kCostMargin);

// One line per setting whose recommended value differs between paths at the same
// reference and shading cost, e.g. "the recommended cbr-lod-bias differs between paths: -1
// on flythrough, -0.5 on orbit; ...". Empty when they agree or only one path ran.
std::vector<std::string> pathDisagreements(const std::vector<SettingChoice>& choices);

// What `cbrbench sweep` prints after the runs: the recommendations, the rule, the
// disagreements (as "warning: ..."), and quality at equal cost. One line each.
std::vector<std::string> sweepSummaryLines(const std::vector<SweepPoint>& points, const VariantRoles& roles);

// Quality at equal cost: for each variant whose VariantRole::equal_cost_with names a scaled
// variant (drr), the scale whose GPU time matches its configuration's, interpolated linearly
// in time between the two swept scales around it. The verdict compares JODs where the sweep
// has them (sweepRanksByJod), else PSNRs.
struct EqualCost {
    std::string config;  // the checkerboard configuration
    double shading_cost = 1;
    double cbr_ms = 0;
    std::optional<double> cbr_psnr, cbr_ssim, cbr_eci, cbr_jod;
    bool matched = false;  // its time lies within the swept drr times
    std::optional<double> drr_scale, drr_ms, drr_psnr, drr_ssim, drr_eci, drr_jod;
    std::string verdict;   // one sentence
};
std::vector<EqualCost> equalCost(const std::vector<SweepPoint>& points, const std::vector<ToleranceChoice>& choices,
                                 const VariantRoles& roles);

// Builds sweep.html from DIR (same offline rules as report.html) and writes it atomically.
// A directory whose sweep.csv holds more than one (path, reference) sweep gets the index
// page: the recommendations side by side, disagreements between paths, links to each.
std::string sweepHtml(const std::filesystem::path& dir, const VariantRoles& roles);
std::string sweepIndexHtml(const std::filesystem::path& dir, const VariantRoles& roles);
void writeSweepReport(const std::filesystem::path& dir, const VariantRoles& roles);

// DIR/sweep.csv from DIR/<sub>/sweep.csv for each of `subdirs`, rows in that order (the
// columns are the same: each row names its path and reference). Written atomically.
void combineSweeps(const std::filesystem::path& dir, const std::vector<std::string>& subdirs);

}  // namespace cbr::reports
