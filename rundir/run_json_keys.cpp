// run.json's keys as flattened paths (run_json_keys.h), built from the schema's names.
#include "rundir/run_json_keys.h"

#include <initializer_list>

#include "rundir/run_json.h"
#include "rundir/run_json_health.h"
#include "rundir/run_json_sequence.h"
#include "rundir/run_json_variants.h"
#include "rundir/setting_columns.h"

namespace cbr::rundir::run {

namespace {

// The paths, added object by object.
class Paths {
public:
    void add(const std::string& path, const char* when = nullptr) { out_.push_back({path, when}); }
    void under(const std::string& prefix, std::initializer_list<const char*> keys, const char* when = nullptr) {
        for (const char* k : keys) add(prefix + "." + k, when);
    }
    std::vector<KeyPath> take() { return std::move(out_); }

private:
    std::vector<KeyPath> out_;
};

std::string at(const std::string& prefix, const char* key) { return prefix + "." + key; }
std::string array(const std::string& path) { return path + "[]"; }

void toolAndHost(Paths& p) {
    p.under(kTool, {tool::kName, tool::kVersion, tool::kCommit});
    p.under(kHost, {host::kName, host::kCpus});
    p.under(at(kHost, host::kMemory),
            {host::memory::kKeepsFreedMemory, host::memory::kTransparentHugePages, host::memory::kHeapHugePages});
}

void deviceKeys(Paths& p) {
    using namespace device;
    p.under(kDevice, {kIndex, kName, kType, kVendorId, kDeviceId, kDriverName, kDriverInfo, kDriverId, kDriverVersion,
                      kApiVersion, kIsLavapipe, kTimestampPeriodNs, kTimestampValidBits, kPipelineStatistics,
                      kTargetClear, kTargetClearRule, kCopyBandwidthGbPerS, kTransferBandwidthGbPerS,
                      kCopyBandwidthRule});
    p.add(at(kDevice, kTimingNote), "lavapipe");
}

void displayKeys(Paths& p) {
    namespace d = settings::display;
    p.under(at(kSettings, cbr::rundir::settingColumn("display")),
            {d::kName, d::kSpec, d::kDescription, d::kWidth, d::kHeight, d::kDiagonalIn, d::kFovDiagonalDeg,
             d::kDistanceM, d::kPpd, d::kPeak, d::kContrast, d::kAmbientLux, d::kKRefl});
}

void settingsKeys(Paths& p) {
    using namespace settings;
    p.under(kSettings, {kWidth, kHeight, kPipeline, kFrames, kRepeat, kWarmupFrames, kWarmupRule, kFramesInFlight,
                        kDepth, kSaveFrames, kCvvdpFps});
    p.add(array(at(kSettings, kVariantOrder)));
    p.under(at(kSettings, kDrrControl),
            {drr_control::kMinScale, drr_control::kMaxScale, drr_control::kDeadBand, drr_control::kStep});
    for (const cbr::settings::Row* row : runJsonSettings())
        if (row->type != cbr::settings::Type::Text) p.add(at(kSettings, row->column));
    displayKeys(p);
}

void sceneKeys(Paths& p) {
    using namespace scene;
    p.under(kScene, {kName, kSource, kHash, kTriangles, kOpaqueDraws, kMaskedDraws, kBlendDraws, kAnimatedInstances,
                     kLights, kDefaultLight, kRecentredMeshes, kDraws, kMaterials, kTextures, kTextureBytes,
                     kTextureGpuBytes, kLoadS, kUploadS, kPeakRssMibLoaded, kPeakRssMibEnd, kCostNote});
    for (const char* k : {kBoundsMin, kBoundsMax, kWarnings, kAnimations, kCameras}) p.add(array(at(kScene, k)));
    const char* animated = "a glTF scene with animations";
    p.under(array(at(kScene, kAnimations)),
            {animation::kName, animation::kIndex, animation::kLengthS, animation::kChannels, animation::kPlayed},
            animated);
    p.under(array(at(kScene, kCameras)), {camera::kName, camera::kType}, "a glTF scene with cameras");
}

void pathKeys(Paths& p) {
    using namespace path;
    p.under(kPath, {kName, kSource, kHash, kFps, kDurationS, kFrames, kCuts});
    const std::string placed = at(kPath, kPlacement);
    p.under(placed, {placement::kRule, placement::kReason}, "a built-in path placed in the scene");
    p.add(array(at(placed, placement::kGrid)), "a path placed on a grid");
    const std::string region = at(placed, placement::kRegion);
    for (const char* k : {placement::region::kMin, placement::region::kMax})
        p.add(array(at(region, k)), "the interior placement");
    p.add(at(region, placement::region::kEyeY), "the interior placement");
}

void metricsKeys(Paths& p) {
    using namespace metrics;
    p.under(kMetrics, {kOn, kReference, kPsnr, kSsim, kEci, kFlip, kFlipPpd, kCvvdp, kReferenceKind, kImageIo, kScorer,
                       kScorerRequested, kScorerNote, kScoredRepeat});
    p.under(kMetrics, {kScorerThreads, kScorerFrames}, "the CPU scorer");
    p.add(at(kMetrics, kReferenceGpuMsMedian), "an ssaa reference");
}

}  // namespace
}  // namespace cbr::rundir::run

