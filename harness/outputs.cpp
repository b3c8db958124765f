// frames.csv, summary.csv and run.json: one schema each, documented in the README.
#include "harness/outputs.h"
#include "harness/resolve_bandwidth.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <nlohmann/json.hpp>

#include "harness/stats.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "renderer/vk/context.h"
#include "reports/csv.h"
#include "reports/sweep.h"

namespace cbr::harness {
namespace {

using reports::Cell;

// Per-frame statistic names (checkerboard pixel classes) in order of first appearance.
std::vector<std::string> statColumns(const RunResults& r) {
    std::vector<std::string> names;
    for (const auto& row : r.rows)
        for (const auto& [name, value] : row.stats)
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    return names;
}

// Pass names in order of first appearance across variants: the per-pass columns.
std::vector<std::string> passColumns(const RunResults& r) {
    std::vector<std::string> names;
    for (const auto& row : r.rows)
        for (const auto& p : row.passes)
            if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
    return names;
}

Cell optional(const std::optional<double>& v) { return v ? Cell(*v) : Cell(); }

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

std::string isoDate() {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

nlohmann::json number(const std::optional<double>& v) {
    if (!v) return nullptr;
    if (!std::isfinite(*v)) return nullptr;  // JSON has no inf: null plus an *_is_inf flag
    return *v;
}

// Reports NaNs that reached a table (written as empty cells) instead of hiding them.
size_t reportNaNs(const reports::CsvTable& table, const char* file) {
    if (table.nanCells() == 0) return 0;
    std::string where;
    for (const auto& w : table.nanWhere()) where += (where.empty() ? "" : ", ") + w;
    std::fprintf(stderr, "cbrbench: warning: %zu non-finite value(s) written as empty cells in %s (%s)\n",
                 table.nanCells(), file, where.c_str());
    return table.nanCells();
}

size_t writeFramesCsv(const std::filesystem::path& file, const RunResults& r, uint32_t width, uint32_t height) {
    std::vector<std::string> passes = passColumns(r);
    std::vector<std::string> cols = {"variant",      "repeat",        "frame",        "time_s",
                                     "width",        "height",        "render_width", "render_height",
                                     "render_scale", "gpu_ms",        "timing_ok",    "psnr_db",
                                     "ssim",         "ssim_luma",     "mse",          "eci",
                                     "flicker_ratio", "crawl_valid_fraction", "fs_invocations",
                                     "status",       "note"};
    std::vector<std::string> stats = statColumns(r);
    cols.insert(cols.end(), stats.begin(), stats.end());
    for (const auto& p : passes) cols.push_back("gpu_ms_" + p);
    // Invocation columns only for passes that report them (graphics passes, where the
    // device has pipeline statistics).
    for (const auto& p : passes) {
        bool reported = std::any_of(r.rows.begin(), r.rows.end(), [&](const FrameRow& row) {
            return std::any_of(row.passes.begin(), row.passes.end(),
                               [&](const auto& pt) { return pt.name == p && pt.fs_invocations >= 0; });
        });
        if (reported) cols.push_back("fs_invocations_" + p);
    }
    reports::CsvTable table(cols);
    for (const auto& row : r.rows) {
        std::map<std::string, Cell> m;
        m["variant"] = row.variant;
        m["repeat"] = row.repeat;
        m["frame"] = row.frame;
        m["time_s"] = row.time_s;
        m["width"] = unsigned(width);
        m["height"] = unsigned(height);
        m["status"] = row.status;
        std::string note = row.note;
        if (!row.quality.note.empty()) note += (note.empty() ? "" : "; ") + row.quality.note;
        m["note"] = note;
        if (row.status == "ok") {
            m["render_width"] = unsigned(row.render_width);
            m["render_height"] = unsigned(row.render_height);
            m["render_scale"] = row.render_scale;
            m["gpu_ms"] = row.gpu_ms;
            m["timing_ok"] = row.timing_ok;
            m["psnr_db"] = optional(row.quality.psnr_db);
            m["ssim"] = optional(row.quality.ssim);
            m["ssim_luma"] = optional(row.quality.ssim_luma);
            m["mse"] = optional(row.quality.mse);
            m["eci"] = optional(row.quality.eci);
            m["flicker_ratio"] = optional(row.quality.flicker_ratio);
            m["crawl_valid_fraction"] = optional(row.quality.crawl_valid_fraction);
            for (const auto& [name, value] : row.stats) m[name] = value;
            long long fs = 0;
            bool any = false;
            for (const auto& pt : row.passes) {
                m["gpu_ms_" + pt.name] = pt.gpu_ms;
                if (pt.fs_invocations >= 0) {
                    m["fs_invocations_" + pt.name] = (long long)pt.fs_invocations;
                    fs += pt.fs_invocations;
                    any = true;
                }
            }
            if (any) m["fs_invocations"] = fs;
        }
        table.addRow(m);
    }
    reports::writeTextAtomically(file, table.str());
    return reportNaNs(table, "frames.csv");
}

}  // namespace

std::vector<VariantSummary> summarize(const RunResults& r) {
    std::vector<VariantSummary> out;
    // Each baseline's (full's) per-(repeat, frame) times, for paired ratios; a sweep pairs
    // each configuration with the full configuration at its shading cost.
    std::map<std::string, std::map<std::pair<int, int>, double>> baseline_ms;
    for (const auto& vr : r.variants) baseline_ms[vr.baseline];
    for (const auto& row : r.rows)
        if (row.status == "ok" && baseline_ms.count(row.variant))
            baseline_ms[row.variant][{row.repeat, row.frame}] = row.gpu_ms;

    for (const auto& vr : r.variants) {
        const auto& full_ms = baseline_ms[vr.baseline];
        VariantSummary s;
        s.variant = vr.name;
        s.status = vr.status;
        s.note = vr.note;
        std::vector<double> ms, psnr, ssim, ssim_luma, mse, fs, eci, flicker;
        double crawl_num = 0, crawl_den = 0;
        std::vector<std::vector<double>> per_rep(size_t(r.repeats)), ratios(size_t(r.repeats));
        std::map<std::string, std::vector<double>> pass_ms, stat_values;
        std::vector<std::string> pass_order, stat_order;
        std::vector<double> widths, heights;
        for (const auto& row : r.rows) {
            if (row.variant != vr.name || row.status != "ok") continue;
            ms.push_back(row.gpu_ms);
            per_rep[size_t(row.repeat)].push_back(row.gpu_ms);
            widths.push_back(row.render_width);
            heights.push_back(row.render_height);
            auto f = full_ms.find({row.repeat, row.frame});
            if (f != full_ms.end() && row.gpu_ms > 0) ratios[size_t(row.repeat)].push_back(f->second / row.gpu_ms);
            for (const auto& [name, value] : row.stats) {
                if (!stat_values.count(name)) stat_order.push_back(name);
                stat_values[name].push_back(value);
            }
            double frame_fs = 0;
            bool any_fs = false;
            for (const auto& pt : row.passes) {
                if (!pass_ms.count(pt.name)) pass_order.push_back(pt.name);
                pass_ms[pt.name].push_back(pt.gpu_ms);
                if (pt.fs_invocations >= 0) {
                    frame_fs += double(pt.fs_invocations);
                    any_fs = true;
                }
            }
            if (any_fs) fs.push_back(frame_fs);
            if (row.quality.mse) mse.push_back(*row.quality.mse);
            if (row.quality.psnr_db) psnr.push_back(*row.quality.psnr_db);
            if (row.quality.ssim) ssim.push_back(*row.quality.ssim);
            if (row.quality.ssim_luma) ssim_luma.push_back(*row.quality.ssim_luma);
            if (row.quality.eci) {
                eci.push_back(*row.quality.eci);
                crawl_num += row.quality.crawl_numerator;
                crawl_den += row.quality.crawl_denominator;
            }
            if (row.quality.flicker_ratio) flicker.push_back(*row.quality.flicker_ratio);
        }
        if (ms.empty()) {
            if (s.status == "ok") s.status = "failed", s.note = "no frame completed";
            out.push_back(s);
            continue;
        }
        s.frames = int(ms.size()) / std::max(1, r.repeats);
        s.gpu_ms_median = median(ms);
        s.gpu_ms_p5 = percentile(ms, 5);
        s.gpu_ms_p95 = percentile(ms, 95);
        s.gpu_ms_p99 = percentile(ms, 99);
        s.gpu_ms_mean = mean(ms);
        std::vector<double> rep_medians;
        for (const auto& rep : per_rep)
            if (!rep.empty()) rep_medians.push_back(median(rep));
        s.noise_cv = coefficientOfVariation(rep_medians);
        {
            std::vector<std::vector<double>> rep_ms;
            for (const auto& rep : per_rep)
                if (!rep.empty()) rep_ms.push_back(rep);
            if (rep_ms.size() >= 2) {
                Interval ci = bootstrapMedianOverRuns(rep_ms);
                s.gpu_ms_ci_low = ci.low;
                s.gpu_ms_ci_high = ci.high;
            }
        }
        std::vector<double> pooled;
        std::vector<std::vector<double>> runs;
        for (const auto& rr : ratios)
            if (!rr.empty()) {
                pooled.insert(pooled.end(), rr.begin(), rr.end());
                runs.push_back(rr);
            }
        if (!pooled.empty()) {
            s.speedup = median(pooled);
            if (runs.size() >= 2) {
                Interval ci = bootstrapMedianOverRuns(runs);
                s.speedup_low = ci.low;
                s.speedup_high = ci.high;
            }
        }
        if (!mse.empty()) {
            // Sequence PSNR from the mean of the per-frame MSEs (metrics.md).
            s.psnr_db = metrics::psnrFromMse(mean(mse));
            s.psnr_db_min = *std::min_element(psnr.begin(), psnr.end());
            s.psnr_db_p5 = percentile(psnr, 5);
        }
        if (!ssim.empty()) {
            s.ssim_mean = mean(ssim);
            s.ssim_min = *std::min_element(ssim.begin(), ssim.end());
        }
        if (!ssim_luma.empty()) s.ssim_luma_mean = mean(ssim_luma);
        if (!eci.empty()) {
            // Sequence ECI pools numerators and denominators (metrics.md); crawl comes in
            // bursts, so p95 and max besides.
            s.eci = crawl_den > 0 ? std::sqrt(crawl_num / crawl_den) : 0.0;
            s.eci_p95 = percentile(eci, 95);
            s.eci_max = *std::max_element(eci.begin(), eci.end());
        }
        if (!flicker.empty()) s.flicker_ratio_mean = mean(flicker);
        if (!fs.empty()) s.fs_invocations_median = median(fs);
        s.render_width = uint32_t(median(widths));
        s.render_height = uint32_t(median(heights));
        for (const auto& name : pass_order) s.pass_ms_median.push_back({name, median(pass_ms[name])});
        for (const auto& name : stat_order) s.stats_mean.push_back({name, mean(stat_values[name])});
        out.push_back(s);
    }
    return out;
}

void writeOutputs(const std::filesystem::path& dir, const RunContext& rc) {
    const RunResults& r = rc.results;
    size_t nan_cells = writeFramesCsv(dir / "frames.csv", r, rc.settings.width, rc.settings.height);
    auto summaries = summarize(r);

    std::vector<std::string> passes = passColumns(r);
    std::vector<std::string> cols = {"variant",        "status",         "frames",          "repeats",
                                     "render_width",   "render_height",  "gpu_ms_median",   "gpu_ms_p5",
                                     "gpu_ms_p95",     "gpu_ms_p99",     "gpu_ms_mean",     "gpu_ms_cv",
                                     "speedup_vs_full", "speedup_ci_low", "speedup_ci_high", "psnr_db_mean",
                                     "psnr_db_min",    "psnr_db_p5",     "ssim_mean",       "ssim_min",
                                     "ssim_luma_mean", "eci",            "eci_p95",         "eci_max",
                                     "flicker_ratio_mean", "fs_invocations_median", "note"};
    for (const auto& p : passes) cols.push_back("gpu_ms_" + p + "_median");
    for (const auto& st : statColumns(r)) cols.push_back(st + "_mean");
    reports::CsvTable table(cols);
    for (const auto& s : summaries) {
        std::map<std::string, Cell> m;
        m["variant"] = s.variant;
        m["status"] = s.status;
        m["note"] = s.note;
        m["repeats"] = r.repeats;
        if (s.frames > 0) {
            m["frames"] = s.frames;
            m["render_width"] = unsigned(s.render_width);
            m["render_height"] = unsigned(s.render_height);
            m["gpu_ms_median"] = s.gpu_ms_median;
            m["gpu_ms_p5"] = s.gpu_ms_p5;
            m["gpu_ms_p95"] = s.gpu_ms_p95;
            m["gpu_ms_p99"] = s.gpu_ms_p99;
            m["gpu_ms_mean"] = s.gpu_ms_mean;
            m["gpu_ms_cv"] = s.noise_cv;
            m["speedup_vs_full"] = optional(s.speedup);
            m["speedup_ci_low"] = optional(s.speedup_low);
            m["speedup_ci_high"] = optional(s.speedup_high);
            m["psnr_db_mean"] = optional(s.psnr_db);
            m["psnr_db_min"] = optional(s.psnr_db_min);
            m["psnr_db_p5"] = optional(s.psnr_db_p5);
            m["ssim_mean"] = optional(s.ssim_mean);
            m["ssim_min"] = optional(s.ssim_min);
            m["ssim_luma_mean"] = optional(s.ssim_luma_mean);
            m["eci"] = optional(s.eci);
            m["eci_p95"] = optional(s.eci_p95);
            m["eci_max"] = optional(s.eci_max);
            m["flicker_ratio_mean"] = optional(s.flicker_ratio_mean);
            m["fs_invocations_median"] = optional(s.fs_invocations_median);
            for (const auto& [name, v] : s.pass_ms_median) m["gpu_ms_" + name + "_median"] = v;
            for (const auto& [name, v] : s.stats_mean) m[name + "_mean"] = v;
        }
        table.addRow(m);
    }
    table.write(dir / "summary.csv");
    nan_cells += reportNaNs(table, "summary.csv");

    using nlohmann::json;
    const auto& d = rc.ctx.description;
    json j;
    j["tool"] = {{"name", "cbrbench"}, {"version", CBR_VERSION}, {"commit", CBR_GIT_COMMIT}};
    j["date"] = isoDate();
    j["command_line"] = rc.options.argv;
    j["wall_seconds"] = r.seconds;
    j["first_frame_wall_seconds"] = r.first_frame_seconds;
    j["device"] = {{"index", d.index},
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
        j["device"]["timing_note"] =
            "lavapipe timestamps measure CPU rasterisation: ratios between variants are meaningful, absolute times "
            "are not GPU times";
    const auto& s = rc.settings;
    j["settings"] = {{"width", s.width},
                     {"height", s.height},
                     {"pipeline", s.deferred ? "deferred" : "forward"},
                     {"frames", r.frames},
                     {"repeat", r.repeats},
                     {"warmup_frames", rc.options.warmup},
                     {"warmup_rule", "fixed count of the path's first frames per variant per repetition"},
                     {"variant_order", r.order},
                     {"shading_cost", s.shading_cost},
                     {"exposure", s.exposure},
                     {"cbr_route", s.cbr_route},
                     {"cbr_lod_bias", s.cbr_lod_bias},
                     {"cso_tolerance", s.cso_tolerance},
                     {"cso_mode", s.cso_absolute ? "absolute" : "relative"},
                     {"resolve_impl", render::resolveImplName(s.resolve_impl)},
                     {"debug_shading", s.debug_pixel_id ? "pixel-id" : "none"},
                     {"drr_scale", s.drr_scale},
                     {"drr_filter", s.drr_filter == render::DrrFilter::Bilinear ? "bilinear" : "catmull-rom"},
                     {"drr_target_ms", s.drr_control.target_ms},
                     {"drr_control",
                      {{"min_scale", s.drr_control.min_scale},
                       {"max_scale", s.drr_control.max_scale},
                       {"dead_band", s.drr_control.dead_band},
                       {"step", s.drr_control.step}}},
                     {"frames_in_flight", s.frames_in_flight},
                     {"depth", "reversed-Z, D32_SFLOAT"},
                     {"save_frames", rc.options.save_frames}};
    const auto& si = rc.scene.info;
    j["scene"] = {{"name", rc.scene.name},
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
    addSceneCost(j["scene"], rc.scene, r.scene_load);
    j["path"] = {{"name", rc.path.name},
                 {"source", rc.options.path},
                 {"hash", pathHash(rc.poses, rc.times)},
                 {"fps", rc.path.fps},
                 {"duration_s", rc.path.duration()},
                 {"frames", rc.poses.size()},
                 {"cuts", std::count_if(rc.poses.begin(), rc.poses.end(), [](const auto& p) { return p.cut; })}};
    if (rc.placement) j["path"]["placement"] = placementJson(*rc.placement, rc.scene.placement);
    j["scene"]["animations"] = animationsJson(rc.scene);
    j["scene"]["cameras"] = nlohmann::json::array();
    for (const auto& c : rc.scene.cameras)
        j["scene"]["cameras"].push_back({{"name", c.name}, {"type", c.perspective ? "perspective" : "orthographic"}});
    j["metrics"] = {{"on", "8-bit sRGB display image, as the saved PNGs, converted to [0,1]"},
                    {"reference", "full at the same frame, unjittered, one sample per pixel"},
                    {"psnr", "10 log10(1/MSE), MSE over all pixels and RGB channels; sequence PSNR from the mean MSE"},
                    {"ssim", "Wang et al. 2004: Gaussian 11x11 sigma 1.5, K1 0.01, K2 0.03, L 1, population "
                             "statistics, 5-pixel border excluded, mean of per-channel SSIM"},
                    {"eci", "edge crawl index: luma blurred with sigma 1, e = Y(V) - Y(R), e_t against e_t-1 "
                            "warped with the renderer's motion vectors (bilinear), on reference edges (Sobel of blurred "
                            "reference luma > 0.02, dilated 1 px), 4 px margin, disocclusions (5% view-depth mismatch) "
                            "and pairs across cuts excluded; sequence ECI pools numerators and denominators"},
                    {"reference_kind", rc.options.reference == "ssaa"
                                           ? "ssaa: " + std::to_string(rc.options.ssaa) + "x" +
                                                 std::to_string(rc.options.ssaa) + " samples per pixel, box filter in HDR"
                                           : std::string("full")},
                    {"image_io", metrics::imageIoBackend()},
                    {"scored_repeat", 0}};
    if (!r.reference_ms.empty()) j["metrics"]["reference_gpu_ms_median"] = median(r.reference_ms);
    json variants = json::array();
    for (size_t i = 0; i < r.variants.size(); ++i) {
        const auto& vr = r.variants[i];
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
        resolveBandwidth(v, summaries[i], r.copy_bandwidth);
        if (vr.alignment) {
            const auto& a = *vr.alignment;
            auto finite = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
            v["frame_alignment"] = {{"frame", a.frame}, {"psnr_db_same", finite(a.psnr_same)},
                                    {"psnr_db_prev", finite(a.psnr_prev)}, {"psnr_db_next", finite(a.psnr_next)},
                                    {"ok", a.ok}};
        }
        const auto& sm = summaries[i];
        if (sm.frames > 0) {
            v["gpu_ms_median"] = sm.gpu_ms_median;
            v["speedup_vs_full"] = number(sm.speedup);
            v["psnr_db"] = number(sm.psnr_db);
            v["psnr_db_is_inf"] = sm.psnr_db && std::isinf(*sm.psnr_db);
            v["ssim_mean"] = number(sm.ssim_mean);
            v["eci"] = number(sm.eci);
            v["render_width"] = sm.render_width;
            v["render_height"] = sm.render_height;
        }
        variants.push_back(v);
    }
    j["variants"] = variants;
    j["non_finite_cells"] = nan_cells;  // NaNs written as empty CSV cells (0 in a healthy run)
    auto& val = rc.ctx.validation;
    json messages = json::array();
    {
        std::lock_guard lock(val.mutex);
        for (const auto& m : val.first_messages) messages.push_back(m);
    }
    j["validation"] = {{"enabled", rc.ctx.validation_enabled},
                       {"errors", val.errors.load()},
                       {"warnings", val.warnings.load()},
                       {"messages", val.errors.load() + val.warnings.load()},
                       {"first_messages", messages}};
    std::vector<std::string> files = {"frames.csv", "summary.csv", "run.json"};
    if (rc.options.save_frames) files.push_back("frames/");
    files.insert(files.end(), r.worst_files.begin(), r.worst_files.end());
    files.push_back("report.html");
    j["files"] = files;
    reports::writeTextAtomically(dir / "run.json", j.dump(2) + "\n");
}

namespace {

// The settings of the variants they change: the swept value, else the run's own.
void sweepSettingCells(std::map<std::string, Cell>& row, const VariantRun& vr, const RunContext& rc) {
    const render::Settings& s = rc.settings;
    if (vr.variant == "drr") {
        row["drr_scale"] = s.drr_scale;
        row["drr_filter"] = rc.options.drr_filter;
    }
    if (vr.variant == "cbr-cso") {
        row["cso_tolerance"] = s.cso_tolerance;
        row["cso_mode"] = rc.options.cso_mode;
    }
    if (vr.variant == "cbr-aso" || vr.variant == "cbr-cso") {
        row["cbr_lod_bias"] = rc.options.cbr_lod_bias;
        row["cbr_route"] = rc.options.cbr_route;
    }
    for (const auto& st : vr.settings) {
        std::string column = st.name;
        std::replace(column.begin(), column.end(), '-', '_');
        row[column] = st.word.empty() ? Cell(st.value) : Cell(st.word);
    }
}

}  // namespace

void writeSweepCsv(const std::filesystem::path& dir, const RunContext& rc) {
    const RunResults& r = rc.results;
    auto summaries = summarize(r);
    reports::CsvTable table(reports::sweepColumns());
    for (size_t i = 0; i < r.variants.size(); ++i) {
        const auto& vr = r.variants[i];
        const auto& sm = summaries[i];
        std::map<std::string, Cell> row{{"config", vr.name},
                                        {"variant", vr.variant},
                                        {"path", sweepPathName(rc.options.path)},
                                        {"reference", rc.options.reference},
                                        {"pipeline", rc.settings.deferred ? "deferred" : "forward"},
                                        {"shading_cost", rc.settings.shading_cost},
                                        {"status", sm.status},
                                        {"note", sm.note},
                                        {"frames", sm.frames},
                                        {"repeats", r.repeats}};
        sweepSettingCells(row, vr, rc);
        if (sm.frames > 0) {
            row["gpu_ms_median"] = sm.gpu_ms_median;
            row["gpu_ms_ci_low"] = optional(sm.gpu_ms_ci_low);
            row["gpu_ms_ci_high"] = optional(sm.gpu_ms_ci_high);
            row["noise_cv"] = sm.noise_cv;
            row["speedup_vs_full"] = optional(sm.speedup);
            row["speedup_ci_low"] = optional(sm.speedup_low);
            row["speedup_ci_high"] = optional(sm.speedup_high);
            row["psnr_db"] = optional(sm.psnr_db);
            row["ssim"] = optional(sm.ssim_mean);
            row["eci"] = optional(sm.eci);
            row["flicker_ratio"] = optional(sm.flicker_ratio_mean);
            for (const auto& [name, value] : sm.stats_mean)
                for (const auto& col : reports::sweepColumns())
                    if (col == name) row[name] = value;
        }
        table.addRow(row);
    }
    reportNaNs(table, "sweep.csv");
    table.write(dir / "sweep.csv");
}

void printSummary(std::ostream& out, const std::filesystem::path& dir, const RunContext& rc) {
    auto summaries = summarize(rc.results);
    char line[512];
    int name_width = 10;  // a sweep's configuration labels are longer than variant names
    for (const auto& s : summaries) name_width = std::max(name_width, int(std::min<size_t>(s.variant.size(), 60)));
    std::snprintf(line, sizeof line, "%-*s %-8s %10s %10s %9s %10s %8s %8s\n", name_width, "variant", "status",
                  "render", "gpu_ms", "speedup", "psnr_db", "ssim", "eci");
    out << "cbrbench: " << rc.scene.name << " / " << rc.path.name << " at " << rc.settings.width << "x"
        << rc.settings.height << ", " << rc.results.frames << " frames x " << rc.results.repeats << " repeats on "
        << rc.ctx.description.name << "\n" << line;
    auto fmt = [](const std::optional<double>& v, const char* f) {
        if (!v) return std::string("-");
        if (std::isinf(*v)) return std::string("inf");
        char b[32];
        std::snprintf(b, sizeof b, f, *v);
        return std::string(b);
    };
    for (const auto& s : summaries) {
        std::string render = std::to_string(s.render_width) + "x" + std::to_string(s.render_height);
        std::snprintf(line, sizeof line, "%-*s %-8s %10s %10s %9s %10s %8s %8s\n", name_width, s.variant.c_str(),
                      s.status.c_str(),
                      s.frames ? render.c_str() : "-",
                      s.frames ? fmt(s.gpu_ms_median, "%.3f").c_str() : "-", fmt(s.speedup, "%.3fx").c_str(),
                      fmt(s.psnr_db, "%.2f").c_str(), fmt(s.ssim_mean, "%.4f").c_str(), fmt(s.eci, "%.4f").c_str());
        out << line;
    }
    auto& val = rc.ctx.validation;
    if (rc.ctx.validation_enabled)
        out << "validation messages: " << val.errors.load() + val.warnings.load() << " (" << val.errors.load()
            << " errors, " << val.warnings.load() << " warnings)\n";
    out << "report:  " << (dir / "report.html").string() << "\n";
    out << "results: " << dir.string() << "/ (summary.csv, frames.csv, run.json"
        << (rc.options.save_frames ? ", frames/" : "") << ")\n";
}

}  // namespace cbr::harness
