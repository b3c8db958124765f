// The run loop: reference first, variants interleaved per repetition, metrics on workers.
#include "harness/run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <unistd.h>

#include "camera_paths/path.h"
#include "harness/gltf_path.h"
#include "harness/interrupt.h"
#include "harness/outputs.h"
#include "harness/placement.h"
#include "harness/quality.h"
#include "harness/results.h"
#include "harness/sweep.h"
#include "harness/worker_pool.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "renderer/gpu/gpu_scene.h"
#include "renderer/renderer.h"
#include "renderer/scene/scene.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "reports/output_dir.h"
#include "reports/report.h"
#include "reports/sweep.h"

namespace cbr::harness {
namespace {

render::Camera toCamera(const paths::CameraPose& pose) {
    render::Camera c;
    c.position = pose.position;
    c.view = pose.view();
    c.fov_y_rad = pose.fov_y_rad;
    c.near = pose.near;
    c.far = pose.far;
    return c;
}

class Progress {
public:
    explicit Progress(int total) : total_(total), tty_(::isatty(2)), start_(std::chrono::steady_clock::now()) {}
    void step(const std::string& what) {
        ++done_;
        if (!tty_) return;
        double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        double eta = done_ > 0 ? elapsed / done_ * (total_ - done_) : 0;
        std::fprintf(stderr, "\r\033[K%s  %d/%d frames  ETA %.0f s", what.c_str(), done_, total_, eta);
    }
    ~Progress() {
        if (tty_) std::fprintf(stderr, "\r\033[K");
    }

private:
    int total_;
    int done_ = 0;
    bool tty_;
    std::chrono::steady_clock::time_point start_;
};

// Everything checked before the first output exists.
struct Prepared {
    RunOptions options;
    render::Settings settings;
    scene::Scene scene;
    paths::CameraPath path;
    std::vector<double> times;
    std::vector<paths::CameraPose> poses;
    PathPlacement placement;  // how a built-in path was placed (run.json path.placement)
    std::vector<const variants::Variant*> order;
    // What runs, in order within each repetition: a variant with its settings (a plain
    // run: one per variant; a sweep: one per configuration).
    struct Config {
        const variants::Variant* variant = nullptr;
        render::Settings settings;
        SweepConfig sweep;
    };
    std::vector<Config> configs;
    std::vector<SweepParam> params;
    std::filesystem::path out;
    SceneLoad load;
};

Prepared prepare(const RunOptions& o) {
    Prepared p;
    p.options = o;
    parseResolution(o.resolution, p.settings.width, p.settings.height);
    if (o.frames < 0) throw std::invalid_argument("--frames " + std::to_string(o.frames) + ": expected >= 1 (or 0: the path's length)");
    if (o.repeat < 1) throw std::invalid_argument("--repeat " + std::to_string(o.repeat) + ": expected >= 1");
    if (o.warmup < 0) throw std::invalid_argument("--warmup " + std::to_string(o.warmup) + ": expected >= 0");
    if (o.shading_cost < 1)
        throw std::invalid_argument("--shading-cost " + std::to_string(o.shading_cost) + ": expected an integer >= 1");
    if (!(o.drr_scale > 0.0 && o.drr_scale <= 1.0))
        throw std::invalid_argument("--drr-scale " + std::to_string(o.drr_scale) + ": expected a per-axis scale in (0, 1]");
    if (o.drr_target_ms < 0 || !std::isfinite(o.drr_target_ms))
        throw std::invalid_argument("--drr-target-ms: expected a positive number of milliseconds (or 0: fixed scale)");
    if (!(o.exposure > 0 && std::isfinite(o.exposure)))
        throw std::invalid_argument("--exposure: expected a positive finite number");
    if (!std::isfinite(o.cbr_lod_bias) || std::abs(o.cbr_lod_bias) > 16)
        throw std::invalid_argument("--cbr-lod-bias: expected a finite bias in [-16, 16] (default -1, which matches full-res derivatives; the paper's -0.5)");
    if (!(o.cso_tolerance > 0 && std::isfinite(o.cso_tolerance)))
        throw std::invalid_argument("--cso-tolerance " + std::to_string(o.cso_tolerance) + ": expected a positive finite number");
    if (o.cso_mode != "relative" && o.cso_mode != "absolute")
        throw std::invalid_argument("--cso-mode " + o.cso_mode + ": expected relative or absolute");
    if (o.cbr_route != "auto" && o.cbr_route != "msaa-jitter" && o.cbr_route != "msaa-locations" &&
        o.cbr_route != "multiview" && o.cbr_route != "layers")
        throw std::invalid_argument("--cbr-route " + o.cbr_route +
                                    ": unknown route; expected auto, msaa-jitter, msaa-locations, multiview or layers");
    if (o.debug_shading != "none" && o.debug_shading != "pixel-id")
        throw std::invalid_argument("--debug-shading " + o.debug_shading + ": expected none or pixel-id");
    p.settings.debug_pixel_id = o.debug_shading == "pixel-id";
    if (!o.debug_slowdown.empty()) {
        size_t eq = o.debug_slowdown.find('=');
        std::string pass = eq == std::string::npos ? "" : o.debug_slowdown.substr(0, eq);
        std::string pct = eq == std::string::npos ? "" : o.debug_slowdown.substr(eq + 1);
        if (!pct.empty() && pct.back() == '%') pct.pop_back();
        char* end = nullptr;
        double value = pct.empty() ? -1 : std::strtod(pct.c_str(), &end);
        if (pass.empty() || !end || *end != '\0' || !(value >= 0 && value <= 1000))
            throw std::invalid_argument("--debug-slowdown " + o.debug_slowdown +
                                        ": expected PASS=PCT with a pass name (e.g. opaque) and 0 <= PCT <= 1000");
        if (value > 0 && o.warmup < 2)
            throw std::invalid_argument("--debug-slowdown needs --warmup 2 or more (the warm-up calibrates it)");
        p.settings.debug_slowdown_pass = pass;
        p.settings.debug_slowdown_pct = value;
    }
    if (o.pipeline != "forward" && o.pipeline != "deferred")
        throw std::invalid_argument("--pipeline " + o.pipeline + ": expected forward or deferred");
    p.settings.deferred = o.pipeline == "deferred";
    if (o.reference != "full" && o.reference != "ssaa")
        throw std::invalid_argument("--reference " + o.reference + ": expected full or ssaa");
    if (o.ssaa < 2 || o.ssaa > 8)
        throw std::invalid_argument("--ssaa " + std::to_string(o.ssaa) + ": expected 2 to 8 samples per axis");
    p.settings.analysis = true;  // quality frames carry motion and depth for the edge-crawl metric
    p.settings.cbr_route = o.cbr_route;
    p.settings.cbr_lod_bias = float(o.cbr_lod_bias);
    p.settings.cso_tolerance = o.cso_tolerance;
    p.settings.cso_absolute = o.cso_mode == "absolute";
    if (o.resolve_impl == "fused")
        p.settings.resolve_impl = render::ResolveImpl::Fused;
    else if (o.resolve_impl == "separate")
        p.settings.resolve_impl = render::ResolveImpl::Separate;
    else if (o.resolve_impl == "reference")
        p.settings.resolve_impl = render::ResolveImpl::Reference;
    else
        throw std::invalid_argument("--resolve-impl " + o.resolve_impl + ": expected fused, separate or reference");
    if (o.drr_filter == "bilinear")
        p.settings.drr_filter = render::DrrFilter::Bilinear;
    else if (o.drr_filter == "catmull-rom")
        p.settings.drr_filter = render::DrrFilter::CatmullRom;
    else
        throw std::invalid_argument("--drr-filter " + o.drr_filter + ": expected bilinear or catmull-rom");
    p.settings.drr_scale = o.drr_scale;
    p.settings.drr_control.target_ms = o.drr_target_ms;
    p.settings.shading_cost = o.shading_cost;
    p.settings.exposure = float(o.exposure);

    // The reference always runs first: every other variant is scored against it.
    const variants::Variant& full = variants::findVariant("full");
    p.order.push_back(&full);
    std::vector<std::string> wanted = o.variants;
    if (wanted.empty())
        for (const auto& v : variants::allVariants()) wanted.emplace_back(v.name);
    for (const auto& name : wanted) {
        const variants::Variant& v = variants::findVariant(name);
        if (std::find(p.order.begin(), p.order.end(), &v) == p.order.end()) p.order.push_back(&v);
    }
    for (const auto& spec : o.params) p.params.push_back(parseSweepParam(spec));
    std::vector<SweepConfig> configs;
    if (o.sweep) {
        configs = expandSweep(p.params, o.variants);
    } else {
        for (const auto* v : p.order) configs.push_back({std::string(v->name), {}, std::string(v->name), "full"});
    }
    for (auto& sc : configs) {
        Prepared::Config c{&variants::findVariant(sc.variant), p.settings, sc};
        for (const auto& s : sc.settings) {
            if (s.name == "cso-tolerance") c.settings.cso_tolerance = s.value;
            if (s.name == "cso-mode") c.settings.cso_absolute = s.word == "absolute";
            if (s.name == "drr-scale") c.settings.drr_scale = s.value;
            if (s.name == "drr-filter")
                c.settings.drr_filter = s.word == "bilinear" ? render::DrrFilter::Bilinear : render::DrrFilter::CatmullRom;
            if (s.name == "cbr-lod-bias") c.settings.cbr_lod_bias = float(s.value);
            if (s.name == "cbr-route") c.settings.cbr_route = s.word;
            if (s.name == "shading-cost") c.settings.shading_cost = int(s.value);
        }
        p.configs.push_back(std::move(c));
    }

    const auto load_start = std::chrono::steady_clock::now();
    p.scene = scene::loadScene(o.scene);
    p.load.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
    p.load.peak_rss_mib_loaded = peakRssMib();
    for (const auto& w : p.scene.warnings) std::fprintf(stderr, "cbrbench: warning: %s: %s\n", o.scene.c_str(), w.c_str());
    const paths::BuiltinContext bctx =
        builtinContext(p.scene, o.path, int(p.settings.width), int(p.settings.height), &p.placement);
    std::filesystem::path path_file(o.path);
    scene::selectAnimations(p.scene, o.animation);
    const bool gltf_path = isGltfPathSpec(o.path);
    p.path = gltf_path                         ? gltfCameraPath(p.scene, o.path, o.fps)
             : path_file.extension() == ".json" ? paths::loadPath(path_file)
                                                : paths::builtinPath(o.path, bctx);
    applyPlacement(o, p.scene, p.path);
    const int frames = gltf_path && !o.frames_set ? 0 : o.frames;
    p.times = paths::frameTimes(p.path, frames);
    p.poses = paths::sampleFrames(p.path, frames);
    p.out = o.out.empty() ? std::filesystem::path("out") / (specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName())
                          : std::filesystem::path(o.out);
    if (o.sweep && o.out.empty())
        p.out = std::filesystem::path("out") / ("sweep-" + specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName());
    if (std::filesystem::exists(p.out))
        throw std::invalid_argument("--out " + p.out.string() + ": already exists; expected a new directory");
    return p;
}

// Saves a display image (and a class map) as frames/<name>_<frame>.png on a worker.
void savePng(const std::filesystem::path& out, const std::string& name, int frame, Bytes image, Bytes classes, int w,
             int h, WorkerPool& workers) {
    char file[128];
    std::snprintf(file, sizeof file, "%s_%04d.png", name.c_str(), frame);
    auto dest = out / "frames" / file;
    std::snprintf(file, sizeof file, "%s_%04d_class.png", name.c_str(), frame);
    auto class_dest = out / "frames" / file;
    workers.submit([dest, class_dest, image, classes, w, h] {
        try {
            metrics::writePng(dest, {w, h, *image});
            if (classes && !classes->empty()) metrics::writePng(class_dest, {w, h, classMapRgba(*classes)});
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cbrbench: PNG not saved: %s\n", e.what());
        }
    });
}

bool moving(const std::vector<paths::CameraPose>& poses, size_t mid) {
    auto differs = [](const paths::CameraPose& a, const paths::CameraPose& b) {
        return a.position != b.position || a.orientation != b.orientation || a.fov_y_rad != b.fov_y_rad;
    };
    return differs(poses[mid - 1], poses[mid]) && differs(poses[mid], poses[mid + 1]);
}

AlignmentCheck checkAlignment(const std::vector<uint8_t>& variant, const std::vector<uint8_t>& ref_prev,
                              const std::vector<uint8_t>& ref_same, const std::vector<uint8_t>& ref_next, int w, int h,
                              int frame) {
    auto image = [&](const std::vector<uint8_t>& rgba) { return metrics::fromRgba8(rgba.data(), w, h, size_t(w) * 4); };
    auto v = image(variant);
    AlignmentCheck a;
    a.frame = frame;
    a.psnr_same = metrics::psnr(image(ref_same), v);
    a.psnr_prev = metrics::psnr(image(ref_prev), v);
    a.psnr_next = metrics::psnr(image(ref_next), v);
    a.ok = a.psnr_same > a.psnr_prev && a.psnr_same > a.psnr_next;
    return a;
}

}  // namespace

void checkRunOptions(const RunOptions& options) { (void)prepare(options); }

namespace {

// The sweeps of the outer dimensions (harness/sweep.h) one after another into OUT/<dir>/,
// then OUT/sweep.csv (every row, naming its path and reference) and the index sweep.html.
// Every sweep's input is checked before the first renders; OUT appears whole or not at all.
int runOuterSweeps(const RunOptions& options, const std::vector<OuterSweep>& outer) {
    auto sub = [&](const OuterSweep& o, const std::filesystem::path& out) {
        RunOptions s = options;
        s.path = o.path;
        s.reference = o.reference;
        s.params = o.params;
        s.out = out.string();
        return s;
    };
    if (outer.size() == 1) return runBenchmark(sub(outer[0], options.out));
    std::string names;
    for (const auto& path : splitList(options.path)) names += (names.empty() ? "" : "+") + sweepPathName(path);
    const std::filesystem::path final_out =
        options.out.empty() ? std::filesystem::path("out") / ("sweep-" + specStem(options.scene) + "-" + names + "-" +
                                                              timestampForName())
                            : std::filesystem::path(options.out);
    for (const auto& o : outer) checkRunOptions(sub(o, final_out / o.dir));
    reports::OutputDir out(final_out);
    std::vector<std::string> dirs;
    for (const auto& o : outer) {
        RunOptions s = sub(o, out.path() / o.dir);
        s.shown_out = (final_out / o.dir).string();
        std::cout << "sweep " << dirs.size() + 1 << "/" << outer.size() << ": " << o.dir << "\n";
        if (int rc = runBenchmark(s); rc != 0) return rc;
        dirs.push_back(o.dir);
    }
    reports::combineSweeps(out.path(), dirs);
    reports::writeSweepReport(out.path());
    out.commit();
    std::cout << "\nsweep over " << outer.size() << " runs:\n";
    for (const auto& line : reports::sweepSummaryLines(reports::loadSweep(out.finalPath()).points))
        std::cout << line << "\n";
    std::cout << "sweep: " << (out.finalPath() / "sweep.csv").string() << ", "
              << (out.finalPath() / "sweep.html").string() << " (each run in its own subdirectory)\n";
    return 0;
}

}  // namespace

int runBenchmark(const RunOptions& options) {
    // A sweep over paths or reference kinds (harness/sweep.h): one run per combination.
    if (options.sweep) {
        auto outer = outerSweeps(options.path, options.reference, options.params);
        if (outer.size() > 1 || outer[0].params.size() != options.params.size()) return runOuterSweeps(options, outer);
    }
    auto wall_start = std::chrono::steady_clock::now();
    Prepared p = prepare(options);
    vk::Context ctx({options.validate, options.device});
    uint32_t max_dim = ctx.caps.max_image_dimension_2d;
    if (p.settings.width > max_dim || p.settings.height > max_dim)
        throw std::invalid_argument("--res " + options.resolution + ": above the device limit; expected each side <= " +
                                    std::to_string(max_dim) + " on " + ctx.description.name);

    if (options.reference == "ssaa" && (p.settings.width * uint32_t(options.ssaa) > max_dim ||
                                        p.settings.height * uint32_t(options.ssaa) > max_dim))
        throw std::invalid_argument("--ssaa " + std::to_string(options.ssaa) + ": the " + options.resolution +
                                    " reference would exceed the device limit of " + std::to_string(max_dim) +
                                    "; expected a smaller factor or resolution");
    render::Settings ref_settings = p.settings;
    ref_settings.supersample = options.ssaa;
    ref_settings.analysis = false;

    reports::OutputDir out(p.out);
    if (options.save_frames) std::filesystem::create_directories(out.path() / "frames");
    const auto upload_start = std::chrono::steady_clock::now();
    gpu::GpuScene gpu_scene = gpu::uploadScene(ctx, p.scene);
    p.load.upload_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - upload_start).count();
    if (!options.quiet) std::fprintf(stderr, "cbrbench: %s\n", sceneLoadLine(p.scene, p.load).c_str());
    // Released on every way out, an interrupt's exception included: destroying the device
    // with the scene's images and buffers alive leaks them (LeakSanitizer, validation).
    // Declared before the renderers, so it runs after theirs; destroyGpuScene is idempotent.
    struct SceneRelease {
        vk::Context& ctx;
        gpu::GpuScene& scene;
        ~SceneRelease() { gpu::destroyGpuScene(ctx, scene); }
    } scene_release{ctx, gpu_scene};

