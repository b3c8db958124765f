// run.json: the run's device, settings, scene, path, metrics, variants and validation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>
#include <unistd.h>

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
#include "settings/table.h"

namespace cbr::harness {
namespace {

using nlohmann::json;

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 1469598103934665603ull) {
    auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

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
    nlohmann::json list = nlohmann::json::array();
    for (const auto& a : s.animations)
        list.push_back({{"name", a.name}, {"index", a.gltf_index}, {"length_s", a.length},
                        {"channels", a.channels.size()}, {"played", a.played}});
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
    const RunResults& r = rc.results;
    const auto& d = rc.ctx.description;
    json out = {{"index", d.index},
                {"name", d.name},
                {"type", d.device_type},
                {"vendor_id", d.vendor_id},
                {"device_id", d.device_id},
                {"driver_name", d.driver_name},
                {"driver_info", d.driver_info},
                {"driver_id", d.driver_id},
                {"driver_version", d.driver_version},
                {"api_version", d.api_version},
                {"is_lavapipe", d.is_lavapipe},
                {"timestamp_period_ns", rc.ctx.caps.timestamp_period_ns},
                {"timestamp_valid_bits", rc.ctx.caps.timestamp_valid_bits},
                {"pipeline_statistics", rc.ctx.caps.pipeline_statistics},
                {"target_clear", rc.ctx.compute_clears ? "compute" : "load-op"},
                {"target_clear_rule", rc.ctx.target_clear_rule},
                {"copy_bandwidth_gb_per_s", r.copy_bandwidth.gb_per_s},
                {"transfer_bandwidth_gb_per_s", r.copy_bandwidth.transfer_gb_per_s},
                {"copy_bandwidth_rule",
                 r.copy_bandwidth.copies == 0
                     ? std::string("not measured (lavapipe's timestamps do not bracket a lone copy)")
                     : "median of " + std::to_string(r.copy_bandwidth.copies) + " compute-shader copies (16-byte " +
                           "loads and stores) of " + std::to_string(int(r.copy_bandwidth.buffer_mib)) +
                           " MiB between device-local buffers, bytes read + written; transfer_bandwidth_gb_per_s: "
                           "the same with vkCmdCopyBuffer"}};
    if (d.is_lavapipe)
        out["timing_note"] =
            "lavapipe timestamps measure CPU rasterisation: ratios between variants are meaningful, absolute times "
            "are not GPU times";
    return out;
}

// The render settings every configuration starts from, and the run's shape.
json settingsJson(const RunContext& rc) {
    const RunResults& r = rc.results;
    const auto& s = rc.settings;
    json out = {{"width", s.width},
            {"height", s.height},
            {"pipeline", s.deferred ? "deferred" : "forward"},
            {"frames", r.frames},
            {"repeat", r.repeats},
            {"warmup_frames", rc.options.warmup},
            {"warmup_rule", "at least warmup_frames of the path's first pose per variant and timed repetition, then until steady (health.rule; frames used: health.variants)"},
            {"variant_order", r.order},
            {"drr_control",
             {{"min_scale", s.drr_control.min_scale},
              {"max_scale", s.drr_control.max_scale},
              {"dead_band", s.drr_control.dead_band},
              {"step", s.drr_control.step}}},
            {"frames_in_flight", s.frames_in_flight},
            {"depth", "reversed-Z, D32_SFLOAT"},
            {"save_frames", rc.options.save_frames},
            {"cvvdp_fps", rc.results.cvvdp_fps}};
    for (const auto& row : settings::table())
        if (row.run_json)
            out[row.column] = row.json_float ? json(float(row.field.get(s))) : settings::toJson(row, s);
    return out;
}

// The scene: source, content hash, counts, load cost, animations and cameras.
json sceneJson(const RunContext& rc) {
    const RunResults& r = rc.results;
    const auto& si = rc.scene.info;
    json out = {{"name", rc.scene.name},
                {"source", rc.scene.source},
                {"hash", sceneHash(rc.scene)},
                {"triangles", si.triangles},
                {"opaque_draws", si.opaque_draws},
                {"masked_draws", si.masked_draws},
                {"blend_draws", si.blend_draws},
                {"animated_instances", si.animated_instances},
                {"lights", rc.scene.lights.size()},
                {"default_light", si.default_light},
                {"recentred_meshes", si.recentred_meshes},
                {"bounds_min", {rc.scene.bounds_min.x, rc.scene.bounds_min.y, rc.scene.bounds_min.z}},
                {"bounds_max", {rc.scene.bounds_max.x, rc.scene.bounds_max.y, rc.scene.bounds_max.z}},
                {"warnings", rc.scene.warnings}};
    addSceneCost(out, rc.scene, r.scene_load);
    out["animations"] = animationsJson(rc.scene);
    out["cameras"] = nlohmann::json::array();
    for (const auto& c : rc.scene.cameras)
        out["cameras"].push_back({{"name", c.name}, {"type", c.perspective ? "perspective" : "orthographic"}});
    return out;
}

// The camera path: source, hash of the sampled poses and times, frames and cuts.
json pathJson(const RunContext& rc) {
    json out = {{"name", rc.path.name},
                {"source", rc.options.path},
                {"hash", pathHash(rc.poses, rc.times)},
                {"fps", rc.path.fps},
                {"duration_s", rc.path.duration()},
                {"frames", rc.poses.size()},
                {"cuts", std::count_if(rc.poses.begin(), rc.poses.end(), [](const auto& p) { return p.cut; })}};
    if (rc.placement) out["placement"] = placementJson(*rc.placement, rc.scene.placement);
    return out;
}

// How quality is measured, and against which reference.
json metricsJson(const RunContext& rc) {
    const RunResults& r = rc.results;
    json out = {{"on", "8-bit sRGB display image, as the saved PNGs, converted to [0,1]"},
                {"reference", "full at the same frame, unjittered, one sample per pixel"},
                {"psnr", "10 log10(1/MSE), MSE over all pixels and RGB channels; sequence PSNR from the mean MSE"},
                {"ssim", "Wang et al. 2004: Gaussian 11x11 sigma 1.5, K1 0.01, K2 0.03, L 1, population "
                         "statistics, 5-pixel border excluded, mean of per-channel SSIM"},
                {"eci", "edge crawl index: luma blurred with sigma 1, e = Y(V) - Y(R), e_t against e_t-1 "
                        "warped with the renderer's motion vectors (bilinear), on reference edges (Sobel of blurred "
                        "reference luma > 0.02, dilated 1 px), 4 px margin, disocclusions (5% view-depth mismatch) "
                        "and pairs across cuts excluded; sequence ECI pools numerators and denominators"},
                {"flip", "LDR-FLIP (Andersson et al. 2020) as NVIDIA's tool v1.6 computes it: mean of the error "
                         "map and weighted quartiles (pixels weighted by their error); summary flip_mean is the mean "
                         "of the per-frame means"},
                {"flip_ppd", settings::flipPpd(rc.options.tune)},
                {"cvvdp", "ColorVideoVDP (Mantiuk, Hammou, Hanji 2024, model " + std::string(metrics::cvvdpModelVersion()) +
                              ") on the display model settings.display at settings.cvvdp_fps frames per second: JOD, 10 "
                              "= no visible difference, one JOD less = 75% of viewers prefer the better; frames.csv "
                              "cvvdp_jod is each frame's, summary cvvdp_jod the sequence's (docs/method/cvvdp.md)"},
                {"reference_kind", rc.options.tune.reference == settings::Reference::Ssaa
                                       ? "ssaa: " + std::to_string(rc.options.tune.ssaa) + "x" +
                                             std::to_string(rc.options.tune.ssaa) + " samples per pixel, box filter in HDR"
                                       : std::string("full")},
                // The library --save-frames writes through; loaded only then (OpenImageIO's
                // plugins are 80 MB of a run's memory), the worst frames' encoders otherwise.
                {"image_io", rc.options.save_frames ? metrics::imageIoBackend() : metrics::encodeBackend()},
                {"scorer", r.scorer},
                {"scorer_requested", settings::text(*settings::find("scorer"), rc.options.tune)},
                {"scorer_note", r.scorer_note},
                {"scored_repeat", 0}};
    if (r.scorer == "cpu") {
        out["scorer_threads"] =
            scoringThreads(rc.options.control.scoring_threads, int(rc.settings.width), int(rc.settings.height));
        out["scorer_frames"] = scorerFrames(int(rc.settings.width), int(rc.settings.height));
    }
    if (!r.reference_ms.empty()) out["reference_gpu_ms_median"] = median(r.reference_ms);
    return out;
}

// One variant (or sweep configuration): what ran, its settings, its description from the
// renderer, the resolve's bandwidth, the frame alignment check and the headline numbers.
json variantJson(const RunContext& rc, const VariantRun& vr, const VariantSummary& sm) {
    json passes = json::array();
    for (const auto& p : vr.passes_ran) passes.push_back({{"name", p}, {"ran", true}});
    for (const auto& [p, reason] : vr.left_out) passes.push_back({{"name", p}, {"ran", false}, {"reason", reason}});
    json v = {{"name", vr.name},
              {"status", vr.status},
              {"pipeline", rc.settings.deferred ? "deferred" : "forward"},
              {"passes", passes}};
    if (!vr.note.empty()) v["note"] = vr.note;
    if (!vr.settings.empty() || vr.variant != vr.name) {
        v["variant"] = vr.variant;
        v["speedup_baseline"] = vr.baseline;
        json set = json::object();
        for (const auto& st : vr.settings) set[st.name] = st.word.empty() ? json(st.value) : json(st.word);
        v["settings"] = set;
    }
    for (const auto& [key, value] : vr.description) v[key] = value;
    resolveBandwidth(v, sm, rc.results.copy_bandwidth);
    if (vr.alignment) {
        const auto& a = *vr.alignment;
        auto finite = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
        v["frame_alignment"] = {{"frame", a.frame}, {"psnr_db_same", finite(a.psnr_same)},
                                {"psnr_db_prev", finite(a.psnr_prev)}, {"psnr_db_next", finite(a.psnr_next)},
                                {"ok", a.ok}};
    }
    if (sm.frames > 0) {
        v["gpu_ms_median"] = sm.gpu_ms_median;
        v["speedup_vs_full"] = number(sm.speedup);
        v["speedup_ci_low"] = number(sm.speedup_low);
        v["speedup_ci_high"] = number(sm.speedup_high);
        v["psnr_db"] = number(sm.psnr_db);
        v["psnr_db_is_inf"] = sm.psnr_db && std::isinf(*sm.psnr_db);
        v["ssim_mean"] = number(sm.ssim_mean);
        v["flip_mean"] = number(sm.flip_mean);
        v["cvvdp_jod"] = number(sm.cvvdp_jod);
        v["eci"] = number(sm.eci);
        v["render_width"] = sm.render_width;
        v["render_height"] = sm.render_height;
    }
    return v;
}

// The validation layer's counts and its first messages.
json validationJson(vk::Context& ctx) {
    auto& val = ctx.validation;
    json messages = json::array();
    {
        std::lock_guard lock(val.mutex);
        for (const auto& m : val.first_messages) messages.push_back(m);
    }
    return {{"enabled", ctx.validation_enabled},
            {"errors", val.errors.load()},
            {"warnings", val.warnings.load()},
            {"messages", val.errors.load() + val.warnings.load()},
            {"first_messages", messages}};
}

// Where the wall time went (harness/base/wall_account.h): the main thread's parts, which add up
// to `seconds`, and the workers' CPU time per task, which overlaps them.
json wallJson(const WallAccount& wall) {
    json parts = json::object(), workers = json::object();
    for (size_t i = 0; i < kWallParts; ++i) parts[wallPartKey(WallPart(i))] = wall.part(WallPart(i));
    for (size_t i = 0; i < kWorkerTasks; ++i) workers[workerTaskKey(WorkerTask(i))] = wall.worker(WorkerTask(i));
    json rss = json::object();
    for (const auto& [after, mib] : wall.peakRss()) rss[after] = mib;
    return {{"seconds", wall.total()}, {"parts_s", parts}, {"worker_cpu_s", workers}, {"peak_rss_mib_after", rss}};
}

// What the run needed and had (harness/run/memory_check.h).
json memoryJson(const MemoryFigures& m) {
    auto maybe = [](const std::optional<double>& v) { return v ? json(*v) : json(); };
    json after = json::array();
    for (const auto& r : m.after)
        after.push_back({{"after", r.after},
                         {"peak_rss_mib", r.peak_rss_mib},
                         {"device_allocated_mib", r.device_allocated_mib},
                         {"device_usage_mib", maybe(r.device_usage_mib)}});
    double peak_rss = 0;
    std::optional<double> device_usage;
    for (const auto& r : m.after) {
        peak_rss = std::max(peak_rss, r.peak_rss_mib);
        if (r.device_usage_mib) device_usage = std::max(device_usage.value_or(0), *r.device_usage_mib);
    }
    return {{"estimate_host_mib", m.host_estimate_mib},
            {"estimate_device_mib", m.device_estimate_mib},
            {"host_limit_mib", m.host_limit_mib},
            {"host_limit_from", m.host_limit_from},
            {"device_limit_mib", m.device_limit_mib},
            {"device_limit_from", m.device_limit_from},
            {"peak_rss_mib", peak_rss},
            {"device_allocated_peak_mib", m.device_allocated_peak_mib},
            {"host_visible_allocated_peak_mib", m.host_visible_allocated_peak_mib},
            {"device_usage_peak_mib", maybe(device_usage)},
            {"device_budget_mib", maybe(m.device_budget_mib)},
            {"device_heap_mib", m.device_heap_mib},
            {"after", after}};
}

// What the run directory holds.
std::vector<std::string> fileList(const RunContext& rc) {
    std::vector<std::string> files = {"frames.csv", "summary.csv", "run.json"};
    if (rc.options.save_frames) files.push_back("frames/");
    files.insert(files.end(), rc.results.worst_files.begin(), rc.results.worst_files.end());
    files.push_back("report.html");
    return files;
}

}  // namespace

