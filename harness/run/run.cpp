// `cbrbench run`: prepare, open the device, upload, render, score, write.
#include "harness/run/run.h"

#include <chrono>
#include <cstdio>
#include <iostream>

#include "harness/output/exports.h"
#include "harness/output/outputs.h"
#include "harness/run/run_internal.h"
#include "harness/run/memory_check.h"
#include "harness/output/table_roles.h"
#include "metrics/cvvdp.h"
#include "renderer/vk/bandwidth.h"
#include "reports/output_dir.h"
#include "reports/report.h"
#include "reports/sweep.h"
#include "rundir/files.h"
#include "rundir/run_json_health.h"

namespace cbr::harness {
namespace {

// The device's image size limit against the resolution (and the ssaa reference's).
void checkDeviceLimits(const RunOptions& options, const render::Settings& settings, const vk::Context& ctx) {
    uint32_t max_dim = ctx.caps.max_image_dimension_2d;
    if (settings.width > max_dim || settings.height > max_dim)
        throw std::invalid_argument("--res " + options.resolution.text() + ": above the device limit; expected each side <= " +
                                    std::to_string(max_dim) + " on " + ctx.description.name);

    const int ssaa = options.tune.ssaa;
    if (options.tune.reference == settings::Reference::Ssaa &&
        (settings.width * uint32_t(ssaa) > max_dim || settings.height * uint32_t(ssaa) > max_dim))
        throw std::invalid_argument("--ssaa " + std::to_string(ssaa) + ": the " + options.resolution.text() +
                                    " reference would exceed the device limit of " + std::to_string(max_dim) +
                                    "; expected a smaller factor or resolution");
}

// The scene on the device, timed for run.json and the load line on stderr.
gpu::GpuScene uploadScene(vk::Context& ctx, Prepared& p, WallAccount& wall) {
    WallAccount::Scope scope(wall, WallPart::Upload);
    gpu::GpuScene gpu_scene = gpu::uploadScene(ctx, p.scene);
    p.load.upload_s = scope.seconds();
    return gpu_scene;
}

// What the run will hold, for its memory estimate.
MemoryPlan memoryPlan(const RunState& s) {
    MemoryPlan plan;
    plan.resolution = s.options.resolution.text();
    plan.width = s.w;
    plan.height = s.h;
    plan.configs = s.p.configs.size();
    plan.scored = s.options.tune.reference == settings::Reference::Ssaa ? plan.configs : plan.configs - 1;
    plan.frames = s.p.poses.size();
    plan.repeat = s.options.repeat;
    plan.device_scorer = s.results.scorer == "device";
    for (const auto& c : s.p.configs) plan.analysis |= c.settings.analysis;
    const auto cvvdp = metrics::makeCvvdpModel(s.w, s.h, s.options.tune.display, s.p.cvvdp_fps);
    plan.cvvdp_window = cvvdp.image ? 1 : cvvdp.filterFrames();
    plan.host_limit_mib = s.options.control.host_memory_limit_mib;
    plan.device_limit_mib = s.options.control.device_memory_limit_mib;
    return plan;
}

// Renderers and scene released, then what is measured once the frames are done: the copy
// bandwidth, the peak memory and the run's wall time.
void releaseAndMeasure(RunState& s) {
    s.renderers.clear();
    gpu::destroyGpuScene(s.ctx, s.gpu_scene);
    // The yardstick of the resolve's effective bandwidth (run.json, report). Not on lavapipe:
    // its timestamps do not bracket a transfer (a 64 MiB copy read as 10 TB/s).
    // Not on lavapipe: its timestamps around a lone dispatch or copy in a one-off submission
    // do not bracket the work (a 64 MiB compute copy read as 8 TB/s).
    if (!s.ctx.description.is_lavapipe) {
        WallAccount::Scope scope(s.wall, WallPart::Bandwidth);
        s.results.copy_bandwidth = vk::measureCopyBandwidth(s.ctx, 512);
    }
    s.results.scene_load = s.p.load;
    s.results.scene_load.peak_rss_mib_end = peakRssMib();
}

// The result files, the report, the move to the final directory and the printed summary.
// run.json is written before the report (the page reads it), so its wall account is
// written again once the report is done, with the final total.
void writeFiles(RunState& s, reports::OutputDir& out) {
    const RunOptions& options = s.options;
    const Prepared& p = s.p;
    RunContext rc{options, p.settings, p.scene, p.path, p.times, p.poses, s.ctx, s.results, &p.placement, &s.wall};
    s.results.seconds = s.wall.elapsed();  // so far: the files written next show it, run.json gets the total
    {
        WallAccount::Scope scope(s.wall, WallPart::Outputs);
        writeOutputs(out.path(), rc);
        if (options.control.sweep) writeSweepCsv(out.path(), rc);
        writeExports(out.path(), options.exports);
    }
    {
        WallAccount::Scope scope(s.wall, WallPart::Report);
        if (!options.control.silent) reports::writeReport(out.path());
        if (options.control.sweep) reports::writeSweepReport(out.path(), variantRoles());
    }
    noteMemory(s.ctx, rundir::run::memory::kReport, s.results.memory, s.wall);
    s.wall.close();
    s.results.seconds = s.wall.total();
    updateRunJsonWall(out.path(), rc);
    out.commit();
    // An outer sweep's run is renamed once more with the others: name where it will be.
    const std::filesystem::path shown = options.control.shown_out.empty() ? out.finalPath() : std::filesystem::path(options.control.shown_out);
    if (!options.control.silent) printSummary(std::cout, shown, rc);
    if (options.control.sweep) {
        for (const auto& line : reports::sweepSummaryLines(reports::loadSweep(out.finalPath()).points, variantRoles()))
            std::cout << line << "\n";
        std::cout << "sweep: " << (shown / rundir::kSweepCsv).string() << ", " << (shown / rundir::kSweepHtml).string() << "\n";
    }
}

}  // namespace

int runBenchmark(const RunOptions& options) {
    WallAccount wall;
    Prepared p = [&] {
        WallAccount::Scope scope(wall, WallPart::SceneLoad);
        return prepare(options);
    }();
    auto open_device = [&] {
        WallAccount::Scope scope(wall, WallPart::DeviceOpen);
        return std::make_unique<vk::Context>(vk::ContextOptions{options.validate, options.device});
    };
    std::unique_ptr<vk::Context> ctx_owner = open_device();
    vk::Context& ctx = *ctx_owner;
    checkDeviceLimits(options, p.settings, ctx);
    reports::OutputDir out(p.out, options.replace);
    if (options.save_frames) std::filesystem::create_directories(out.path() / "frames");
    gpu::GpuScene gpu_scene = uploadScene(ctx, p, wall);
    // Released on every way out, an interrupt's exception included: destroying the device
    // with the scene's images and buffers alive leaks them (LeakSanitizer, validation).
    // Declared before the renderers, so it runs after theirs; destroyGpuScene is idempotent.
    struct SceneRelease {
        vk::Context& ctx;
        gpu::GpuScene& scene;
        ~SceneRelease() { gpu::destroyGpuScene(ctx, scene); }
    } scene_release{ctx, gpu_scene};

    RunState s(p, ctx, gpu_scene, out.path(), wall);
    makeRenderers(s);
    makeSsaaReference(s);
    chooseScorer(s);
    checkMemory(memoryPlan(s), ctx, s.results.memory);
    calibrateSlowdown(s);  // refuses a --debug-slowdown pass that no variant has
    // Once the run is known to fit and its slowdown to apply: a refused run says one line, and nothing else.
    if (!options.control.silent) std::fprintf(stderr, "cbrbench: %s\n", sceneLoadLine(p.scene, p.load).c_str());
    renderQualityFrames(s);
    noteMemory(s.ctx, rundir::run::memory::kQualityPass, s.results.memory, s.wall);
    renderRepetitions(s);
    assessHealth(s);
    s.spill.close();  // every timed row is in it: frames.csv is written from it
    noteMemory(s.ctx, rundir::run::memory::kTimedFrames, s.results.memory, s.wall);
    scoreFrames(s);
    noteMemory(s.ctx, rundir::run::memory::kWorstImages, s.results.memory, s.wall);
    releaseAndMeasure(s);
    writeFiles(s, out);
    if (!options.control.silent) std::fprintf(stderr, "cbrbench: %s\n", s.wall.line().c_str());
    return 0;
}

}  // namespace cbr::harness