    RunResults results;
    results.frames = int(p.poses.size());
    results.repeats = options.repeat;
    for (const auto& c : p.configs) {
        results.order.push_back(c.sweep.label);
        VariantRun vr;
        vr.name = c.sweep.label;
        vr.variant = c.sweep.variant;
        vr.baseline = c.sweep.baseline;
        vr.settings = c.sweep.settings;
        results.variants.push_back(std::move(vr));
    }

    const int w = int(p.settings.width), h = int(p.settings.height);
    unsigned hw = std::thread::hardware_concurrency();
    WorkerPool workers(std::max(1u, hw / 2));
    QualityScorer scorer(w, h, p.poses.size(), workers);
    // The alignment check looks at the middle frame of a path of at least 3 frames.
    const size_t mid = p.poses.size() / 2;
    std::vector<Bytes> mid_images(p.configs.size());
    std::vector<Bytes> reference_frames(p.poses.size());
    Progress progress(int(p.configs.size() * p.poses.size()) * options.repeat +
                      (options.reference == "ssaa" ? int(p.poses.size()) : 0));

    auto request = [&](size_t i, bool readback) {
        render::FrameRequest req;
        req.index = int(i);
        req.time = p.times[i];
        req.camera = toCamera(p.poses[i]);
        req.history_reset = i == 0 || p.poses[i].cut;
        req.prev_time = i == 0 ? p.times[i] : p.times[i - 1];
        req.prev_camera = i == 0 ? req.camera : toCamera(p.poses[i - 1]);
        req.readback = readback;
        return req;
    };
    auto warmUp = [&](render::Renderer& renderer) {
        // Warm-up: the path's first frames, untimed, excluded (timing.md).
        for (int i = 0; i < options.warmup; ++i) {
            size_t k = size_t(i) % p.poses.size();
            render::FrameRequest req = request(k, false);
            req.index = -1;
            req.history_reset = true;
            throwIfInterrupted();
            renderer.submit(req);
        }
        renderer.finish();
    };

