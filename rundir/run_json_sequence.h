// run.json of score-seq (kind "score-seq"): the run's keys where they mean the same (tool, date,
// host, settings, scene and path names, variants[], worst[]), and its own: the sequences, the
// thresholds and the summary.
#pragma once

#include "rundir/run_json.h"
#include "rundir/run_json_variants.h"
#include "rundir/summary_csv.h"

namespace cbr::rundir::run {

inline constexpr const char* kKind = "kind";  // absent in a run's run.json
inline constexpr const char* kScoreSeqKind = "score-seq";
inline constexpr const char* kSequence = "sequence";
inline constexpr const char* kThresholds = "thresholds";
inline constexpr const char* kSummary = "summary";

namespace sequence {
inline constexpr const char* kReference = "reference";
inline constexpr const char* kTest = "test";
inline constexpr const char* kFrames = "frames";
inline constexpr const char* kMatchedBy = "matched_by";
inline constexpr const char* kMotion = "motion";
inline constexpr const char* kCuts = "cuts";
inline constexpr const char* kConversions = "conversions";
namespace motion {
inline constexpr const char* kSource = "source";
inline constexpr const char* kMethod = "method";          // the global shift's
inline constexpr const char* kFiles = "files";            // --motion's
inline constexpr const char* kScale = "scale";            // --motion's
inline constexpr const char* kConvention = "convention";  // --motion's
}  // namespace motion
}  // namespace sequence

namespace thresholds {
inline constexpr const char* kWarn = "warn";
inline constexpr const char* kFail = "fail";
inline constexpr const char* kCrossed = "crossed";
inline constexpr const char* kVerdict = "verdict";
inline constexpr const char* kMetric = "metric";  // warn[], fail[] and crossed[]
inline constexpr const char* kValue = "value";    // warn[], fail[] and crossed[]
namespace crossed {
inline constexpr const char* kThreshold = "threshold";
inline constexpr const char* kLevel = "level";  // kWarn or kFail
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kFrameNumber = "frame_number";
}  // namespace crossed
}  // namespace thresholds

namespace sequence_summary {  // score-seq's summary: summary.csv's figures
inline constexpr const char* kPsnrDb = variant::kPsnrDb;
inline constexpr const char* kPsnrDbIsInf = variant::kPsnrDbIsInf;
inline constexpr const char* kSsimMean = summary::kSsimMean;
inline constexpr const char* kFlipMean = summary::kFlipMean;
inline constexpr const char* kCvvdpJod = summary::kCvvdpJod;
inline constexpr const char* kEci = summary::kEci;
inline constexpr const char* kFlickerRatioMean = summary::kFlickerRatioMean;
}  // namespace sequence_summary

}  // namespace cbr::rundir::run