namespace cbr::rundir::run {
namespace {

void variantDescriptionKeys(Paths& p, const std::string& v) {
    using namespace variant;
    const char* cbr = "checkerboard variants";
    p.under(v, {kRoute, kRouteReason, kQuarterResolution, kOcclusionRule, kFill, kLostBorder, kResolve, kClassStats,
                kClassMap, kResolveBytesPerFrame}, cbr);
    p.add(at(v, kResolveGroup), "checkerboard variants, not with --resolve-impl reference");
    p.under(v, {kCsoTolerance, kCsoMode}, "cbr-cso");
    p.under(v, {kRenderResolution, kJitter, kBlend, kReset}, "taau");
    p.under(v, {kLodBias, kMotion, kHistory, kTonemap}, "checkerboard variants and taau");
    p.add(at(v, kDebugSlowdown), "--debug-slowdown");
    p.add(at(v, kPipelineDetail), cbr);
}

void variantKeys(Paths& p) {
    using namespace variant;
    const std::string v = array(kVariants);
    p.add(v);
    p.under(v, {kName, kStatus, kPipeline});
    p.add(at(v, kNote), "a variant that failed, was skipped or is unsteady");
    p.add(array(at(v, kPasses)));
    p.under(array(at(v, kPasses)), {pass::kName, pass::kRan});
    p.add(at(array(at(v, kPasses)), pass::kReason), "a pass that did not run");
    p.under(v, {kVariant, kSpeedupBaseline}, "a sweep");
    p.add(at(at(v, variant::kSettings), "<param>"), "a sweep");
    p.under(at(v, kFrameAlignment), {frame_alignment::kFrame, frame_alignment::kPsnrDbSame, frame_alignment::kPsnrDbPrev,
                                     frame_alignment::kPsnrDbNext, frame_alignment::kOk});
    p.under(v, {kGpuMsMedian, kSpeedup, kSpeedupLow, kSpeedupHigh, kPsnrDb, kPsnrDbIsInf, kSsimMean, kFlipMean,
                kCvvdpJod, kEci, kRenderWidth, kRenderHeight});
    namespace rb = resolve_bandwidth;
    p.under(at(v, kResolveBandwidth), {rb::kPass, rb::kMbPerFrame, rb::kPassMsMedian, rb::kGbPerS, rb::kDeviceCopyGbPerS,
                                       rb::kFractionOfCopy, rb::kRule},
            "checkerboard variants");
    variantDescriptionKeys(p, v);
}

void worstKeys(Paths& p) {
    const std::string w = array(kWorst);
    p.add(w);
    p.under(w, {worst::kVariant, worst::kKind, worst::kFrame, worst::kValue});
    for (const char* image : worst::image::kAll) {
        const bool always = image != worst::image::kClassMap && image != worst::image::kCvvdpMap;
        const char* when = image == worst::image::kClassMap ? "checkerboard variants"
                           : always                         ? nullptr
                                                            : "ColorVideoVDP scored";
        p.add(at(at(w, worst::kFiles), image), when);
        p.add(at(at(w, worst::kPage), image), when);
    }
}

void validationKeys(Paths& p) {
    using namespace validation;
    p.under(kValidation, {kEnabled, kErrors, kWarnings, kMessages});
    p.add(array(at(kValidation, kFirstMessages)));
}

}  // namespace
}  // namespace cbr::rundir::run