    // `--reference ssaa`: a supersampled render is the reference, and `full` is scored too.
    if (options.reference == "ssaa") {
        render::Renderer reference(ctx, gpu_scene, variants::supersampledReference(), ref_settings);
        warmUp(reference);
        auto keep = [&](render::FrameResult&& fr) {
            progress.step("reference (ssaa " + std::to_string(options.ssaa) + "x" + std::to_string(options.ssaa) + ")");
            results.reference_ms.push_back(fr.gpu_ms);
            auto image = std::make_shared<const std::vector<uint8_t>>(std::move(fr.rgba));
            reference_frames[size_t(fr.index)] = image;
            scorer.setReference(size_t(fr.index), image);
            if (options.save_frames) savePng(out.path(), "reference", fr.index, image, nullptr, w, h, workers);
        };
        for (size_t i = 0; i < p.poses.size(); ++i) {
            throwIfInterrupted();
            for (auto& fr : reference.submit(request(i, true))) keep(std::move(fr));
        }
        for (auto& fr : reference.finish()) keep(std::move(fr));
    }
    const bool full_is_reference = options.reference != "ssaa";

    // One renderer per variant for the whole run: pipelines and targets are built once.
    std::vector<std::unique_ptr<render::Renderer>> renderers(p.configs.size());
    for (size_t vi = 0; vi < p.configs.size(); ++vi) {
        VariantRun& vr = results.variants[vi];
        try {
            renderers[vi] = std::make_unique<render::Renderer>(ctx, gpu_scene, *p.configs[vi].variant,
                                                               p.configs[vi].settings);
            vr.description = renderers[vi]->describe();
        } catch (const vk::Unsupported& e) {
            vr.status = "skipped";
            vr.note = e.what();
        } catch (const vk::Error& e) {
            vr.status = "failed";
            vr.note = e.what();
        }
    }

