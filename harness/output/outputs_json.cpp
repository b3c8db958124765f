// run.json: the run's device, settings, scene, path, metrics, variants and validation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>
#include <unistd.h>

#include "harness/base/fnv.h"
#include "harness/base/process.h"
#include "harness/output/outputs_internal.h"
#include "harness/quality/quality.h"
#include "harness/output/resolve_bandwidth.h"
#include "harness/figures/stats.h"
#include "metrics/cvvdp.h"
#include "metrics/image_encode.h"
#include "metrics/image_io.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/context.h"
#include "reports/csv.h"
#include "rundir/files.h"
#include "rundir/run_json.h"
#include "rundir/run_json_health.h"
#include "rundir/run_json_variants.h"
#include "rundir/setting_columns.h"
#include "settings/table.h"

namespace cbr::harness {
namespace {

using nlohmann::json;

std::string hex(uint64_t v) {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// Content hashes: two runs with equal hashes rendered the same geometry and camera.
std::string sceneHash(const scene::Scene& s) {
    uint64_t h = fnv1a(s.vertices.data(), s.vertices.size() * sizeof(scene::Vertex));
    h = fnv1a(s.indices.data(), s.indices.size() * sizeof(uint32_t), h);
    for (const auto& t : s.textures) h = fnv1a(t.rgba8.data(), t.rgba8.size(), h);
    for (const auto& m : s.materials) h = fnv1a(&m.base_color_factor, sizeof(m.base_color_factor), h);
    for (const auto& a : s.animations)  // what plays moves the geometry
        if (a.played)
            for (const auto& c : a.channels) {
                h = fnv1a(c.times.data(), c.times.size() * sizeof(double), h);
                h = fnv1a(c.values.data(), c.values.size() * sizeof(double), h);
            }
    return hex(h);
}

// run.json scene.animations: every glTF animation that targets nodes, and whether it played.
nlohmann::json animationsJson(const scene::Scene& s) {
    namespace k = rundir::run::scene::animation;
    nlohmann::json list = nlohmann::json::array();
    for (const auto& a : s.animations)
        list.push_back({{k::kName, a.name}, {k::kIndex, a.gltf_index}, {k::kLengthS, a.length},
                        {k::kChannels, a.channels.size()}, {k::kPlayed, a.played}});
    return list;
}

std::string pathHash(const std::vector<paths::CameraPose>& poses, const std::vector<double>& times) {
    uint64_t h = fnv1a(times.data(), times.size() * sizeof(double));
    for (const auto& p : poses) {
        h = fnv1a(&p.position, sizeof(p.position), h);
        h = fnv1a(&p.orientation, sizeof(p.orientation), h);
        h = fnv1a(&p.fov_y_rad, sizeof(double), h);
    }
    return hex(h);
}

nlohmann::json number(const std::optional<double>& v) {
    if (!v) return nullptr;
    if (!std::isfinite(*v)) return nullptr;  // JSON has no inf: null plus an *_is_inf flag
    return *v;
}

// The device, its timestamp and statistics abilities, and the measured copy bandwidth.
json deviceJson(const RunContext& rc) {
    namespace k = rundir::run::device;
    const RunResults& r = rc.results;
    const auto& d = rc.ctx.description;
    json out = {{k::kIndex, d.index},
                {k::kName, d.name},
                {k::kType, d.device_type},
                {k::kVendorId, d.vendor_id},
                {k::kDeviceId, d.device_id},
                {k::kDriverName, d.driver_name},
                {k::kDriverInfo, d.driver_info},
                {k::kDriverId, d.driver_id},
                {k::kDriverVersion, d.driver_version},
                {k::kApiVersion, d.api_version},
                {k::kIsLavapipe, d.is_lavapipe},
                {k::kTimestampPeriodNs, rc.ctx.caps.timestamp_period_ns},
                {k::kTimestampValidBits, rc.ctx.caps.timestamp_valid_bits},
                {k::kPipelineStatistics, rc.ctx.caps.pipeline_statistics},
                {k::kTargetClear, rc.ctx.compute_clears ? "compute" : "load-op"},
                {k::kTargetClearRule, rc.ctx.target_clear_rule},
                {k::kCopyBandwidthGbPerS, r.copy_bandwidth.gb_per_s},
                {k::kTransferBandwidthGbPerS, r.copy_bandwidth.transfer_gb_per_s},
                {k::kCopyBandwidthRule,
                 r.copy_bandwidth.copies == 0
                     ? std::string("not measured (lavapipe's timestamps do not bracket a lone copy)")
                     : "median of " + std::to_string(r.copy_bandwidth.copies) + " compute-shader copies (16-byte " +
                           "loads and stores) of " + std::to_string(int(r.copy_bandwidth.buffer_mib)) +
                           " MiB between device-local buffers, bytes read + written; transfer_bandwidth_gb_per_s: "
                           "the same with vkCmdCopyBuffer"}};
    if (d.is_lavapipe)
        out[k::kTimingNote] =
            "lavapipe timestamps measure CPU rasterisation: ratios between variants are meaningful, absolute times "
            "are not GPU times";
    return out;
}

// The render settings every configuration starts from, and the run's shape.
json settingsJson(const RunContext& rc) {
    namespace k = rundir::run::settings;
    const RunResults& r = rc.results;
    const auto& s = rc.settings;
    json out = {{k::kWidth, s.width},
            {k::kHeight, s.height},
            {k::kPipeline, s.deferred ? "deferred" : "forward"},
            {k::kFrames, r.frames},
            {k::kRepeat, r.repeats},
            {k::kWarmupFrames, rc.options.warmup},
            {k::kWarmupRule, "at least warmup_frames of the path's first pose per variant and timed repetition, then until steady (health.rule; frames used: health.variants)"},
            {k::kVariantOrder, r.order},
            {k::kDrrControl,
             {{k::drr_control::kMinScale, s.drr_control.min_scale},
              {k::drr_control::kMaxScale, s.drr_control.max_scale},
              {k::drr_control::kDeadBand, s.drr_control.dead_band},
              {k::drr_control::kStep, s.drr_control.step}}},
            {k::kFramesInFlight, s.frames_in_flight},
            {k::kDepth, "reversed-Z, D32_SFLOAT"},
            {k::kSaveFrames, rc.options.save_frames},
            {k::kCvvdpFps, rc.results.cvvdp_fps}};
    for (const settings::Row* row : rundir::runJsonSettings())
        out[row->column] = row->json_float ? json(float(row->field.get(s))) : settings::toJson(*row, s);
    return out;
}

// The scene: source, content hash, counts, load cost, animations and cameras.
json sceneJson(const RunContext& rc) {
    namespace k = rundir::run::scene;
    const RunResults& r = rc.results;
    const auto& si = rc.scene.info;
    json out = {{k::kName, rc.scene.name},
                {k::kSource, rc.scene.source},
                {k::kHash, sceneHash(rc.scene)},
                {k::kTriangles, si.triangles},
                {k::kOpaqueDraws, si.opaque_draws},
                {k::kMaskedDraws, si.masked_draws},
                {k::kBlendDraws, si.blend_draws},
                {k::kAnimatedInstances, si.animated_instances},
                {k::kLights, rc.scene.lights.size()},
                {k::kDefaultLight, si.default_light},
                {k::kRecentredMeshes, si.recentred_meshes},
                {k::kBoundsMin, {rc.scene.bounds_min.x, rc.scene.bounds_min.y, rc.scene.bounds_min.z}},
                {k::kBoundsMax, {rc.scene.bounds_max.x, rc.scene.bounds_max.y, rc.scene.bounds_max.z}},
                {k::kWarnings, rc.scene.warnings}};
    addSceneCost(out, rc.scene, r.scene_load);
    out[k::kAnimations] = animationsJson(rc.scene);
    out[k::kCameras] = nlohmann::json::array();
    for (const auto& c : rc.scene.cameras)
        out[k::kCameras].push_back(
            {{k::camera::kName, c.name}, {k::camera::kType, c.perspective ? "perspective" : "orthographic"}});
    return out;
}

// The camera path: source, hash of the sampled poses and times, frames and cuts.
json pathJson(const RunContext& rc) {
    namespace k = rundir::run::path;
    json out = {{k::kName, rc.path.name},
                {k::kSource, rc.options.path},
                {k::kHash, pathHash(rc.poses, rc.times)},
                {k::kFps, rc.path.fps},
                {k::kDurationS, rc.path.duration()},
                {k::kFrames, rc.poses.size()},
                {k::kCuts, std::count_if(rc.poses.begin(), rc.poses.end(), [](const auto& p) { return p.cut; })}};
    if (rc.placement) out[k::kPlacement] = placementJson(*rc.placement, rc.scene.placement);
    return out;
}

// How quality is measured, and against which reference.
json metricsJson(const RunContext& rc) {
    namespace k = rundir::run::metrics;
    const RunResults& r = rc.results;
    json out = {{k::kOn, "8-bit sRGB display image, as the saved PNGs, converted to [0,1]"},
                {k::kReference, "full at the same frame, unjittered, one sample per pixel"},
                {k::kPsnr, "10 log10(1/MSE), MSE over all pixels and RGB channels; sequence PSNR from the mean MSE"},
                {k::kSsim, "Wang et al. 2004: Gaussian 11x11 sigma 1.5, K1 0.01, K2 0.03, L 1, population "
                         "statistics, 5-pixel border excluded, mean of per-channel SSIM"},
                {k::kEci, "edge crawl index: luma blurred with sigma 1, e = Y(V) - Y(R), e_t against e_t-1 "
                        "warped with the renderer's motion vectors (bilinear), on reference edges (Sobel of blurred "
                        "reference luma > 0.02, dilated 1 px), 4 px margin, disocclusions (5% view-depth mismatch) "
                        "and pairs across cuts excluded; sequence ECI pools numerators and denominators"},
                {k::kFlip, "LDR-FLIP (Andersson et al. 2020) as NVIDIA's tool v1.6 computes it: mean of the error "
                         "map and weighted quartiles (pixels weighted by their error); summary flip_mean is the mean "
                         "of the per-frame means"},
                {k::kFlipPpd, settings::flipPpd(rc.options.tune)},
                {k::kCvvdp, "ColorVideoVDP (Mantiuk, Hammou, Hanji 2024, model " + std::string(metrics::cvvdpModelVersion()) +
                              ") on the display model settings.display at settings.cvvdp_fps frames per second: JOD, 10 "
                              "= no visible difference, one JOD less = 75% of viewers prefer the better; frames.csv "
                              "cvvdp_jod is each frame's, summary cvvdp_jod the sequence's (docs/method/cvvdp.md)"},
                {k::kReferenceKind, rc.options.tune.reference == settings::Reference::Ssaa
                                       ? "ssaa: " + std::to_string(rc.options.tune.ssaa) + "x" +
                                             std::to_string(rc.options.tune.ssaa) + " samples per pixel, box filter in HDR"
                                       : std::string("full")},
                // The library --save-frames writes through; loaded only then (OpenImageIO's
                // plugins are 80 MB of a run's memory), the worst frames' encoders otherwise.
                {k::kImageIo, rc.options.save_frames ? metrics::imageIoBackend() : metrics::encodeBackend()},
                {k::kScorer, r.scorer},
                {k::kScorerRequested, settings::text(*settings::find("scorer"), rc.options.tune)},
                {k::kScorerNote, r.scorer_note},
                {k::kScoredRepeat, 0}};
    if (r.scorer == "cpu") {
        out[k::kScorerThreads] =
            scoringThreads(rc.options.control.scoring_threads, int(rc.settings.width), int(rc.settings.height));
        out[k::kScorerFrames] = scorerFrames(int(rc.settings.width), int(rc.settings.height));
    }
    if (!r.reference_ms.empty()) out[k::kReferenceGpuMsMedian] = median(r.reference_ms);
    return out;
}

// One variant (or sweep configuration): what ran, its settings, its description from the
// renderer, the resolve's bandwidth, the frame alignment check and the headline numbers.
json variantJson(const RunContext& rc, const VariantRun& vr, const VariantSummary& sm) {
    namespace k = rundir::run::variant;
    json passes = json::array();
    for (const auto& p : vr.passes_ran) passes.push_back({{k::pass::kName, p}, {k::pass::kRan, true}});
    for (const auto& [p, reason] : vr.left_out)
        passes.push_back({{k::pass::kName, p}, {k::pass::kRan, false}, {k::pass::kReason, reason}});
    json v = {{k::kName, vr.name},
              {k::kStatus, vr.status},
              {k::kPipeline, rc.settings.deferred ? "deferred" : "forward"},
              {k::kPasses, passes}};
    if (!vr.note.empty()) v[k::kNote] = vr.note;
    if (!vr.settings.empty() || vr.variant != vr.name) {
        v[k::kVariant] = vr.variant;
        v[k::kSpeedupBaseline] = vr.baseline;
        json set = json::object();
        for (const auto& st : vr.settings) set[st.name] = st.word.empty() ? json(st.value) : json(st.word);
        v[k::kSettings] = set;
    }
    for (const auto& [key, value] : vr.description) v[key] = value;
    resolveBandwidth(v, sm, rc.results.copy_bandwidth);
    if (vr.alignment) {
        namespace fa = k::frame_alignment;
        const auto& a = *vr.alignment;
        auto finite = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
        v[k::kFrameAlignment] = {{fa::kFrame, a.frame}, {fa::kPsnrDbSame, finite(a.psnr_same)},
                                 {fa::kPsnrDbPrev, finite(a.psnr_prev)}, {fa::kPsnrDbNext, finite(a.psnr_next)},
                                 {fa::kOk, a.ok}};
    }
    if (sm.frames > 0) {
        v[k::kGpuMsMedian] = sm.gpu_ms_median;
        v[k::kSpeedup] = number(sm.speedup);
        v[k::kSpeedupLow] = number(sm.speedup_low);
        v[k::kSpeedupHigh] = number(sm.speedup_high);
        v[k::kPsnrDb] = number(sm.psnr_db);
        v[k::kPsnrDbIsInf] = sm.psnr_db && std::isinf(*sm.psnr_db);
        v[k::kSsimMean] = number(sm.ssim_mean);
        v[k::kFlipMean] = number(sm.flip_mean);
        v[k::kCvvdpJod] = number(sm.cvvdp_jod);
        v[k::kEci] = number(sm.eci);
        v[k::kRenderWidth] = sm.render_width;
        v[k::kRenderHeight] = sm.render_height;
    }
    return v;
}

// The validation layer's counts and its first messages.
json validationJson(vk::Context& ctx) {
    namespace k = rundir::run::validation;
    auto& val = ctx.validation;
    json messages = json::array();
    {
        std::lock_guard lock(val.mutex);
        for (const auto& m : val.first_messages) messages.push_back(m);
    }
    return {{k::kEnabled, ctx.validation_enabled},
            {k::kErrors, val.errors.load()},
            {k::kWarnings, val.warnings.load()},
            {k::kMessages, val.errors.load() + val.warnings.load()},
            {k::kFirstMessages, messages}};
}

// Where the wall time went (harness/base/wall_account.h): the main thread's parts, which add up
// to `seconds`, and the workers' CPU time per task, which overlaps them.
json wallJson(const WallAccount& wall) {
    namespace k = rundir::run::wall;
    json parts = json::object(), workers = json::object();
    for (size_t i = 0; i < kWallParts; ++i) parts[wallPartKey(WallPart(i))] = wall.part(WallPart(i));
    for (size_t i = 0; i < kWorkerTasks; ++i) workers[workerTaskKey(WorkerTask(i))] = wall.worker(WorkerTask(i));
    json rss = json::object();
    for (const auto& [after, mib] : wall.peakRss()) rss[after] = mib;
    return {{k::kSeconds, wall.total()}, {k::kPartsS, parts}, {k::kWorkerCpuS, workers}, {k::kPeakRssMibAfter, rss}};
}

// What the run needed and had (harness/run/memory_check.h).
json memoryJson(const MemoryFigures& m) {
    namespace k = rundir::run::memory;
    auto maybe = [](const std::optional<double>& v) { return v ? json(*v) : json(); };
    json after = json::array();
    for (const auto& r : m.after)
        after.push_back({{k::after::kAfter, r.after},
                         {k::after::kPeakRssMib, r.peak_rss_mib},
                         {k::after::kDeviceAllocatedMib, r.device_allocated_mib},
                         {k::after::kDeviceUsageMib, maybe(r.device_usage_mib)}});
    double peak_rss = 0;
    std::optional<double> device_usage;
    for (const auto& r : m.after) {
        peak_rss = std::max(peak_rss, r.peak_rss_mib);
        if (r.device_usage_mib) device_usage = std::max(device_usage.value_or(0), *r.device_usage_mib);
    }
    return {{k::kEstimateHostMib, m.host_estimate_mib},
            {k::kEstimateDeviceMib, m.device_estimate_mib},
            {k::kHostLimitMib, m.host_limit_mib},
            {k::kHostLimitFrom, m.host_limit_from},
            {k::kDeviceLimitMib, m.device_limit_mib},
            {k::kDeviceLimitFrom, m.device_limit_from},
            {k::kPeakRssMib, peak_rss},
            {k::kDeviceAllocatedPeakMib, m.device_allocated_peak_mib},
            {k::kHostVisibleAllocatedPeakMib, m.host_visible_allocated_peak_mib},
            {k::kDeviceUsagePeakMib, maybe(device_usage)},
            {k::kDeviceBudgetMib, maybe(m.device_budget_mib)},
            {k::kDeviceHeapMib, m.device_heap_mib},
            {k::kAfter, after}};
}

// What the run directory holds.
std::vector<std::string> fileList(const RunContext& rc) {
    std::vector<std::string> files = {rundir::kFramesCsv, rundir::kSummaryCsv, rundir::kRunJson};
    if (rc.options.save_frames) files.push_back(std::string(rundir::kFramesDir) + "/");
    files.insert(files.end(), rc.results.worst_files.begin(), rc.results.worst_files.end());
    files.push_back(rundir::kReportHtml);
    return files;
}

}  // namespace

// The worst frames and their files (each written once, however many entries name it).
json worstJson(const std::vector<WorstFrame>& worst) {
    namespace k = rundir::run::worst;
    json out = json::array();
    for (const auto& wf : worst) {
        json files = json::object(), page = json::object();
        for (const auto& [what, file] : wf.files) files[what] = file;
        for (const auto& [what, file] : wf.page) page[what] = file;
        out.push_back({{k::kVariant, wf.variant}, {k::kKind, wf.kind}, {k::kFrame, wf.frame},
                       {k::kValue, number(wf.value)}, {k::kFiles, files}, {k::kPage, page}});
    }
    return out;
}

std::string isoDate() {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

void writeRunJson(const std::filesystem::path& file, const RunContext& rc, const std::vector<VariantSummary>& summaries,
                  size_t nan_cells) {
    using namespace rundir::run;
    const RunResults& r = rc.results;
    json j;
    j[kTool] = {{tool::kName, "cbrbench"}, {tool::kVersion, CBR_VERSION}, {tool::kCommit, CBR_GIT_COMMIT}};
    j[kDate] = isoDate();
    j[kCommandLine] = rc.options.control.argv;
    j[kHost] = hostJson();
    j[kWallSeconds] = r.seconds;
    j[kFirstFrameWallSeconds] = r.first_frame_seconds;
    j[kDevice] = deviceJson(rc);
    j[kSettings] = settingsJson(rc);
    j[kScene] = sceneJson(rc);
    j[kPath] = pathJson(rc);
    j[kMetrics] = metricsJson(rc);
    j[kReferenceVariant] = std::string(variants::referenceVariant().name);  // what the others are timed and scored against
    json list = json::array();
    for (size_t i = 0; i < r.variants.size(); ++i) list.push_back(variantJson(rc, r.variants[i], summaries[i]));
    j[kVariants] = list;
    j[kNonFiniteCells] = nan_cells;  // NaNs written as empty CSV cells (0 in a healthy run)
    j[kValidation] = validationJson(rc.ctx);
    j[kFiles] = fileList(rc);
    j[kWorst] = worstJson(r.worst);
    j[kHealth] = healthJson(r);
    if (rc.wall) j[kWall] = wallJson(*rc.wall);
    if (!r.memory.after.empty()) j[kMemory] = memoryJson(r.memory);
    reports::writeTextAtomically(file, j.dump(2) + "\n");
}

void updateRunJsonWall(const std::filesystem::path& dir, const RunContext& rc) {
    using namespace rundir::run;
    if (!rc.wall) return;
    const auto file = dir / rundir::kRunJson;
    std::ifstream in(file);
    json j = json::parse(in);
    j[kWallSeconds] = rc.wall->total();
    j[kWall] = wallJson(*rc.wall);
    if (!rc.results.memory.after.empty()) j[kMemory] = memoryJson(rc.results.memory);
    reports::writeTextAtomically(file, j.dump(2) + "\n");
}

}  // namespace cbr::harness
