// summary.csv: one row per variant or sweep configuration (docs/reference/outputs.md). The
// column names, and the ordered columns harness/output/outputs_csv.cpp writes; score-seq's
// summary.csv is a subset with the frame size.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "rundir/frames_csv.h"

namespace cbr::rundir::summary {

inline constexpr const char* kVariant = frames::kVariant;
inline constexpr const char* kStatus = frames::kStatus;  // ok, unsteady, failed, skipped
inline constexpr const char* kFrames = "frames";         // frames per repetition
inline constexpr const char* kRepeats = "repeats";
inline constexpr const char* kRenderWidth = frames::kRenderWidth;
inline constexpr const char* kRenderHeight = frames::kRenderHeight;
inline constexpr const char* kGpuMsMedian = "gpu_ms_median";
inline constexpr const char* kGpuMsP5 = "gpu_ms_p5";
inline constexpr const char* kGpuMsP95 = "gpu_ms_p95";
inline constexpr const char* kGpuMsP99 = "gpu_ms_p99";
inline constexpr const char* kGpuMsMean = "gpu_ms_mean";
inline constexpr const char* kGpuMsCv = "gpu_ms_cv";
// The one speed-up (docs/method/measurement.md) and its 95% interval; sweep.csv and run.json
// name them alike.
inline constexpr const char* kSpeedup = "speedup_vs_full";
inline constexpr const char* kSpeedupLow = "speedup_ci_low";
inline constexpr const char* kSpeedupHigh = "speedup_ci_high";
inline constexpr const char* kPsnrDbMean = "psnr_db_mean";
inline constexpr const char* kPsnrDbMin = "psnr_db_min";
inline constexpr const char* kPsnrDbP5 = "psnr_db_p5";
inline constexpr const char* kSsimMean = "ssim_mean";
inline constexpr const char* kSsimMin = "ssim_min";
inline constexpr const char* kSsimLumaMean = "ssim_luma_mean";
inline constexpr const char* kFlipMean = frames::kFlipMean;  // the mean of the frames' means
inline constexpr const char* kCvvdpJod = frames::kCvvdpJod;  // the sequence's JOD
inline constexpr const char* kEci = frames::kEci;            // the sequence's pooled ECI
inline constexpr const char* kEciP95 = "eci_p95";
inline constexpr const char* kEciMax = "eci_max";
inline constexpr const char* kFlickerRatioMean = "flicker_ratio_mean";
inline constexpr const char* kFsInvocationsMedian = "fs_invocations_median";
inline constexpr const char* kNote = frames::kNote;
inline constexpr const char* kWidth = frames::kWidth;  // score-seq's: the frame size
inline constexpr const char* kHeight = frames::kHeight;

// gpu_ms_<pass>_median: one pass's median time; <stat>_mean: a frame statistic's mean
// (px_<class>_mean).
std::string passMedian(std::string_view pass);
std::string statMean(std::string_view stat);

// The columns, in order: the fixed ones, then each pass's median, then each statistic's mean.
const std::vector<std::string>& fixedColumns();
std::vector<std::string> columns(const std::vector<std::string>& passes, const std::vector<std::string>& stats);
// score-seq's summary.csv, in order.
const std::vector<std::string>& sequenceColumns();

}  // namespace cbr::rundir::summary