    // A debug slowdown calibrates on its first warm-up frames: give each renderer enough
    // of them before the first repetition, so every repetition applies the same amount.
    if (!p.settings.debug_slowdown_pass.empty() && p.settings.debug_slowdown_pct > 0)
        for (auto& r : renderers)
            if (r) try {
                for (int i = 0; i < 12; ++i) {
                    render::FrameRequest req = request(size_t(i) % p.poses.size(), false);
                    req.index = -1;
                    req.history_reset = true;
                    r->submit(req);
                }
                r->finish();
            } catch (const vk::Error&) {
                // The repetitions meet the same error and record the variant as failed.
            }
    for (int rep = 0; rep < options.repeat; ++rep) {
        for (size_t vi = 0; vi < p.configs.size(); ++vi) {
            VariantRun& vr = results.variants[vi];
            const std::string& name = vr.name;
            std::vector<bool> done(p.poses.size(), false);
            auto failRemaining = [&] {
                // A failed variant becomes rows that say so, not a crash of the run.
                for (size_t i = 0; i < p.poses.size(); ++i) {
                    if (done[i]) continue;
                    FrameRow& row = results.rows.emplace_back();
                    row.variant = name;
                    row.repeat = rep;
                    row.frame = int(i);
                    row.time_s = p.times[i];
                    row.status = vr.status;
                    row.note = vr.note;
                }
            };
            if (vr.status != "ok") {
                failRemaining();
                continue;
            }
            render::Renderer& renderer = *renderers[vi];
            bool quality = rep == 0;
            // The first configuration is full: the reference (a sweep's other full
            // configurations differ only in shading cost and are scored against it).
            bool is_reference = vi == 0 && full_is_reference;
            auto handle = [&](render::FrameResult&& fr) {
                if (results.rows.empty())
                    results.first_frame_seconds =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
                FrameRow& row = results.rows.emplace_back();
                done[size_t(fr.index)] = true;
                row.variant = name;
                row.repeat = rep;
                row.frame = fr.index;
                row.time_s = p.times[size_t(fr.index)];
                row.render_width = fr.render_width;
                row.render_height = fr.render_height;
                row.render_scale = fr.render_scale;
                row.gpu_ms = fr.gpu_ms;
                row.timing_ok = fr.timing_consistent;
                if (!fr.timing_consistent) row.note = "pass times do not sum to the frame time";
                row.passes = fr.passes;
                row.stats = fr.stats;
                if (rep == 0 && fr.index == 0) {
                    for (const auto& pt : fr.passes) vr.passes_ran.push_back(pt.name);
                    vr.left_out = fr.left_out;
                }
                progress.step("repeat " + std::to_string(rep + 1) + "/" + std::to_string(options.repeat) + " " + name);
                if (fr.rgba.empty()) return;
                size_t i = size_t(fr.index);
                auto image = std::make_shared<const std::vector<uint8_t>>(std::move(fr.rgba));
                Bytes classes = fr.diagnostic.empty()
                                    ? nullptr
                                    : std::make_shared<const std::vector<uint8_t>>(std::move(fr.diagnostic));
                if (i == mid) mid_images[vi] = image;
                if (is_reference) {
                    reference_frames[i] = image;
                    scorer.setReference(i, image);
                }
                QualityFrame qf{fr.index, image, classes,
                                fr.analysis.empty() ? nullptr
                                                    : std::make_shared<const std::vector<float>>(std::move(fr.analysis)),
                                i == 0 || p.poses[i].cut};
                scorer.score(name, is_reference, row, std::move(qf));
                if (options.save_frames) savePng(out.path(), name, fr.index, image, classes, w, h, workers);
            };
            try {
                warmUp(renderer);
                for (size_t i = 0; i < p.poses.size(); ++i) {
                    throwIfInterrupted();
                    for (auto& fr : renderer.submit(request(i, quality))) handle(std::move(fr));
                }
                for (auto& fr : renderer.finish()) handle(std::move(fr));
            } catch (const vk::Unsupported& e) {
                vr.status = "skipped";
                vr.note = e.what();
                failRemaining();
            } catch (const vk::Error& e) {
                vr.status = "failed";
                vr.note = e.what();
                failRemaining();
            }
        }
    }
    results.worst_files = scorer.finish(out.path());
    // Descriptions again: some (the calibrated debug slowdown) are known only after warm-up.
    for (size_t vi = 0; vi < p.configs.size(); ++vi)
        if (renderers[vi]) results.variants[vi].description = renderers[vi]->describe();
    if (p.poses.size() >= 3 && moving(p.poses, mid))
        for (size_t vi = 0; vi < p.configs.size(); ++vi)
            if (!(vi == 0 && full_is_reference) && mid_images[vi] && reference_frames[mid - 1] && reference_frames[mid] && reference_frames[mid + 1])
                results.variants[vi].alignment =
                    checkAlignment(*mid_images[vi], *reference_frames[mid - 1], *reference_frames[mid],
                                   *reference_frames[mid + 1], w, h, int(mid));
    renderers.clear();
    gpu::destroyGpuScene(ctx, gpu_scene);
    // The yardstick of the resolve's effective bandwidth (run.json, report). Not on lavapipe:
    // its timestamps do not bracket a transfer (a 64 MiB copy read as 10 TB/s).
    // Not on lavapipe: its timestamps around a lone dispatch or copy in a one-off submission
    // do not bracket the work (a 64 MiB compute copy read as 8 TB/s).
    if (!ctx.description.is_lavapipe) results.copy_bandwidth = vk::measureCopyBandwidth(ctx, 512);
    results.scene_load = p.load;
    results.scene_load.peak_rss_mib_end = peakRssMib();
    results.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

    RunContext rc{options, p.settings, p.scene, p.path, p.times, p.poses, ctx, results, &p.placement};
    writeOutputs(out.path(), rc);
    if (!options.quiet) reports::writeReport(out.path());
    if (options.sweep) {
        writeSweepCsv(out.path(), rc);
        reports::writeSweepReport(out.path());
    }
    out.commit();
    // An outer sweep's run is renamed once more with the others: name where it will be.
    const std::filesystem::path shown = options.shown_out.empty() ? out.finalPath() : std::filesystem::path(options.shown_out);
    if (!options.quiet) printSummary(std::cout, shown, rc);
    if (options.sweep) {
        for (const auto& line : reports::sweepSummaryLines(reports::loadSweep(out.finalPath()).points))
            std::cout << line << "\n";
        std::cout << "sweep: " << (shown / "sweep.csv").string() << ", " << (shown / "sweep.html").string() << "\n";
    }
    return 0;
}

}  // namespace cbr::harness
