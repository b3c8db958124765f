// The run's steps, shared by run.cpp, run_prepare.cpp and run_loop.cpp (not for other commands).
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <vector>

#include "camera_paths/path.h"
#include "harness/jobs/builtin_context.h"
#include "harness/output/frame_rows.h"
#include "harness/run/machine_sampler.h"
#include "harness/jobs/options.h"
#include "harness/base/progress.h"
#include "harness/quality/quality.h"
#include "harness/figures/results.h"
#include "harness/figures/scene_load.h"
#include "harness/jobs/sweep_configs.h"
#include "harness/base/wall_account.h"
#include "harness/base/worker_pool.h"
#include "renderer/gpu/gpu_scene.h"
#include "renderer/renderer.h"
#include "renderer/scoring/frame_scoring.h"
#include "renderer/scene/scene.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/context.h"

namespace cbr::harness {

// Everything checked before the first output exists.
struct Prepared {
    RunOptions options;
    render::Settings settings;
    scene::Scene scene;
    paths::CameraPath path;
    std::vector<double> times;
    std::vector<paths::CameraPose> poses;
    // The frame rate the scored frames stand for, ColorVideoVDP's: the frames' spacing along the
    // path, (frames - 1) / the time they span; 0 for a single frame (scored as an image).
    double cvvdp_fps = 0;
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

// Options to settings, configurations, scene and path, output directory (run_prepare.cpp).
Prepared prepare(const RunOptions& o);

// The state the render loop's steps share, from the uploaded scene to the scored frames.
// Members are destroyed in reverse: renderers, then the scorer, then the workers (which
// finish their PNG writes into `out` before the output directory goes).
struct RunState {
    RunState(const Prepared& p, vk::Context& ctx, gpu::GpuScene& gpu_scene, const std::filesystem::path& out,
             WallAccount& wall);
    // The scorer's jobs write into quality_rows, which is destroyed before the scorer and the
    // workers: a run that unwinds (a failure, an interrupt) waits for them first.
    ~RunState() { workers.wait(); }

    const Prepared& p;
    const RunOptions& options;
    vk::Context& ctx;
    gpu::GpuScene& gpu_scene;
    const std::filesystem::path out;  // the temporary output directory
    WallAccount& wall;  // started before the scene loaded
    const int w, h;
    RunResults results;
    // The timed frame rows, written out as each is made (frame_rows.h); append() also keeps
    // a row's numbers in results.digest.
    FramesSpill spill;
    void append(const FrameRow& row) {
        spill.append(row);
        results.digest.add(row);
    }
    WorkerPool workers;
    QualityScorer scorer;
    // The alignment check looks at the middle frame of a path of at least 3 frames.
    const size_t mid;
    std::vector<Bytes> mid_images;
    std::vector<Bytes> reference_frames;  // only the alignment check's, around the middle frame
    // The quality pass's rows, one per (configuration, frame): only their scores are kept,
    // copied into repetition 0's timed rows.
    std::vector<FrameRow> quality_rows;
    FrameRow& qualityRow(size_t config, size_t frame) { return quality_rows[config * p.poses.size() + frame]; }
    ProgressBar progress;  // frames rendered, on a terminal
    // --scorer device (or auto on a GPU): the metrics in Vulkan compute, shared by the
    // renderers (declared before them, so it outlives them).
    std::unique_ptr<scoring::DeviceScoring> device_scoring;
    // One renderer per variant for the whole run: pipelines and targets are built once.
    std::vector<std::unique_ptr<render::Renderer>> renderers;
    std::unique_ptr<render::Renderer> ssaa_reference;  // --reference ssaa, during the quality pass
    // The machine while frames are timed (CPU load, NVML on NVIDIA): started and stopped
    // around the repetitions.
    MachineSampler sampler;
};

// The `rep` of a ConfigPass that renders the untimed, scored quality frames.
constexpr int kQualityPass = -1;

// The first configuration is full: the reference, unless `--reference ssaa` (a sweep's
// other full configurations differ only in shading cost and are scored against it).
inline bool isReference(const RunState& s, size_t vi) { return vi == 0 && s.options.tune.reference != settings::Reference::Ssaa; }

// The steps in the order runBenchmark calls them: one renderer per configuration (run_setup.cpp),
void makeRenderers(RunState& s);
// `--reference ssaa`'s supersampled renderer (run_loop.cpp),
void makeSsaaReference(RunState& s);
// --scorer: the device scorer for every renderer, or the CPU's (RunResults::scorer says which;
// run_setup.cpp); then checkMemory (memory_check.h), and the loop (run_loop.cpp):
void chooseScorer(RunState& s);
void calibrateSlowdown(RunState& s);
void renderQualityFrames(RunState& s);
void renderRepetitions(RunState& s);
// Drift, warm-up and the machine's state into results.health; unsteady configurations get
// that status (run_health.cpp).
void assessHealth(RunState& s);
void scoreFrames(RunState& s);

}  // namespace cbr::harness
