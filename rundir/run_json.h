// run.json's keys, grouped by object (docs/reference/outputs.md): the top level and the objects
// of where and what ran (tool, host, device, settings, scene, path, metrics). The variants, the
// worst frames and validation are in run_json_variants.h; health, wall and memory in
// run_json_health.h; score-seq's own in run_json_sequence.h. The settings table names the
// settings object's tunables (setting_columns.h); the display model's keys are settings/'s.
#pragma once

#include "settings/display_keys.h"

namespace cbr::rundir::run {

// The top level.
inline constexpr const char* kTool = "tool";
inline constexpr const char* kDate = "date";
inline constexpr const char* kCommandLine = "command_line";
inline constexpr const char* kHost = "host";
inline constexpr const char* kWallSeconds = "wall_seconds";
inline constexpr const char* kFirstFrameWallSeconds = "first_frame_wall_seconds";
inline constexpr const char* kDevice = "device";
inline constexpr const char* kSettings = "settings";
inline constexpr const char* kScene = "scene";
inline constexpr const char* kPath = "path";
inline constexpr const char* kMetrics = "metrics";
inline constexpr const char* kReferenceVariant = "reference_variant";
inline constexpr const char* kVariants = "variants";
inline constexpr const char* kNonFiniteCells = "non_finite_cells";
inline constexpr const char* kValidation = "validation";
inline constexpr const char* kFiles = "files";
inline constexpr const char* kWorst = "worst";
inline constexpr const char* kHealth = "health";
inline constexpr const char* kWall = "wall";
inline constexpr const char* kMemory = "memory";

namespace tool {
inline constexpr const char* kName = "name";
inline constexpr const char* kVersion = "version";
inline constexpr const char* kCommit = "commit";
}  // namespace tool

namespace host {
inline constexpr const char* kName = "name";
inline constexpr const char* kCpus = "cpus";
inline constexpr const char* kMemory = "memory";
namespace memory {  // the process's memory policy
inline constexpr const char* kKeepsFreedMemory = "keeps_freed_memory";
inline constexpr const char* kTransparentHugePages = "transparent_huge_pages";
inline constexpr const char* kHeapHugePages = "heap_huge_pages";
}  // namespace memory
}  // namespace host

namespace device {
inline constexpr const char* kIndex = "index";
inline constexpr const char* kName = "name";
inline constexpr const char* kType = "type";
inline constexpr const char* kVendorId = "vendor_id";
inline constexpr const char* kDeviceId = "device_id";
inline constexpr const char* kDriverName = "driver_name";
inline constexpr const char* kDriverInfo = "driver_info";
inline constexpr const char* kDriverId = "driver_id";
inline constexpr const char* kDriverVersion = "driver_version";
inline constexpr const char* kApiVersion = "api_version";
inline constexpr const char* kIsLavapipe = "is_lavapipe";
inline constexpr const char* kTimestampPeriodNs = "timestamp_period_ns";
inline constexpr const char* kTimestampValidBits = "timestamp_valid_bits";
inline constexpr const char* kPipelineStatistics = "pipeline_statistics";
inline constexpr const char* kTargetClear = "target_clear";
inline constexpr const char* kTargetClearRule = "target_clear_rule";
inline constexpr const char* kCopyBandwidthGbPerS = "copy_bandwidth_gb_per_s";
inline constexpr const char* kTransferBandwidthGbPerS = "transfer_bandwidth_gb_per_s";
inline constexpr const char* kCopyBandwidthRule = "copy_bandwidth_rule";
inline constexpr const char* kTimingNote = "timing_note";  // lavapipe only
}  // namespace device

// The settings every configuration starts from and the run's shape; then every row of the
// settings table with run_json, by its column (rundir::runJsonSettings()).
namespace settings {
inline constexpr const char* kWidth = "width";
inline constexpr const char* kHeight = "height";
inline constexpr const char* kPipeline = "pipeline";
inline constexpr const char* kFrames = "frames";
inline constexpr const char* kRepeat = "repeat";
inline constexpr const char* kWarmupFrames = "warmup_frames";
inline constexpr const char* kWarmupRule = "warmup_rule";
inline constexpr const char* kVariantOrder = "variant_order";
inline constexpr const char* kDrrControl = "drr_control";
inline constexpr const char* kFramesInFlight = "frames_in_flight";
inline constexpr const char* kDepth = "depth";
inline constexpr const char* kSaveFrames = "save_frames";
inline constexpr const char* kCvvdpFps = "cvvdp_fps";
namespace drr_control {
inline constexpr const char* kMinScale = "min_scale";
inline constexpr const char* kMaxScale = "max_scale";
inline constexpr const char* kDeadBand = "dead_band";
inline constexpr const char* kStep = "step";
}  // namespace drr_control
// settings.display: the display model's keys, written by the settings table's display row.
namespace display = cbr::settings::display_keys;
}  // namespace settings

namespace scene {
inline constexpr const char* kName = "name";
inline constexpr const char* kSource = "source";
inline constexpr const char* kHash = "hash";
inline constexpr const char* kTriangles = "triangles";
inline constexpr const char* kOpaqueDraws = "opaque_draws";
inline constexpr const char* kMaskedDraws = "masked_draws";
inline constexpr const char* kBlendDraws = "blend_draws";
inline constexpr const char* kAnimatedInstances = "animated_instances";
inline constexpr const char* kLights = "lights";
inline constexpr const char* kDefaultLight = "default_light";
inline constexpr const char* kRecentredMeshes = "recentred_meshes";
inline constexpr const char* kBoundsMin = "bounds_min";
inline constexpr const char* kBoundsMax = "bounds_max";
inline constexpr const char* kWarnings = "warnings";
inline constexpr const char* kAnimations = "animations";
inline constexpr const char* kCameras = "cameras";
// What loading cost (harness/figures/scene_load.cpp).
inline constexpr const char* kDraws = "draws";
inline constexpr const char* kMaterials = "materials";
inline constexpr const char* kTextures = "textures";
inline constexpr const char* kTextureBytes = "texture_bytes";
inline constexpr const char* kTextureGpuBytes = "texture_gpu_bytes";
inline constexpr const char* kLoadS = "load_s";
inline constexpr const char* kUploadS = "upload_s";
inline constexpr const char* kPeakRssMibLoaded = "peak_rss_mib_loaded";
inline constexpr const char* kPeakRssMibEnd = "peak_rss_mib_end";
inline constexpr const char* kCostNote = "cost_note";
namespace animation {  // scene.animations[]
inline constexpr const char* kName = "name";
inline constexpr const char* kIndex = "index";
inline constexpr const char* kLengthS = "length_s";
inline constexpr const char* kChannels = "channels";
inline constexpr const char* kPlayed = "played";
}  // namespace animation
namespace camera {  // scene.cameras[]
inline constexpr const char* kName = "name";
inline constexpr const char* kType = "type";
}  // namespace camera
}  // namespace scene

namespace path {
inline constexpr const char* kName = "name";
inline constexpr const char* kSource = "source";
inline constexpr const char* kHash = "hash";
inline constexpr const char* kFps = "fps";
inline constexpr const char* kDurationS = "duration_s";
inline constexpr const char* kFrames = "frames";
inline constexpr const char* kCuts = "cuts";
inline constexpr const char* kPlacement = "placement";  // a built-in path placed in the scene
namespace placement {
inline constexpr const char* kRule = "rule";
inline constexpr const char* kReason = "reason";
inline constexpr const char* kGrid = "grid";
inline constexpr const char* kRegion = "region";  // the interior rule's region
namespace region {
inline constexpr const char* kMin = "min";
inline constexpr const char* kMax = "max";
inline constexpr const char* kEyeY = "eye_y";
}  // namespace region
}  // namespace placement
}  // namespace path

namespace metrics {
inline constexpr const char* kOn = "on";
inline constexpr const char* kReference = "reference";
inline constexpr const char* kPsnr = "psnr";
inline constexpr const char* kSsim = "ssim";
inline constexpr const char* kEci = "eci";
inline constexpr const char* kFlip = "flip";
inline constexpr const char* kFlipPpd = "flip_ppd";
inline constexpr const char* kCvvdp = "cvvdp";
inline constexpr const char* kReferenceKind = "reference_kind";
inline constexpr const char* kImageIo = "image_io";
inline constexpr const char* kScorer = "scorer";
inline constexpr const char* kScorerRequested = "scorer_requested";
inline constexpr const char* kScorerNote = "scorer_note";
inline constexpr const char* kScoredRepeat = "scored_repeat";
inline constexpr const char* kScorerThreads = "scorer_threads";  // the CPU scorer only
inline constexpr const char* kScorerFrames = "scorer_frames";    // the CPU scorer only
inline constexpr const char* kReferenceGpuMsMedian = "reference_gpu_ms_median";  // an ssaa reference's
}  // namespace metrics

}  // namespace cbr::rundir::run
