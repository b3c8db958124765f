// The HTML report's sections, each a function of the loaded run (report.cpp assembles them).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reports/report_data.h"
#include "reports/svg.h"

namespace cbr::reports {

// report.cpp: the page around the sections (style and the small script), the same for
// every page the suite writes (report.html, compare.html, sweep.html).
std::string pageStart(const std::string& title);
std::string pageEnd();

// report.cpp: provenance, settings, the summary table, passes.
std::string provenanceSection(const RunData& d);
std::string summarySection(const RunData& d);
std::string passesSection(const RunData& d);

// report_charts.cpp: per-frame charts and the error-vs-time comparison.
std::string timeSection(const RunData& d);
std::string qualitySection(const RunData& d);
std::string pixelClassSection(const RunData& d);
std::string paretoSection(const RunData& d);

// report_sequence.cpp: the page of a score-seq folder (run.json kind "score-seq").
std::string sequenceReportHtml(const RunData& d);
// True for a score-seq folder.
bool isSequence(const RunData& d);

// report_images.cpp: worst-frame comparisons.
std::string imagesSection(const RunData& d);

// One variant's cost and quality, for the answer sentence.
struct CostQuality {
    std::string name;
    std::optional<double> gpu_ms;   // median frame GPU time
    std::optional<double> psnr_db;  // sequence PSNR (+inf: identical to the reference)
    std::optional<double> ssim;
    Speedup speedup;  // paired speed-up vs the reference and its 95% interval (reports/speedup.h)
    std::optional<double> jod;  // ColorVideoVDP's sequence JOD (reports/jod.h); the reference's is 10
};
// report_answer.cpp: ONE sentence: which variant gives the best quality for its cost. Quality
// is the JOD where a variant other than the reference has one, else the PSNR. The front is that
// of the paired speed-up against that quality (the plot's ringed points), every speed printed
// is the paired speed-up with its interval, and a variant counts as faster than the reference
// only where that interval, when there is one, lies above 1 (measurablyFaster; timing.md:
// report only significant differences).
std::string paretoSentence(const std::vector<CostQuality>& variants, const std::string& reference);
// The sentence for a loaded run.
std::string paretoSentence(const RunData& d);
// The run's sentence speaks in JOD (the page then says what a JOD is).
bool answersInJod(const RunData& d);

// Colour chips with names, above a chart.
std::string legendHtml(const std::vector<Series>& series, const std::string& extra = {});

// Pixel classes of the checkerboard reconstruction, in stacking order, with the class-map colours.
struct PixelClass {
    const char* column;  // frames.csv column (rundir/pixel_classes.h); summary.csv its statMean
    const char* label;
    const char* color;
};
// The colours are the class maps' (harness/quality/quality.cpp classColours), so legend and map agree.
inline constexpr PixelClass kPixelClasses[] = {
    {rundir::pixels::kShaded, "shaded", "#606060"},
    {rundir::pixels::kReused, "reused", "#28c83c"},
    {rundir::pixels::kMissingParity, "missing (parity)", "#f0dc28"},
    {rundir::pixels::kOccluded, "occluded", "#e62828"},
    {rundir::pixels::kOffscreen, "off-screen", "#285af0"},
    {rundir::pixels::kReset, "reset", "#dc3cdc"},
    {rundir::pixels::kClipped, "reused, clipped (full history)", "#28c8c8"},
};
}  // namespace cbr::reports
