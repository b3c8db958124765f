// run.json's variants[] (one entry per variant or sweep configuration: what ran, the renderer's
// description of it, its headline numbers), worst[] and validation (docs/reference/outputs.md).
#pragma once

#include "rundir/frames_csv.h"
#include "rundir/summary_csv.h"

namespace cbr::rundir::run {

namespace variant {
inline constexpr const char* kName = "name";  // the configuration's label, as summary.csv's variant
inline constexpr const char* kStatus = "status";
inline constexpr const char* kNote = "note";  // a variant that failed, was skipped or is unsteady
inline constexpr const char* kPipeline = "pipeline";
inline constexpr const char* kPasses = "passes";
// Sweeps: the variant of a configuration, its swept settings by --param name, its speed-up's pair.
inline constexpr const char* kVariant = "variant";
inline constexpr const char* kSpeedupBaseline = "speedup_baseline";
inline constexpr const char* kSettings = "settings";
inline constexpr const char* kFrameAlignment = "frame_alignment";
inline constexpr const char* kResolveBandwidth = "resolve_bandwidth";  // checkerboard variants
// The headline numbers, summary.csv's where it has them.
inline constexpr const char* kGpuMsMedian = summary::kGpuMsMedian;
inline constexpr const char* kSpeedup = summary::kSpeedup;
inline constexpr const char* kSpeedupLow = summary::kSpeedupLow;
inline constexpr const char* kSpeedupHigh = summary::kSpeedupHigh;
inline constexpr const char* kPsnrDb = frames::kPsnrDb;  // null where infinite (then psnr_db_is_inf)
inline constexpr const char* kPsnrDbIsInf = "psnr_db_is_inf";
inline constexpr const char* kSsimMean = summary::kSsimMean;
inline constexpr const char* kFlipMean = summary::kFlipMean;
inline constexpr const char* kCvvdpJod = summary::kCvvdpJod;
inline constexpr const char* kEci = summary::kEci;
inline constexpr const char* kRenderWidth = summary::kRenderWidth;
inline constexpr const char* kRenderHeight = summary::kRenderHeight;

// The renderer's description of the variant (render::Renderer::describe, written with these
// names), each a string.
inline constexpr const char* kPipelineDetail = "pipeline_detail";
inline constexpr const char* kRoute = "route";
inline constexpr const char* kRouteReason = "route_reason";
inline constexpr const char* kQuarterResolution = "quarter_resolution";
inline constexpr const char* kRenderResolution = "render_resolution";
inline constexpr const char* kLodBias = "lod_bias";
inline constexpr const char* kOcclusionRule = "occlusion_rule";
inline constexpr const char* kMotion = "motion";
inline constexpr const char* kFill = "fill";
inline constexpr const char* kHistory = "history";
inline constexpr const char* kLostBorder = "lost_border";
inline constexpr const char* kResolve = "resolve";
inline constexpr const char* kResolveGroup = "resolve_group";
inline constexpr const char* kTonemap = "tonemap";
inline constexpr const char* kClassStats = "class_stats";
inline constexpr const char* kClassMap = "class_map";
inline constexpr const char* kResolveBytesPerFrame = "resolve_bytes_per_frame";
inline constexpr const char* kCsoTolerance = "cso_tolerance";
inline constexpr const char* kCsoMode = "cso_mode";
inline constexpr const char* kJitter = "jitter";
inline constexpr const char* kBlend = "blend";
inline constexpr const char* kReset = "reset";
inline constexpr const char* kDebugSlowdown = "debug_slowdown";  // --debug-slowdown only

namespace pass {  // variants[].passes[]
inline constexpr const char* kName = "name";
inline constexpr const char* kRan = "ran";
inline constexpr const char* kReason = "reason";  // why it did not run
}  // namespace pass

namespace frame_alignment {
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kPsnrDbSame = "psnr_db_same";
inline constexpr const char* kPsnrDbPrev = "psnr_db_prev";
inline constexpr const char* kPsnrDbNext = "psnr_db_next";
inline constexpr const char* kOk = "ok";
}  // namespace frame_alignment

namespace resolve_bandwidth {
inline constexpr const char* kPass = "pass";
inline constexpr const char* kMbPerFrame = "mb_per_frame";
inline constexpr const char* kPassMsMedian = "pass_ms_median";
inline constexpr const char* kGbPerS = "gb_per_s";
inline constexpr const char* kDeviceCopyGbPerS = "device_copy_gb_per_s";
inline constexpr const char* kFractionOfCopy = "fraction_of_copy";
inline constexpr const char* kRule = "rule";
}  // namespace resolve_bandwidth
}  // namespace variant

// worst[]: each variant's worst frame by SSIM and by ECI, and its images.
namespace worst {
inline constexpr const char* kVariant = "variant";
inline constexpr const char* kKind = "kind";  // kSsim or kEci
inline constexpr const char* kFrame = "frame";
inline constexpr const char* kValue = "value";
inline constexpr const char* kFiles = "files";  // by image: its PNG in worst/
inline constexpr const char* kPage = "page";    // by image: the report's copy in worst/page/
inline constexpr const char* kSsim = frames::kSsim;
inline constexpr const char* kEci = frames::kEci;
namespace image {  // the keys of files and page
inline constexpr const char* kReference = "reference";
inline constexpr const char* kVariant = "variant";
inline constexpr const char* kError = "error";
inline constexpr const char* kSsimMap = "ssim_map";
inline constexpr const char* kFlipMap = "flip_map";
inline constexpr const char* kCvvdpMap = "cvvdp_map";  // where ColorVideoVDP was scored
inline constexpr const char* kCrawlMap = "crawl_map";
inline constexpr const char* kClassMap = "class_map";  // checkerboard variants
inline constexpr const char* kAll[] = {kReference, kVariant, kError, kSsimMap, kFlipMap, kCvvdpMap, kCrawlMap, kClassMap};
}  // namespace image
}  // namespace worst

namespace validation {
inline constexpr const char* kEnabled = "enabled";
inline constexpr const char* kErrors = "errors";
inline constexpr const char* kWarnings = "warnings";
inline constexpr const char* kMessages = "messages";
inline constexpr const char* kFirstMessages = "first_messages";
}  // namespace validation

}  // namespace cbr::rundir::run
