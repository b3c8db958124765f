// cbrbench's subcommands (cli.h): options and actions, one factory per command.
#include "harness/cli.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "camera_paths/path.h"
#include "harness/ab/ab.h"
#include "harness/calibrate/calibrate.h"
#include "harness/cli_text.h"
#include "harness/compare/compare.h"
#include "harness/jobs/job_matrix.h"
#include "harness/run/run.h"
#include "harness/output/table_roles.h"
#include "harness/jobs/sweep_configs.h"
#include "harness/export/export.h"
#include "harness/help_markdown.h"
#include "harness/matrix/matrix.h"
#include "harness/score/metric_cost.h"
#include "harness/score/score_image.h"
#include "harness/score/score_seq.h"
#include "harness/score/sequence_files.h"
#include "harness/stress/stress.h"
#include "harness/sweep/sweep.h"
#include "metrics/cvvdp.h"
#include "metrics/flip.h"
#include "renderer/scene/scene.h"
#include "renderer/variants/variants.h"
#include "renderer/vk/context.h"
#include "reports/report.h"
#include "reports/sweep.h"
#include "settings/options.h"
#include "rundir/files.h"

namespace cbr::harness {
namespace {

// "full, drr, ...": the variant table's names, so the help lists exactly what runs.
std::string variantNames() {
    std::string out;
    for (const auto& v : variants::allVariants()) out += (out.empty() ? "" : ", ") + std::string(v.name);
    return out;
}

// --flip-ppd of score and metric-cost: the table's row, as run's.
const std::string kFlipPpdHelp = settings::optionHelp(*settings::find("flip-ppd"));
const std::string kDisplayHelp = settings::optionHelp(*settings::find("display"));

// The devices, each column as wide as its content; the default is marked as chooseDevice picks it.
int listDevices() {
    const auto devices = cbr::vk::listDevices();
    const auto lavapipe = std::find_if(devices.begin(), devices.end(), [](const auto& d) { return d.is_lavapipe; });
    const int chosen = lavapipe != devices.end() ? lavapipe->index : 0;
    std::vector<std::vector<std::string>> rows = {{"index", "name", "type", "driver", "api", ""}};
    for (const auto& d : devices)
        rows.push_back({std::to_string(d.index), d.name, d.device_type, d.driver_name + " " + d.driver_info,
                        d.api_version, d.index == chosen ? "(default)" : ""});
    printColumns(rows);
    if (devices.empty()) std::printf("no Vulkan device found; expected lavapipe (mesa-vulkan-drivers) or a GPU\n");
    return 0;
}

// The options of `run` and `sweep` (a sweep is a run over configurations): the typed ones
// into `o`, the lists and parsed values as words into `w` (parseMatrixSpec reads them).
void addRunOptions(CLI::App* cmd, RunOptions& o, RunWords& w) {
    cmd->add_option("--scene", w.scene, "procedural scene name (cbrbench scenes) or a .gltf/.glb file")->capture_default_str();
    cmd->add_option("--path", w.path,
                    "built-in path name (cbrbench paths), a path .json file, or gltf / gltf:NAME (the scene file's camera)")
        ->capture_default_str();
    cmd->add_option("--fps", o.fps, "frame rate of a --path gltf camera (frames over the animation's length)")
        ->capture_default_str();
    cmd->add_option("--animation", o.animation,
                    "glTF animations to play: all, none, or a comma list of names or indices (looped)")
        ->capture_default_str();
    cmd->add_option("--variants", w.variants,
                    "comma-separated variants of " + variantNames() + " (default: all; full always runs: the reference)");
    cmd->add_option("--res", w.resolution, "output resolution WIDTHxHEIGHT")->capture_default_str();
    cmd->add_option("--frames", o.frames,
                    "frames sampled evenly over the path (0: the path's own length; --path gltf: default 0)")
        ->capture_default_str()
        ->each([&o](const std::string&) { o.frames_set = true; });
    cmd->add_option("--repeat", o.repeat, "repetitions of the whole flythrough, variants interleaved")
        ->capture_default_str();
    cmd->add_option("--warmup", o.warmup, "untimed warm-up frames per variant and repetition, at least; more until the frame time is steady (0: none)")->capture_default_str();
    cmd->add_option("--device", o.device, "device index or name substring (default: lavapipe, else the first)");
    cmd->add_flag("--validate", o.validate, "enable the Khronos validation layer and count its messages");
    cmd->add_flag("--save-frames", o.save_frames, "save display images as PNG (the scored quality pass)");
    cmd->add_option("--export", w.exports, "also write the results as: gbench (gbench.json, Google Benchmark JSON)");
    cmd->add_option("--out", o.out, "output directory (default out/<scene>-<path>-<date-time>)");
    cmd->add_flag("--replace", o.replace,
                  "replace --out if it exists (a folder cbrbench wrote): swapped in one step once the new one is "
                  "complete; a failed or interrupted run leaves the old one");
    cmd->add_option_function<std::string>(
           "--debug-slowdown",
           [&o](const std::string& text) {
               try {
                   o.debug_slowdown = parseSlowdown(text);
               } catch (const std::invalid_argument& e) {
                   throw CLI::ValidationError(e.what());
               }
           },
           "PASS=PCT: make one pass PCT percent slower with calibrated extra GPU work (tests the detector; needs "
           "--warmup >= 2)")
        ->type_name("PASS=PCT");
    cmd->add_option("--pipeline", w.pipeline, "forward or deferred (G-buffer, lighting resolve)")->capture_default_str();
    settings::addOptions(cmd, o.tune);
    cmd->add_option("--scene-offset", w.scene_offset, "X,Y,Z: move the scene and the camera path by this (e.g. 1e6,1e6,1e6)");
    cmd->add_option("--scene-scale", o.scene_scale, "scale the scene and the camera path about the origin (0.001: mm)")
        ->capture_default_str();
    cmd->add_option("--near", o.near, "near plane of every keyframe, scene units (after placement)");
    cmd->add_option("--far", o.far, "far plane of every keyframe, scene units (after placement)");
    cmd->add_option("--host-memory-limit", o.control.host_memory_limit_mib,
                    "MiB: refuse a run whose estimated peak is above this (default: what the host has available)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--device-memory-limit", o.control.device_memory_limit_mib,
                    "MiB: refuse a run whose estimated device memory is above this (default: the device's budget)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--scoring-threads", o.control.scoring_threads,
                    "worker threads of the CPU scorer (default 0: half the hardware threads), at most as many as "
                    "frames its memory budget holds (2 at 3840x2160); the scores do not depend on it")
        ->check(CLI::Range(0, 256));
}


// A command that prints a list and exits 0.
Command listing(CLI::App& app, const char* name, const char* description, std::function<void()> print) {
    return {app.add_subcommand(name, description), [print] {
                print();
                return 0;
            }};
}

Command reportCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("report", "rebuild DIR/report.html from the files in DIR, without rendering");
    auto dir = std::make_shared<std::string>();
    cli->add_option("DIR", *dir, "a run's output directory")->required();
    return {cli, [dir] {
                if (!std::filesystem::is_directory(*dir))
                    throw std::invalid_argument("report " + *dir + ": not a directory; expected a run's output directory");
                const std::filesystem::path d(*dir);
                const bool sweep_dir = std::filesystem::exists(d / rundir::kSweepCsv);
                // A sweep's directory may be copied without its per-frame files: sweep.html alone.
                if (!sweep_dir || std::filesystem::exists(d / rundir::kSummaryCsv)) {
                    reports::writeReport(d);
                    std::printf("report: %s\n", (d / rundir::kReportHtml).c_str());
                }
                if (sweep_dir) {
                    reports::writeSweepReport(d, variantRoles());
                    std::printf("sweep report: %s\n", (d / rundir::kSweepHtml).c_str());
                }
                return 0;
            }};
}

Command compareCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("compare", "regression verdicts: CURRENT_DIR against BASELINE_DIR (exit 0 same, "
                                               "1 regression, 2 inconclusive: no cell decided, or UNKNOWN cells with "
                                               "--strict, 3 bad input, 70 an unexpected error)");
    auto cmp = std::make_shared<CompareOptions>();
    cli->add_option("BASELINE_DIR", cmp->baseline_dir, "the baseline run's output directory")->required();
    cli->add_option("CURRENT_DIR", cmp->current_dir, "the current run's output directory (gets compare.*)")->required();
    cli->add_option("--threshold", cmp->threshold, "time change that counts (e.g. 3% or 0.03)")->capture_default_str();
    cli->add_option("--alpha", cmp->alpha, "false discovery rate across cells")->capture_default_str();
    cli->add_option("--psnr-threshold", cmp->psnr_db, "PSNR change that counts, dB")->capture_default_str();
    cli->add_option("--ssim-threshold", cmp->ssim, "SSIM change that counts")->capture_default_str();
    cli->add_option("--eci-threshold", cmp->eci, "relative ECI change that counts")->capture_default_str();
    cli->add_option("--jod-threshold", cmp->jod, "ColorVideoVDP JOD change that counts (a larger drop is WORSE), JOD")
        ->capture_default_str();
    cli->add_option("--junit", cmp->junit,
                    "also write the verdicts as JUnit XML to FILE (SLOWER/WORSE: failures, UNKNOWN: skipped)");
    cli->add_flag("--strict", cmp->strict, "UNKNOWN cells give exit code 2");
    // Its callers read exit 2 as "inconclusive": its bad input is 3.
    return {cli, [cmp] { return runCompare(*cmp); }, kCompareBadInput, kExitVerdictError};
}