namespace cbr::rundir::run {
namespace {

void healthVariantKeys(Paths& p, const std::string& v) {
    using namespace health::variant;
    p.add(v);
    p.under(v, {kName, kOtherCoresMax, kUnsteady, kNote});
    p.add(array(at(v, kWarmUpFrames)));
    p.add(array(at(v, kWarmUpCapped)));
    namespace d = health::drift;
    const std::string drift = at(v, kDrift);
    p.under(drift, {d::kTested, d::kUnsteady, d::kWhyNot, d::kNoise, d::kLevelLimit, d::kSpanLimit, d::kLevelMax,
                    d::kSpanMax});
    p.add(array(at(drift, d::kRepetitionRatios)));
    p.under(at(drift, d::kLargest), {d::largest::kRepetition, d::largest::kFirstFrame, d::largest::kLastFrame,
                                     d::largest::kRatio, d::largest::kWholeRepetition});
}

void machineKeys(Paths& p, const std::string& m) {
    using namespace health::machine;
    p.under(m, {kTimestampDeviationNs, kSamples, kSampleIntervalS});
    p.under(at(m, kCpu), {cpu::kCores, cpu::kOwnCores, cpu::kOwnShare, cpu::kOtherCores, cpu::kOtherCoresMax,
                          cpu::kStealCores, cpu::kMhzBefore, cpu::kMhzMin, cpu::kMhzMax, cpu::kMhzAfter});
    const std::string g = at(m, kGpu);
    p.under(g, {gpu::kNvml, gpu::kNote, gpu::kTemperatureCMax, gpu::kPowerWMax, gpu::kThrottled, gpu::kClockLeftBand});
    p.add(array(at(g, gpu::kThrottleReasons)));
    namespace c = gpu::clock;
    p.under(at(g, gpu::kSmMhz), {c::kBefore, c::kMin, c::kMedian, c::kMax, c::kAfter, c::kMaxRated});
    p.under(at(g, gpu::kMemMhz), {c::kMin, c::kMax});
}

void healthKeys(Paths& p) {
    using namespace health;
    p.under(kHealth, {kQuiet, kBusy, kUnsteady, kStatusGate, kLine});
    p.add(array(at(kHealth, kDisturbances)));
    healthVariantKeys(p, array(at(kHealth, health::kVariants)));
    machineKeys(p, at(kHealth, kMachine));
    p.under(at(kHealth, kRule), {rule::kWarmUpWindow, rule::kWarmUpTolerance, rule::kWarmUpCapFrames,
                                 rule::kWarmUpCapSeconds, rule::kDriftLevelFloor, rule::kDriftSpanFloor,
                                 rule::kDriftLevelNoiseK, rule::kDriftSpanNoiseK, rule::kBusyOtherCores,
                                 rule::kClockBand});
}

void wallKeys(Paths& p) {
    p.add(at(kWall, wall::kSeconds));
    for (const char* part : wall::kParts) p.add(at(at(kWall, wall::kPartsS), part));
    for (const char* task : wall::kWorkerTasks) p.add(at(at(kWall, wall::kWorkerCpuS), task));
    for (const char* step : memory::kSteps) p.add(at(at(kWall, wall::kPeakRssMibAfter), step));
}

void memoryKeys(Paths& p) {
    using namespace memory;
    p.under(kMemory, {kEstimateHostMib, kEstimateDeviceMib, kHostLimitMib, kHostLimitFrom, kDeviceLimitMib,
                      kDeviceLimitFrom, kPeakRssMib, kDeviceAllocatedPeakMib, kHostVisibleAllocatedPeakMib,
                      kDeviceUsagePeakMib, kDeviceBudgetMib, kDeviceHeapMib});
    const std::string a = array(at(kMemory, kAfter));
    p.add(a);
    p.under(a, {after::kAfter, after::kPeakRssMib, after::kDeviceAllocatedMib, after::kDeviceUsageMib});
}

}  // namespace

std::vector<KeyPath> runJsonKeys() {
    Paths p;
    toolAndHost(p);
    for (const char* k : {kDate, kWallSeconds, kFirstFrameWallSeconds, kReferenceVariant, kNonFiniteCells}) p.add(k);
    for (const char* k : {kCommandLine, kFiles}) p.add(array(k));
    deviceKeys(p);
    settingsKeys(p);
    sceneKeys(p);
    pathKeys(p);
    metricsKeys(p);
    variantKeys(p);
    worstKeys(p);
    validationKeys(p);
    healthKeys(p);
    wallKeys(p);
    memoryKeys(p);
    return p.take();
}

std::vector<KeyPath> sequenceJsonKeys() {
    Paths p;
    toolAndHost(p);
    for (const char* k : {kKind, kDate, kWallSeconds}) p.add(k);
    p.add(array(kCommandLine));
    p.under(kSettings, {settings::kWidth, settings::kHeight, settings::kCvvdpFps, settingColumn("flip-ppd"),
                        settingColumn("exposure")});
    displayKeys(p);
    p.add(at(kScene, scene::kName));
    p.add(at(kPath, path::kName));
    using namespace sequence;
    p.under(kSequence, {kReference, kTest, kFrames, kMatchedBy});
    for (const char* k : {kCuts, kConversions}) p.add(array(at(kSequence, k)));
    p.add(at(at(kSequence, kMotion), motion::kSource));
    p.add(at(at(kSequence, kMotion), motion::kMethod), "the global shift");
    p.under(at(kSequence, kMotion), {motion::kFiles, motion::kConvention}, "--motion");
    p.add(array(at(at(kSequence, kMotion), motion::kScale)), "--motion");
    namespace t = thresholds;
    p.add(at(kThresholds, t::kVerdict));
    for (const char* list : {t::kWarn, t::kFail, t::kCrossed}) p.add(array(at(kThresholds, list)));
    for (const char* list : {t::kWarn, t::kFail, t::kCrossed})
        p.under(array(at(kThresholds, list)), {t::kMetric, t::kValue}, "thresholds given (crossed: and crossed)");
    p.under(array(at(kThresholds, t::kCrossed)),
            {t::crossed::kThreshold, t::crossed::kLevel, t::crossed::kFrame, t::crossed::kFrameNumber},
            "a threshold crossed");
    namespace s = sequence_summary;
    p.under(kSummary, {s::kPsnrDb, s::kPsnrDbIsInf, s::kSsimMean, s::kFlipMean, s::kCvvdpJod, s::kEci,
                       s::kFlickerRatioMean});
    p.add(array(kVariants));
    p.under(array(kVariants), {variant::kName, variant::kStatus});
    worstKeys(p);
    return p.take();
}

namespace {

std::vector<std::string> segments(const std::string& path) {
    std::vector<std::string> out(1);
    for (char c : path) {
        if (c == '.') out.emplace_back();
        else out.back() += c;
    }
    return out;
}

}  // namespace

bool matches(const std::string& schema_path, const std::string& written_path) {
    const auto a = segments(schema_path), b = segments(written_path);
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i] && !(a[i].size() > 2 && a[i].front() == '<' && a[i].back() == '>')) return false;
    return true;
}

}  // namespace cbr::rundir::run