// The worst frames and their files (each written once, however many entries name it).
json worstJson(const std::vector<WorstFrame>& worst) {
    json out = json::array();
    for (const auto& wf : worst) {
        json files = json::object(), page = json::object();
        for (const auto& [what, file] : wf.files) files[what] = file;
        for (const auto& [what, file] : wf.page) page[what] = file;
        out.push_back({{"variant", wf.variant}, {"kind", wf.kind}, {"frame", wf.frame}, {"value", number(wf.value)},
                       {"files", files}, {"page", page}});
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
    const RunResults& r = rc.results;
    json j;
    j["tool"] = {{"name", "cbrbench"}, {"version", CBR_VERSION}, {"commit", CBR_GIT_COMMIT}};
    j["date"] = isoDate();
    j["command_line"] = rc.options.control.argv;
    j["host"] = hostJson();
    j["wall_seconds"] = r.seconds;
    j["first_frame_wall_seconds"] = r.first_frame_seconds;
    j["device"] = deviceJson(rc);
    j["settings"] = settingsJson(rc);
    j["scene"] = sceneJson(rc);
    j["path"] = pathJson(rc);
    j["metrics"] = metricsJson(rc);
    j["reference_variant"] = std::string(variants::referenceVariant().name);  // what the others are timed and scored against
    json variants = json::array();
    for (size_t i = 0; i < r.variants.size(); ++i) variants.push_back(variantJson(rc, r.variants[i], summaries[i]));
    j["variants"] = variants;
    j["non_finite_cells"] = nan_cells;  // NaNs written as empty CSV cells (0 in a healthy run)
    j["validation"] = validationJson(rc.ctx);
    j["files"] = fileList(rc);
    j["worst"] = worstJson(r.worst);
    j["health"] = healthJson(r);
    if (rc.wall) j["wall"] = wallJson(*rc.wall);
    if (!r.memory.after.empty()) j["memory"] = memoryJson(r.memory);
    reports::writeTextAtomically(file, j.dump(2) + "\n");
}

void updateRunJsonWall(const std::filesystem::path& dir, const RunContext& rc) {
    if (!rc.wall) return;
    const auto file = dir / "run.json";
    std::ifstream in(file);
    json j = json::parse(in);
    j["wall_seconds"] = rc.wall->total();
    j["wall"] = wallJson(*rc.wall);
    if (!rc.results.memory.after.empty()) j["memory"] = memoryJson(rc.results.memory);
    reports::writeTextAtomically(file, j.dump(2) + "\n");
}

}  // namespace cbr::harness