Command abCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand(
        "ab", "A/B of two builds or two option sets on this machine: runs in ABBA order, added to both sides until "
              "every cell is SAME, SLOWER or FASTER or the budget is spent (exit 0 settled, 1 regression, 2 bad "
              "input, 3 undecided, 4 a run failed, 70 an unexpected error); run arguments of both sides after --");
    auto a = std::make_shared<AbOptions>();
    cli->add_option("RUN_ARGS", a->run_args, "run options both sides take, after -- (e.g. -- --res 640x360 --variants "
                                             "full,cbr-aso)");
    cli->add_option("--a-bin", a->a_bin, "side A's (the baseline's) cbrbench binary (default: this one)");
    cli->add_option("--b-bin", a->b_bin, "side B's cbrbench binary (default: this one)");
    cli->add_option("--a-args", a->a_args, "run options of side A only, one string split at spaces (not one the "
                                           "shared run options already give)");
    cli->add_option("--b-args", a->b_args, "run options of side B only, e.g. \"--debug-slowdown opaque=2\"");
    cli->add_option("--threshold", a->threshold, "time change that counts (e.g. 3% or 0.03)")->capture_default_str();
    cli->add_option("--alpha", a->alpha, "false-alarm rate over all looks and cells")->capture_default_str();
    cli->add_option("--repeat", a->repeat, "repetitions of every run")->capture_default_str();
    cli->add_option("--max-runs", a->max_runs, "budget: runs per side (even; ABBA blocks add 2)")->capture_default_str();
    cli->add_option("--max-seconds", a->max_seconds, "budget: seconds; no block starts that would end past it (0: none)")
        ->capture_default_str();
    cli->add_option("--unit", a->unit, "the sample: run (each run's median) or repetition (every repetition's "
                                       "median)")->capture_default_str();
    cli->add_option("--psnr-threshold", a->psnr_db, "PSNR change that counts, dB")->capture_default_str();
    cli->add_option("--ssim-threshold", a->ssim, "SSIM change that counts")->capture_default_str();
    cli->add_option("--eci-threshold", a->eci, "relative ECI change that counts")->capture_default_str();
    cli->add_option("--out", a->out, "output directory (default out/ab-<date-time>)");
    cli->add_option("--junit", a->junit, "also write the verdicts as JUnit XML to FILE (SLOWER, WORSE and "
                                         "undecided: failures)");
    cli->add_flag("--quiet", a->quiet, "no line per run on stdout (the looks and the table still print)");
    cli->add_flag("--no-stop", a->no_stop, "run the whole budget even when settled early (the verdicts are the same; "
                                           "calibrate --settle replays the runs)");
    return {cli,
            [a, argv] {
                a->argv = argv;
                return runAb(*a);
            },
            kAbBadInput, kExitVerdictError};
}

