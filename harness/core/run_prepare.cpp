// A run's inputs checked before any output exists: settings, configurations, scene and path.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <stdexcept>

#include "harness/core/exports.h"
#include "harness/core/gltf_path.h"
#include "harness/core/placement.h"
#include "harness/core/run_internal.h"

namespace cbr::harness {
namespace {

// The options that need no scene, each against what it accepts; the first bad one throws.
void checkOptions(const RunOptions& o) {
    if (o.frames < 0) throw std::invalid_argument("--frames " + std::to_string(o.frames) + ": expected >= 1 (or 0: the path's length)");
    if (o.repeat < 1) throw std::invalid_argument("--repeat " + std::to_string(o.repeat) + ": expected >= 1");
    if (o.warmup < 0) throw std::invalid_argument("--warmup " + std::to_string(o.warmup) + ": expected >= 0");
    if (o.shading_cost < 1)
        throw std::invalid_argument("--shading-cost " + std::to_string(o.shading_cost) + ": expected an integer >= 1");
    if (!(o.drr_scale > 0.0 && o.drr_scale <= 1.0))
        throw std::invalid_argument("--drr-scale " + std::to_string(o.drr_scale) + ": expected a per-axis scale in (0, 1]");
    if (!(o.taau_scale > 0.0 && o.taau_scale <= 1.0))
        throw std::invalid_argument("--taau-scale " + std::to_string(o.taau_scale) + ": expected a per-axis scale in (0, 1]");
    if (o.taau_phases != 8 && o.taau_phases != 16)
        throw std::invalid_argument("--taau-phases " + std::to_string(o.taau_phases) + ": expected 8 or 16");
    if (!(o.taau_blend > 0.0 && o.taau_blend <= 1.0))
        throw std::invalid_argument("--taau-blend " + std::to_string(o.taau_blend) + ": expected a weight in (0, 1]");
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
    checkFlipPpd(o.flip_ppd);
}

// --debug-slowdown PASS=PCT into the settings.
void parseDebugSlowdown(const RunOptions& o, render::Settings& settings) {
    if (o.debug_slowdown.empty()) return;
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
    settings.debug_slowdown_pass = pass;
    settings.debug_slowdown_pct = value;
}

// The render settings every configuration starts from.
// The enum value an option names, or one line listing what it accepts
// ("--drr-filter x: expected bilinear or catmull-rom").
template <class E>
E chooseOne(const char* option, const std::string& value, std::initializer_list<std::pair<const char*, E>> choices) {
    std::string accepted;
    size_t k = 0;
    for (const auto& [name, e] : choices) {
        if (value == name) return e;
        accepted += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(name);
        ++k;
    }
    throw std::invalid_argument(std::string(option) + " " + value + ": expected " + accepted);
}

render::Settings settingsFromOptions(const RunOptions& o) {
    render::Settings s;
    parseResolution(o.resolution, s.width, s.height);
    checkOptions(o);
    s.debug_pixel_id = o.debug_shading == "pixel-id";
    parseDebugSlowdown(o, s);
    if (o.pipeline != "forward" && o.pipeline != "deferred")
        throw std::invalid_argument("--pipeline " + o.pipeline + ": expected forward or deferred");
    s.deferred = o.pipeline == "deferred";
    if (o.reference != "full" && o.reference != "ssaa")
        throw std::invalid_argument("--reference " + o.reference + ": expected full or ssaa");
    if (o.ssaa < 2 || o.ssaa > 8)
        throw std::invalid_argument("--ssaa " + std::to_string(o.ssaa) + ": expected 2 to 8 samples per axis");
    s.analysis = true;  // quality frames carry motion and depth for the edge-crawl metric
    s.cbr_route = o.cbr_route;
    s.cbr_lod_bias = float(o.cbr_lod_bias);
    if (o.cbr_history != "quarter" && o.cbr_history != "full")
        throw std::invalid_argument("--cbr-history " + o.cbr_history + ": expected quarter or full");
    s.cbr_full_history = o.cbr_history == "full";
    if (o.history_filter != "catmull-rom" && o.history_filter != "bilinear")
        throw std::invalid_argument("--history-filter " + o.history_filter + ": expected catmull-rom or bilinear");
    s.cbr_history_catmull_rom = o.history_filter == "catmull-rom";
    s.cbr_history_format = chooseOne<render::HistoryFormat>("--history-format", o.history_format,
                                                            {{"b10g11r11", render::HistoryFormat::B10g11r11},
                                                             {"rgba16f", render::HistoryFormat::Rgba16f}});
    s.cso_tolerance = o.cso_tolerance;
    s.cso_absolute = o.cso_mode == "absolute";
    s.resolve_impl = chooseOne<render::ResolveImpl>("--resolve-impl", o.resolve_impl,
                                                    {{"fused", render::ResolveImpl::Fused},
                                                     {"separate", render::ResolveImpl::Separate},
                                                     {"reference", render::ResolveImpl::Reference}});
    s.target_clear = chooseOne<render::TargetClear>("--target-clear", o.target_clear,
                                                    {{"auto", render::TargetClear::Auto},
                                                     {"load-op", render::TargetClear::LoadOp},
                                                     {"compute", render::TargetClear::Compute}});
    s.drr_filter = chooseOne<render::DrrFilter>(
        "--drr-filter", o.drr_filter,
        {{"bilinear", render::DrrFilter::Bilinear}, {"catmull-rom", render::DrrFilter::CatmullRom}});
    s.drr_scale = o.drr_scale;
    s.drr_control.target_ms = o.drr_target_ms;
    s.taau_scale = o.taau_scale;
    s.taau_phases = o.taau_phases;
    s.taau_blend = o.taau_blend;
    s.shading_cost = o.shading_cost;
    s.exposure = float(o.exposure);
    return s;
}

// The variants in run order, and what runs per repetition: one configuration per
// variant, or a sweep's configurations with their settings applied.
void makeConfigs(const RunOptions& o, Prepared& p) {
    // The reference always runs first: every other variant is scored against it.
    const variants::Variant& reference = variants::referenceVariant();
    p.order.push_back(&reference);
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
        for (const auto* v : p.order) configs.push_back({std::string(v->name), {}, std::string(v->name), std::string(reference.name)});
    }
    for (auto& sc : configs) {
        Prepared::Config c{&variants::findVariant(sc.variant), p.settings, sc};
        for (const auto& s : sc.settings) {
            if (s.name == "cso-tolerance") c.settings.cso_tolerance = s.value;
            if (s.name == "cso-mode") c.settings.cso_absolute = s.word == "absolute";
            if (s.name == "drr-scale") c.settings.drr_scale = s.value;
            if (s.name == "drr-filter")
                c.settings.drr_filter = s.word == "bilinear" ? render::DrrFilter::Bilinear : render::DrrFilter::CatmullRom;
            if (s.name == "taau-scale") c.settings.taau_scale = s.value;
            if (s.name == "taau-blend") c.settings.taau_blend = s.value;
            if (s.name == "cbr-lod-bias") c.settings.cbr_lod_bias = float(s.value);
            if (s.name == "cbr-route") c.settings.cbr_route = s.word;
            if (s.name == "cbr-history") c.settings.cbr_full_history = s.word == "full";
            if (s.name == "shading-cost") c.settings.shading_cost = int(s.value);
        }
        p.configs.push_back(std::move(c));
    }
}

// The scene (timed for run.json), its animations, the camera path placed in it, and the
// frames sampled from the path.
void loadSceneAndPath(const RunOptions& o, Prepared& p) {
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
}

// --out, or a new name under out/; never an existing directory.
std::filesystem::path outputDirectory(const RunOptions& o) {
    std::filesystem::path out =
        o.out.empty() ? std::filesystem::path("out") / (specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName())
                      : std::filesystem::path(o.out);
    if (o.sweep && o.out.empty())
        out = std::filesystem::path("out") / ("sweep-" + specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName());
    if (std::filesystem::exists(out))
        throw std::invalid_argument("--out " + out.string() + ": already exists; expected a new directory");
    return out;
}

}  // namespace

Prepared prepare(const RunOptions& o) {
    Prepared p;
    p.options = o;
    p.settings = settingsFromOptions(o);
    (void)parseExportFormats(o.exports, "--export");
    makeConfigs(o, p);
    loadSceneAndPath(o, p);
    p.out = outputDirectory(o);
    return p;
}

}  // namespace cbr::harness
