// sweep.csv: one row per configuration of a sweep (docs/reference/outputs.md). The column names,
// and the ordered columns harness/output/outputs_csv.cpp writes and reports/sweep.cpp reads. The
// settings' columns are the settings table's.
#pragma once

#include <string>
#include <vector>

#include "rundir/frames_csv.h"
#include "rundir/summary_csv.h"
#include "settings/table.h"

namespace cbr::rundir::sweep {

inline constexpr const char* kConfig = "config";  // the label, also frames.csv's and summary.csv's variant
inline constexpr const char* kVariant = frames::kVariant;  // the variant table's row
inline constexpr const char* kPath = "path";
inline constexpr const char* kPipeline = "pipeline";
inline constexpr const char* kStatus = summary::kStatus;
inline constexpr const char* kNote = summary::kNote;
inline constexpr const char* kFrames = summary::kFrames;
inline constexpr const char* kRepeats = summary::kRepeats;
inline constexpr const char* kGpuMsMedian = summary::kGpuMsMedian;
inline constexpr const char* kGpuMsCiLow = "gpu_ms_ci_low";
inline constexpr const char* kGpuMsCiHigh = "gpu_ms_ci_high";
inline constexpr const char* kNoiseCv = "noise_cv";
inline constexpr const char* kSpeedup = summary::kSpeedup;
inline constexpr const char* kSpeedupLow = summary::kSpeedupLow;
inline constexpr const char* kSpeedupHigh = summary::kSpeedupHigh;
inline constexpr const char* kPsnrDb = frames::kPsnrDb;  // the sequence's PSNR
inline constexpr const char* kSsim = frames::kSsim;      // the mean SSIM
inline constexpr const char* kEci = frames::kEci;
inline constexpr const char* kFlickerRatio = frames::kFlickerRatio;  // the mean flicker ratio
inline constexpr const char* kCvvdpJod = frames::kCvvdpJod;

// The outer setting (a sweep per value) and the workload: the settings table's columns.
const char* referenceColumn();
const char* shadingCostColumn();

// The settings a sweep varies per configuration and writes a column each: the table's rows that
// sweep and name their variants, in its order.
const std::vector<const settings::Row*>& settingRows();

// The columns, in order: what ran, the settings, the status, the figures, the pixel classes.
const std::vector<std::string>& columns();
// The columns that hold words (the rest hold numbers or are empty).
bool isTextColumn(const std::string& column);

}  // namespace cbr::rundir::sweep