Command exportCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("export", "write a run's results in another tool's format (gbench: Google "
                                              "Benchmark JSON, which compare.py and benchmark dashboards read)");
    struct Args {
        std::string dir, format, out;
    };
    auto a = std::make_shared<Args>();
    cli->add_option("RUN_DIR", a->dir, "a run's output directory")->required();
    cli->add_option("--format", a->format, "gbench")->required();
    cli->add_option("--out", a->out, "the file to write (default: RUN_DIR/gbench.json)");
    return {cli, [a] {
                const auto formats = parseExportFormats(a->format, "export --format");
                if (formats.size() != 1)
                    throw std::invalid_argument("export --format: give one format; accepted: " + std::string(kExportFormats));
                return runExport(a->dir, formats[0], a->out);
            }};
}

Command calibrateCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand("calibrate", "false-alarm and detection rates of compare's time verdicts on "
                                                 "this device: A/A pairs and injected slowdowns (calibrate.csv)");
    auto cal = std::make_shared<CalibrateOptions>();
    auto words = std::make_shared<RunWords>();
    addRunOptions(cli, cal->run, *words);
    cli->add_option("--pairs", cal->pairs, "A/A pairs (two runs of the same settings)")->capture_default_str();
    cli->add_option("--slow-pairs", cal->slow_pairs, "pairs per injected slowdown")->capture_default_str();
    cli->add_option("--slowdown", cal->slowdowns, "PASS=PCT[,PCT...]: slowdowns injected with --debug-slowdown "
                                                  "(empty: A/A only)")->capture_default_str();
    cli->add_option("--repeats", cal->repeats, "repetition counts judged, each >= 3 (runs use the largest)")
        ->capture_default_str();
    cli->add_option("--threshold", cal->threshold, "compare's --threshold")->capture_default_str();
    cli->add_option("--alpha", cal->alpha, "compare's --alpha")->capture_default_str();
    cli->add_option("--from", cal->from, "an earlier calibration's directory: judge its runs again (other "
                                         "--threshold, --alpha or --repeats) without rendering");
    cli->add_flag("--settle", cal->settle, "pairs through `cbrbench ab` (ABBA, runs added until settled), each run to "
                                           "--max-runs and replayed with both sample units: calibrate_settle.csv; "
                                           "--repeats' smallest count is every run's repetitions");
    cli->add_option("--max-runs", cal->max_runs, "--settle: ab's budget, runs per side")->capture_default_str();
    return {cli, [cal, words, argv] {
                if (words->variants.empty()) words->variants = variants::referenceVariant().name;
                cal->run.control.argv = argv;
                const MatrixSpec spec = parseMatrixSpec(*words, cal->run);
                if (spec.jobCount() != 1)
                    throw std::invalid_argument("calibrate: comma lists in --scene, --path, --pipeline or --res; "
                                                "expected one of each (calibrate judges one job)");
                cal->run = spec.firstJob();
                cal->out = cal->run.out;
                return runCalibrate(*cal);
            }};
}

