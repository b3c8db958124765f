// The HTML report's sections, each a function of the loaded run (report.cpp assembles them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reports/report_data.h"
#include "reports/svg.h"

namespace cbr::reports {

// report.cpp: provenance, settings, the summary table, passes.
std::string provenanceSection(const RunData& d);
std::string summarySection(const RunData& d);
std::string passesSection(const RunData& d);

// report_charts.cpp: per-frame charts and the error-vs-time comparison.
std::string timeSection(const RunData& d);
std::string qualitySection(const RunData& d);
std::string pixelClassSection(const RunData& d);
std::string paretoSection(const RunData& d);

// report_images.cpp: worst-frame comparisons.
std::string imagesSection(const RunData& d);

// One variant's cost and quality, for the answer sentence.
struct CostQuality {
    std::string name;
    std::optional<double> gpu_ms;  // median frame GPU time
    std::optional<double> psnr_db;  // sequence PSNR (+inf: identical to the reference)
    std::optional<double> ssim;
};
// ONE sentence: which variant gives the best quality (PSNR) for its cost, judged on the
// same axes as the plot (median GPU ms; speed = full's median / the variant's).
std::string paretoSentence(const std::vector<CostQuality>& variants);
// The sentence for a loaded run.
std::string paretoSentence(const RunData& d);

// Colour chips with names, above a chart.
std::string legendHtml(const std::vector<Series>& series, const std::string& extra = {});

// Pixel classes of the checkerboard reconstruction, in stacking order, with the class-map colours.
struct PixelClass {
    const char* column;  // frames.csv column; summary.csv adds "_mean"
    const char* label;
    const char* color;
};
inline constexpr PixelClass kPixelClasses[] = {
    {"px_shaded", "shaded", "#9e9e9e"},          {"px_reused", "reused", "#2ca02c"},
    {"px_missing_parity", "missing (parity)", "#e6c700"}, {"px_occluded", "occluded", "#d62728"},
    {"px_offscreen", "off-screen", "#1f77b4"},   {"px_reset", "reset", "#e377c2"},
};

}  // namespace cbr::reports
