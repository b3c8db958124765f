// The run directory's file and folder names: what `cbrbench run` (and score-seq) write, and
// what the report, sweep, export, compare and merge open (docs/reference/outputs.md).
#pragma once

namespace cbr::rundir {

inline constexpr const char* kFramesCsv = "frames.csv";    // one row per variant, repetition and frame
inline constexpr const char* kSummaryCsv = "summary.csv";  // one row per variant
inline constexpr const char* kRunJson = "run.json";        // provenance, settings, headline numbers
inline constexpr const char* kSweepCsv = "sweep.csv";      // a sweep's configurations
inline constexpr const char* kReportHtml = "report.html";
inline constexpr const char* kSweepHtml = "sweep.html";
inline constexpr const char* kWorstDir = "worst";          // the worst frames' images
inline constexpr const char* kWorstPageDir = "page";       // worst/page/: the report's smaller copies
inline constexpr const char* kFramesDir = "frames";        // --save-frames

}  // namespace cbr::rundir