Command metricCostCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("metric-cost", "benchmark: PSNR, SSIM, ECI, FLIP and ColorVideoVDP milliseconds per frame, on the "
                                                   "CPU and on the device");
    auto a = std::make_shared<MetricCostOptions>();
    auto res = std::make_shared<std::string>(a->res.text());
    cli->add_option("--res", *res, "frame size WIDTHxHEIGHT")->capture_default_str();
    cli->add_option("--frames", a->frames, "timed frames (median reported)")->capture_default_str();
    cli->add_option("--flip-ppd", a->flip_ppd, kFlipPpdHelp);
    cli->add_option("--display", a->display, kDisplayHelp)->capture_default_str();
    cli->add_option("--fps", a->fps, "ColorVideoVDP's frame rate (its temporal window)")->capture_default_str();
    cli->add_option("--scorer", a->scorer, "which scorers: cpu, device, or all")
        ->capture_default_str()
        ->check(CLI::IsMember({"all", "cpu", "device"}));
    cli->add_option("--device", a->device, "device index or name substring for the device scorer (default: lavapipe, else the first)");
    return {cli, [a, res] {
                a->res = parseResolution(*res);
                return runMetricCost(*a);
            }};
}

Command scoreCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("score", "PSNR, SSIM, ColorVideoVDP (JOD) and FLIP of an image against a reference (any format "
                                             "OpenImageIO reads; linear EXR/HDR tone-mapped as the renderer does)");
    struct Args {
        std::string ref, img, crop, display = "standard_4k";
        double flip_ppd = 0;
        float exposure = 1.0f;
    };
    auto a = std::make_shared<Args>();
    cli->add_option("REFERENCE", a->ref, "reference image")->required();
    cli->add_option("IMAGE", a->img, "image to score (the same size)")->required();
    cli->add_option("--crop", a->crop, "score only X,Y,W,H (e.g. to leave out a border column)");
    cli->add_option("--display", a->display, kDisplayHelp)->capture_default_str();
    cli->add_option("--flip-ppd", a->flip_ppd, kFlipPpdHelp);
    cli->add_option("--exposure", a->exposure, "exposure of the display transform for linear (float) inputs")
        ->capture_default_str();
    return {cli, [a] { return scoreImages(a->ref, a->img, a->crop, a->flip_ppd, a->exposure, a->display); }};
}

