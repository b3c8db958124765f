// run.json's health (warm-up, drift and the machine while frames were timed, with the rule they
// were judged by), wall (where the wall time went) and memory (what the run needed and had).
#pragma once

#include <cstddef>
#include <iterator>

namespace cbr::rundir::run {

namespace health {
inline constexpr const char* kQuiet = "quiet";
inline constexpr const char* kBusy = "busy";
inline constexpr const char* kUnsteady = "unsteady";
inline constexpr const char* kStatusGate = "status_gate";
inline constexpr const char* kLine = "line";
inline constexpr const char* kDisturbances = "disturbances";
inline constexpr const char* kVariants = "variants";
inline constexpr const char* kMachine = "machine";
inline constexpr const char* kRule = "rule";
namespace variant {  // health.variants[], in run order
inline constexpr const char* kName = "name";
inline constexpr const char* kWarmUpFrames = "warm_up_frames";
inline constexpr const char* kWarmUpCapped = "warm_up_capped";
inline constexpr const char* kDrift = "drift";
inline constexpr const char* kOtherCoresMax = "other_cores_max";
inline constexpr const char* kUnsteady = "unsteady";
inline constexpr const char* kNote = "note";
}  // namespace variant
namespace drift {  // health.variants[].drift
inline constexpr const char* kTested = "tested";
inline constexpr const char* kUnsteady = "unsteady";
inline constexpr const char* kWhyNot = "why_not";
inline constexpr const char* kNoise = "noise";
inline constexpr const char* kRepetitionRatios = "repetition_ratios";
inline constexpr const char* kLevelLimit = "level_limit";
inline constexpr const char* kSpanLimit = "span_limit";
inline constexpr const char* kLevelMax = "level_max";
inline constexpr const char* kSpanMax = "span_max";
inline constexpr const char* kLargest = "largest";
namespace largest {
inline constexpr const char* kRepetition = "repetition";
inline constexpr const char* kFirstFrame = "first_frame";
inline constexpr const char* kLastFrame = "last_frame";
inline constexpr const char* kRatio = "ratio";
inline constexpr const char* kWholeRepetition = "whole_repetition";
}  // namespace largest
}  // namespace drift
namespace machine {
inline constexpr const char* kCpu = "cpu";
inline constexpr const char* kGpu = "gpu";
inline constexpr const char* kTimestampDeviationNs = "timestamp_deviation_ns";
inline constexpr const char* kSamples = "samples";
inline constexpr const char* kSampleIntervalS = "sample_interval_s";
namespace cpu {
inline constexpr const char* kCores = "cores";
inline constexpr const char* kOwnCores = "own_cores";
inline constexpr const char* kOwnShare = "own_share";
inline constexpr const char* kOtherCores = "other_cores";
inline constexpr const char* kOtherCoresMax = "other_cores_max";
inline constexpr const char* kStealCores = "steal_cores";
inline constexpr const char* kMhzBefore = "mhz_before";
inline constexpr const char* kMhzMin = "mhz_min";
inline constexpr const char* kMhzMax = "mhz_max";
inline constexpr const char* kMhzAfter = "mhz_after";
}  // namespace cpu
namespace gpu {
inline constexpr const char* kNvml = "nvml";
inline constexpr const char* kNote = "note";
inline constexpr const char* kSmMhz = "sm_mhz";
inline constexpr const char* kMemMhz = "mem_mhz";
inline constexpr const char* kTemperatureCMax = "temperature_c_max";
inline constexpr const char* kPowerWMax = "power_w_max";
inline constexpr const char* kThrottleReasons = "throttle_reasons";
inline constexpr const char* kThrottled = "throttled";
inline constexpr const char* kClockLeftBand = "clock_left_band";
namespace clock {  // sm_mhz and mem_mhz (mem_mhz: min and max only)
inline constexpr const char* kBefore = "before";
inline constexpr const char* kMin = "min";
inline constexpr const char* kMedian = "median";
inline constexpr const char* kMax = "max";
inline constexpr const char* kAfter = "after";
inline constexpr const char* kMaxRated = "max_rated";
}  // namespace clock
}  // namespace gpu
}  // namespace machine
namespace rule {
inline constexpr const char* kWarmUpWindow = "warm_up_window";
inline constexpr const char* kWarmUpTolerance = "warm_up_tolerance";
inline constexpr const char* kWarmUpCapFrames = "warm_up_cap_frames";
inline constexpr const char* kWarmUpCapSeconds = "warm_up_cap_seconds";
inline constexpr const char* kDriftLevelFloor = "drift_level_floor";
inline constexpr const char* kDriftSpanFloor = "drift_span_floor";
inline constexpr const char* kDriftLevelNoiseK = "drift_level_noise_k";
inline constexpr const char* kDriftSpanNoiseK = "drift_span_noise_k";
inline constexpr const char* kBusyOtherCores = "busy_other_cores";
inline constexpr const char* kClockBand = "clock_band";
}  // namespace rule
}  // namespace health

namespace wall {
inline constexpr const char* kSeconds = "seconds";
inline constexpr const char* kPartsS = "parts_s";            // by part: the main thread's wall seconds
inline constexpr const char* kWorkerCpuS = "worker_cpu_s";    // by task: the workers' CPU seconds
inline constexpr const char* kPeakRssMibAfter = "peak_rss_mib_after";  // by step: peak RSS
// The parts, in the order a run meets them (harness/base/wall_account.h WallPart's order):
// report and other close after the report is written.
inline constexpr const char* kParts[] = {"scene_load",   "device_open",  "upload",    "pipelines", "scorer_setup",
                                         "warm_up",      "quality_render", "readback", "scoring",  "timed_frames",
                                         "worst_images", "bandwidth",    "outputs",   "report",    "other"};
inline constexpr size_t kPartsBeforeReport = std::size(kParts) - 2;
// The workers' tasks (WorkerTask's order).
inline constexpr const char* kWorkerTasks[] = {"psnr", "ssim", "flip", "eci", "cvvdp", "image_encode"};
}  // namespace wall

namespace memory {
inline constexpr const char* kEstimateHostMib = "estimate_host_mib";
inline constexpr const char* kEstimateDeviceMib = "estimate_device_mib";
inline constexpr const char* kHostLimitMib = "host_limit_mib";
inline constexpr const char* kHostLimitFrom = "host_limit_from";
inline constexpr const char* kDeviceLimitMib = "device_limit_mib";
inline constexpr const char* kDeviceLimitFrom = "device_limit_from";
inline constexpr const char* kPeakRssMib = "peak_rss_mib";
inline constexpr const char* kDeviceAllocatedPeakMib = "device_allocated_peak_mib";
inline constexpr const char* kHostVisibleAllocatedPeakMib = "host_visible_allocated_peak_mib";
inline constexpr const char* kDeviceUsagePeakMib = "device_usage_peak_mib";
inline constexpr const char* kDeviceBudgetMib = "device_budget_mib";
inline constexpr const char* kDeviceHeapMib = "device_heap_mib";
inline constexpr const char* kAfter = "after";
namespace after {  // memory.after[]: a reading after each step
inline constexpr const char* kAfter = "after";  // the step
inline constexpr const char* kPeakRssMib = "peak_rss_mib";
inline constexpr const char* kDeviceAllocatedMib = "device_allocated_mib";
inline constexpr const char* kDeviceUsageMib = "device_usage_mib";
}  // namespace after
// The steps a reading is taken after (memory.after[].after, wall.peak_rss_mib_after's keys).
inline constexpr const char* kQualityPass = "quality_pass";
inline constexpr const char* kTimedFrames = "timed_frames";
inline constexpr const char* kWorstImages = "worst_images";
inline constexpr const char* kReport = "report";
inline constexpr const char* kSteps[] = {kQualityPass, kTimedFrames, kWorstImages, kReport};
}  // namespace memory

}  // namespace cbr::rundir::run
