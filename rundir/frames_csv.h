// frames.csv: one row per variant, repetition and frame (docs/reference/outputs.md). The column
// names, and the ordered columns harness/output/frame_rows.cpp writes; score-seq's frames.csv
// shares the quality columns and adds its own.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace cbr::rundir::frames {

inline constexpr const char* kVariant = "variant";  // in a sweep: the configuration's label
inline constexpr const char* kRepeat = "repeat";
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kTimeS = "time_s";
inline constexpr const char* kWidth = "width";
inline constexpr const char* kHeight = "height";
inline constexpr const char* kRenderWidth = "render_width";
inline constexpr const char* kRenderHeight = "render_height";
inline constexpr const char* kRenderScale = "render_scale";
inline constexpr const char* kGpuMs = "gpu_ms";
inline constexpr const char* kTimingOk = "timing_ok";
inline constexpr const char* kPsnrDb = "psnr_db";
inline constexpr const char* kSsim = "ssim";
inline constexpr const char* kSsimLuma = "ssim_luma";
inline constexpr const char* kMse = "mse";
inline constexpr const char* kEci = "eci";
inline constexpr const char* kFlickerRatio = "flicker_ratio";
inline constexpr const char* kCrawlValidFraction = "crawl_valid_fraction";
inline constexpr const char* kFlipMean = "flip_mean";
inline constexpr const char* kFlipQ1 = "flip_q1";
inline constexpr const char* kFlipMedian = "flip_median";
inline constexpr const char* kFlipQ3 = "flip_q3";
inline constexpr const char* kCvvdpJod = "cvvdp_jod";
inline constexpr const char* kFsInvocations = "fs_invocations";
inline constexpr const char* kStatus = "status";  // ok, failed, skipped (summary.csv adds unsteady)
inline constexpr const char* kNote = "note";

// score-seq's frames.csv: the files of each frame and the motion the edge crawl took.
inline constexpr const char* kFrameNumber = "frame_number";
inline constexpr const char* kReferenceFile = "reference_file";
inline constexpr const char* kTestFile = "test_file";
inline constexpr const char* kMotion = "motion";
inline constexpr const char* kShiftDx = "shift_dx";
inline constexpr const char* kShiftDy = "shift_dy";
inline constexpr const char* kShiftResponse = "shift_response";
inline constexpr const char* kGlobalShiftRejected = "global_shift_rejected";
inline constexpr const char* kCut = "cut";

// gpu_ms_<pass>: one pass's GPU time; fs_invocations_<pass>: its fragment-shader invocations.
inline constexpr std::string_view kPassTimePrefix = "gpu_ms_";
std::string passTime(std::string_view pass);
std::string passInvocations(std::string_view pass);
// The pass of a gpu_ms_<pass> column; empty for any other column.
std::string passOfColumn(std::string_view column);

// The columns every run writes, in order; then come the frame statistics (px_<class>), the
// passes' times and the invocations of the passes that report them (columns()).
const std::vector<std::string>& fixedColumns();
std::vector<std::string> columns(const std::vector<std::string>& stats, const std::vector<std::string>& passes,
                                 const std::set<std::string>& passes_with_invocations);
// score-seq's frames.csv, in order.
const std::vector<std::string>& sequenceColumns();

}  // namespace cbr::rundir::frames