Command scoreSeqCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand(
        "score-seq", "PSNR, SSIM, ColorVideoVDP (JOD), FLIP, edge crawl and flicker of an image sequence against a reference sequence, "
                     "per frame, with a report; exit 0 pass, 1 --warn crossed, 2 --fail crossed, 3 sizes differ, "
                     "4 a file missing or unreadable, 5 a bad option (idiff's convention), 70 an unexpected error");
    auto seq = std::make_shared<ScoreSeqOptions>();
    cli->add_option("REFERENCE", seq->reference, "reference frames: a folder (natural name order) or a pattern "
                                                 "such as ref/frame_%04d.png")->required();
    cli->add_option("TEST", seq->test, "frames to score, the same way (two patterns: matched by frame number, "
                                       "else by position)")->required();
    cli->add_option("--motion", seq->motion, "float images (EXR) of the reference's motion in pixels, matched like "
                                             "TEST: the surface at p in frame t was at p + (R,G) in frame t-1 "
                                             "(default: one global translation per frame by phase correlation)");
    cli->add_option("--motion-scale", seq->motion_scale, "SX,SY multiplying the motion files' R and G into that "
                                                         "convention")->capture_default_str();
    cli->add_option("--cuts", seq->cuts, "frame numbers that start a new shot (no edge-crawl pair across them)")
        ->delimiter(',');
    cli->add_option("--name", seq->name, "label of the test sequence (default: its folder's name)");
    cli->add_option("--out", seq->out, "output folder, must not exist unless --replace (default out/score-seq-<date-time>)");
    cli->add_flag("--replace", seq->replace, "replace --out if it exists (a folder cbrbench wrote), in one step once complete");
    cli->add_option("--display", seq->display, kDisplayHelp)->capture_default_str();
    cli->add_option("--fps", seq->fps, "frames per second the sequence stands for (ColorVideoVDP's temporal channels)")
        ->capture_default_str();
    cli->add_option("--flip-ppd", seq->flip_ppd, kFlipPpdHelp)->capture_default_str();
    cli->add_option("--exposure", seq->exposure, "exposure of the display transform for linear (float) inputs")
        ->capture_default_str();
    cli->add_option("--warn", seq->warn, "METRIC=VALUE (repeatable): exit 1 when the worst frame crosses it; "
                                         "METRIC psnr or ssim (crossed below), flip, eci or flicker (above)");
    cli->add_option("--fail", seq->fail, "METRIC=VALUE (repeatable): exit 2 when the worst frame crosses it");
    // idiff's convention, where 2 is a failed comparison: a bad option is 5.
    return {cli,
            [seq, argv]() -> int {
                seq->argv = argv;
                try {
                    return runScoreSeq(*seq);
                } catch (const SequenceError& e) {
                    std::fprintf(stderr, "cbrbench: %s\n", e.what());
                    return e.code;
                } catch (const std::invalid_argument& e) {
                    std::fprintf(stderr, "cbrbench: %s\n", e.what());
                    return kSeqBadOption;
                }
            },
            kSeqBadOption, kExitVerdictError};
}

