// A run's inputs checked before any output exists: settings, configurations, scene and path.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "harness/jobs/gltf_path.h"
#include "harness/jobs/placement.h"
#include "harness/run/run_internal.h"
#include "settings/table.h"

namespace cbr::harness {
namespace {

// The options that need no scene, each against what it accepts; the first bad one throws.
void checkOptions(const RunOptions& o) {
    if (o.frames < 0) throw std::invalid_argument("--frames " + std::to_string(o.frames) + ": expected >= 1 (or 0: the path's length)");
    if (o.repeat < 1) throw std::invalid_argument("--repeat " + std::to_string(o.repeat) + ": expected >= 1");
    if (o.warmup < 0) throw std::invalid_argument("--warmup " + std::to_string(o.warmup) + ": expected >= 0");
    checkResolution(o.resolution);  // typed at the command line; options made in code are checked here
    settings::check(o.tune);  // the command line checked them; options made in code are checked here
}

// --debug-slowdown (parsed with the options) into the settings.
void applyDebugSlowdown(const RunOptions& o, render::Settings& settings) {
    if (o.debug_slowdown.empty()) return;
    parseSlowdown(o.debug_slowdown.spec());  // options made in code are checked as the command line's
    if (o.debug_slowdown.pct > 0 && o.warmup < 2)
        throw std::invalid_argument("--debug-slowdown needs --warmup 2 or more (the warm-up calibrates it)");
    settings.debug_slowdown_pass = o.debug_slowdown.pass;
    settings.debug_slowdown_pct = o.debug_slowdown.pct;
}

// The render settings every configuration starts from: the table's tunables as parsed,
// and what the harness derives from the other options.
render::Settings settingsFromOptions(const RunOptions& o) {
    render::Settings s;
    checkOptions(o);
    s.width = o.resolution.width;
    s.height = o.resolution.height;
    static_cast<settings::Tunables&>(s) = o.tune;
    applyDebugSlowdown(o, s);
    s.deferred = o.pipeline == Pipeline::Deferred;
    s.analysis = true;  // quality frames carry motion and depth for the edge-crawl metric
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
    if (o.control.sweep) {
        configs = expandSweep(p.params, o.variants);
    } else {
        for (const auto* v : p.order) configs.push_back({std::string(v->name), {}, std::string(v->name), std::string(reference.name)});
    }
    for (auto& sc : configs) {
        Prepared::Config c{&variants::findVariant(sc.variant), p.settings, sc};
        applySweepSettings(c.settings, sc.settings);
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
    const double span = p.times.size() > 1 ? p.times.back() - p.times.front() : 0.0;
    p.cvvdp_fps = span > 0 ? double(p.times.size() - 1) / span : 0.0;
}

// --out, or a new name under out/; never an existing directory.
std::filesystem::path outputDirectory(const RunOptions& o) {
    std::filesystem::path out =
        o.out.empty() ? std::filesystem::path("out") / (specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName())
                      : std::filesystem::path(o.out);
    if (o.control.sweep && o.out.empty())
        out = std::filesystem::path("out") / ("sweep-" + specStem(o.scene) + "-" + specStem(o.path) + "-" + timestampForName());
    if (std::filesystem::exists(out) && !o.replace)
        throw std::invalid_argument("--out " + out.string() + ": already exists; expected a new directory (or --replace)");
    return out;
}

// The scene and path named without loading the scene: a built-in name or a file that is
// there, a path file parsed (it needs no scene). What needs the scene itself (a glTF's
// contents, its camera for --path gltf, --animation names) is checked when the run loads
// it, still before any output.
void checkSpecs(const RunOptions& o) {
    const auto& procedural = scene::proceduralScenes();
    const bool named = std::any_of(procedural.begin(), procedural.end(), [&](const auto& s) { return s.name == o.scene; });
    std::error_code ec;
    // Neither: loadScene says what is wrong in its own words, having loaded nothing.
    if (!named && !std::filesystem::is_regular_file(o.scene, ec)) (void)scene::loadScene(o.scene);
    if (isGltfPathSpec(o.path)) return;
    if (std::filesystem::path(o.path).extension() == ".json") {
        (void)paths::loadPath(o.path);
        return;
    }
    const auto& builtin = paths::builtinPaths();
    if (std::none_of(builtin.begin(), builtin.end(), [&](const auto& b) { return b.name == o.path; }))
        (void)paths::builtinPath(o.path, {});  // throws, naming the paths there are
}

}  // namespace

void checkRunOptions(const RunOptions& o) {
    Prepared p;
    p.settings = settingsFromOptions(o);
    makeConfigs(o, p);
    checkSpecs(o);
    (void)outputDirectory(o);
}

Prepared prepare(const RunOptions& o) {
    Prepared p;
    p.options = o;
    p.settings = settingsFromOptions(o);
    makeConfigs(o, p);
    loadSceneAndPath(o, p);
    p.out = outputDirectory(o);
    return p;
}

}  // namespace cbr::harness