// `run`, `plan` and `sweep` take the run options; `run` and `sweep` render.
struct RunArgs {
    RunOptions o;
    RunWords words;
    int shards = 1;
    // The command line typed, and recorded: a bad word throws here, before anything runs.
    MatrixSpec spec(const std::vector<std::string>& argv) {
        o.control.argv = argv;
        return parseMatrixSpec(words, o);
    }
};

Command runCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand("run", "render a flythrough through the variants; write summary.csv, frames.csv, "
                                          "run.json, report.html and worst/ (each variant's worst frames) to --out");
    auto r = std::make_shared<RunArgs>();
    addRunOptions(cli, r->o, r->words);
    cli->add_option("--shard", r->words.shard,
                    "I/N: run shard I (0-based) of N of a job matrix (comma lists in --scene, --path, --pipeline, "
                    "--res); a matrix also reads SLURM_ARRAY_TASK_ID/COUNT or GTEST_SHARD_INDEX/TOTAL_SHARDS");
    return {cli, [r, argv] {
                const MatrixSpec spec = r->spec(argv);
                if (spec.isMatrix()) return runMatrix(spec, spec.shard ? *spec.shard : shardFromEnvironment());
                return runBenchmark(spec.firstJob());
            }};
}

Command planCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand("plan", "print the job matrix (scene x path x pipeline x resolution) with stable "
                                            "job ids and shards; takes run's options");
    auto r = std::make_shared<RunArgs>();
    addRunOptions(cli, r->o, r->words);
    cli->add_option("--shards", r->shards, "number of shards to assign jobs to")->capture_default_str();
    return {cli, [r, argv] { return printPlan(r->spec(argv), r->shards); }};
}

Command sweepCommand(CLI::App& app, const std::vector<std::string>& argv) {
    auto* cli = app.add_subcommand("sweep", "run the variants over swept settings, interleaved in one process; write "
                                             "sweep.csv and sweep.html (recommended value per swept setting, quality at equal cost)");
    auto r = std::make_shared<RunArgs>();
    addRunOptions(cli, r->o, r->words);
    cli->add_option("--param", r->o.params,
                    "NAME=LO:HI:log|lin:N or NAME=V1,V2,... (repeatable; word-valued names take a list only): " +
                        sweepParamSummary() +
                        "; reference runs one sweep per value into OUT/ref=K/, as --path a,b runs one per path")
        ->required();
    return {cli, [r, argv] {
                r->o.control.sweep = true;
                const MatrixSpec spec = r->spec(argv);
                // The paths are the sweep's outer dimension (one sweep per path), not jobs.
                if (spec.scenes.size() > 1 || spec.pipelines.size() > 1 || spec.resolutions.size() > 1)
                    throw std::invalid_argument("sweep: comma lists in --scene, --pipeline or --res; expected one of "
                                                "each (a sweep is one job: its configurations are compared with each "
                                                "other; --path may list several)");
                return runSweep(spec.firstJob(), spec.paths);
            }};
}

Command mergeCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("merge", "merge shard outputs of one plan into one directory (refuses mixed "
                                             "devices, plans and duplicate jobs)");
    struct Args {
        std::vector<std::string> dirs;
        std::string out;
        bool replace = false;
    };
    auto a = std::make_shared<Args>();
    cli->add_option("DIR", a->dirs, "shard output directories")->required();
    cli->add_option("--out", a->out, "the merged directory (must not exist unless --replace)")->required();
    cli->add_flag("--replace", a->replace, "replace --out if it exists (a folder cbrbench wrote), in one step once complete");
    return {cli, [a] { return mergeRuns(a->dirs, a->out, a->replace); }};
}

// stress --pipelines: a comma list of pipelines.
std::vector<Pipeline> stressPipelines(const std::string& list) {
    std::vector<Pipeline> out;
    for (const auto& word : splitList(list)) {
        const auto p = findPipeline(word);
        if (!p) throw std::invalid_argument("--pipelines " + word + ": expected forward and/or deferred");
        out.push_back(*p);
    }
    return out;
}

Command stressCommand(CLI::App& app) {
    auto* cli = app.add_subcommand("stress", "named extreme cases through every variant and both pipelines; exit 0 "
                                              "only if every case's expectation holds (stress.csv, stress.html)");
    struct Args {
        StressOptions so;
        std::string cases, pipelines = "forward,deferred", resolution = so.resolution.text();
        bool list = false;
    };
    auto a = std::make_shared<Args>();
    StressOptions& so = a->so;
    cli->add_option("--res", a->resolution, "frame size of every case")->capture_default_str();
    cli->add_option("--out", so.out, "output directory (default out/stress-<date-time>)");
    cli->add_flag("--replace", so.replace, "replace --out if it exists (a folder cbrbench wrote), in one step once complete");
    cli->add_option("--device", so.device, "device index or name substring");
    cli->add_option("--cases", a->cases, "comma-separated case names (default: all; `--list` names them)");
    cli->add_option("--pipelines", a->pipelines, "forward and/or deferred")->capture_default_str();
    cli->add_option("--cbr-route", so.cbr_route,
                    std::string("checkerboard route of every run: ") + settings::accepted(*settings::find("cbr-route")) + " (default: auto)");
    cli->add_flag("--validate", so.validate, "Khronos validation layer on in every run; any message fails the case");
    cli->add_option("--static-frames", so.static_frames, "length of the static-camera case")->capture_default_str();
    cli->add_option("--subpixel-frames", so.subpixel_frames, "length of the sub-pixel motion case")
        ->capture_default_str();
    cli->add_flag("--list", a->list, "list the cases and their expectations");
    return {cli, [a] {
                if (a->list) {
                    std::vector<std::vector<std::string>> rows;
                    for (const auto& c : stressCases()) rows.push_back({c.name, c.expectation});
                    printColumns(rows);
                    return 0;
                }
                a->so.resolution = parseResolution(a->resolution);
                a->so.cases = splitList(a->cases);
                a->so.pipelines = stressPipelines(a->pipelines);
                return runStress(a->so);
            }};
}

}  // namespace

std::vector<Command> addCommands(CLI::App& app, const std::vector<std::string>& argv, bool& quiet) {
    std::vector<Command> c;
    c.push_back({app.add_subcommand("devices", "list Vulkan devices (index, name, driver, API version)"), listDevices});
    c.push_back(listing(app, "scenes", "list the built-in procedural scenes", [] {
        std::vector<std::vector<std::string>> rows;
        for (const auto& s : scene::proceduralScenes()) rows.push_back({s.name, s.description});
        printColumns(rows);
    }));
    c.push_back(listing(app, "paths", "list the built-in camera paths", [] {
        std::vector<std::vector<std::string>> rows;
        for (const auto& p : paths::builtinPaths()) rows.push_back({p.name, p.description});
        printColumns(rows);
    }));
    c.push_back(listing(app, "displays", "list the display models of --display (ColorVideoVDP's viewing conditions)", [] {
        std::vector<std::vector<std::string>> rows;
        for (const auto& name : metrics::displayNames()) {
            char ppd[32];
            std::snprintf(ppd, sizeof ppd, "%.1f ppd", metrics::parseDisplay(name).ppd());
            rows.push_back({name, ppd, metrics::displayDescription(name)});
        }
        printColumns(rows, {1});
    }));
    c.push_back(listing(app, "variants", "list the rendering variants", [] {
        std::vector<std::vector<std::string>> rows;
        for (const auto& v : variants::allVariants()) rows.push_back({std::string(v.name), std::string(v.description)});
        printColumns(rows);
    }));
    c.push_back(runCommand(app, argv));
    c.push_back(reportCommand(app));
    c.push_back(compareCommand(app));
    c.push_back(abCommand(app, argv));
    c.push_back(exportCommand(app));
    c.push_back(calibrateCommand(app, argv));
    c.push_back(metricCostCommand(app));
    c.push_back(scoreCommand(app));
    c.push_back(scoreSeqCommand(app, argv));
    c.push_back(planCommand(app, argv));
    c.push_back(mergeCommand(app));
    c.push_back(stressCommand(app));
    c.push_back(sweepCommand(app, argv));
    c.push_back(helpCommand(app));
    for (const char* name : {"run", "sweep", "stress", "merge", "calibrate", "score-seq"})
        app.get_subcommand(name)->add_flag("--quiet", quiet,
                                           "no progress bar on the terminal (none is drawn when stderr is not one)");
    return c;
}

}  // namespace cbr::harness
