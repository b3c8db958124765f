// What a run measured: one row per variant x repetition x frame (written to frames.csv as it
// is made, its numbers kept as a FrameDigest), plus per-variant facts.
#pragma once

#include "renderer/vk/bandwidth.h"
#include <map>
#include <set>
#include <optional>
#include <string>
#include <vector>

#include "harness/figures/health.h"
#include "harness/figures/scene_load.h"
#include "harness/jobs/sweep_configs.h"
#include "renderer/settings.h"

namespace cbr::harness {

struct Quality {
    std::optional<double> mse;
    std::optional<double> psnr_db;  // +inf for identical images
    std::optional<double> ssim;
    std::optional<double> ssim_luma;
    std::optional<double> eci;              // edge crawl index (metrics.md); none without a frame pair
    std::optional<double> flicker_ratio;
    std::optional<double> crawl_valid_fraction;
    double crawl_numerator = 0, crawl_denominator = 0;  // for the pooled sequence ECI
    // LDR-FLIP (metrics/flip.h): mean of the error map and its weighted quartiles.
    std::optional<double> flip_mean, flip_q1, flip_median, flip_q3;
    // ColorVideoVDP (metrics/cvvdp.h): the frame's pooled difference q; frames.csv writes its JOD.
    std::optional<double> cvvdp_q;
    std::string note;               // why a metric is missing
};

struct FrameRow {
    std::string variant;
    int repeat = 0;
    int frame = 0;
    double time_s = 0;
    uint32_t render_width = 0;
    uint32_t render_height = 0;
    double render_scale = 1;
    double gpu_ms = 0;
    bool timing_ok = true;
    std::vector<render::PassTime> passes;
    std::vector<std::pair<std::string, double>> stats;  // e.g. px_shaded (checkerboard classes)
    Quality quality;                // rep 0 only: rendering is deterministic
    std::string status = "ok";      // ok | failed | skipped
    std::string note;
};

// What is kept of the frame rows once each is written out (frame_rows.cpp): the numbers the
// summaries need, per configuration in row order (about 0.2 KB a row, against the row's few
// KB), and the columns frames.csv and summary.csv take from the rows.
struct VariantSamples {  // one configuration's ok rows
    std::vector<double> ms;
    std::vector<int> repeat, frame;  // parallel to ms: pairs a time with its baseline's
    std::vector<double> widths, heights;
    std::vector<double> psnr, ssim, ssim_luma, mse, fs, eci, flicker, flip, cvvdp_q;
    double crawl_num = 0, crawl_den = 0;
    std::map<std::string, std::vector<double>> pass_ms, stat_values;
    std::vector<std::string> pass_order, stat_order;
    void add(const FrameRow& row);
};
struct FrameColumns {  // over every row, ok or not, in first-seen order
    std::vector<std::string> stats, passes;
    std::set<std::string> fs_reported;  // passes with a fragment-invocation count in some row
    void add(const FrameRow& row);
};
struct FrameDigest {
    FrameColumns columns;
    std::map<std::string, VariantSamples> samples;  // by configuration (FrameRow::variant): ok rows
    size_t rows = 0;
    void add(const FrameRow& row);
    const VariantSamples* find(const std::string& config) const {
        auto it = samples.find(config);
        return it == samples.end() ? nullptr : &it->second;
    }
};

// metrics.md: once per sequence, PSNR(R_t, V_t) must beat PSNR(R_t, V_t-1) and
// PSNR(R_t, V_t+1) on a moving path, or the variant's frames are misaligned in time.
struct AlignmentCheck {
    int frame = 0;
    double psnr_same = 0, psnr_prev = 0, psnr_next = 0;
    bool ok = false;
};

// A variant's worst frame of one kind (lowest SSIM, highest ECI) and the files showing it:
// (what, path under the run directory) pairs, what = reference, variant, error, ssim_map,
// flip_map, crawl_map, class_map. Each file is written once, even when two entries share
// it (the same frame worst by both kinds; the reference frame of several variants).
struct WorstFrame {
    std::string variant;
    std::string kind;  // ssim | eci
    int frame = 0;
    double value = 0;
    std::vector<std::pair<std::string, std::string>> files;  // full resolution, lossless PNG
    std::vector<std::pair<std::string, std::string>> page;   // the report's copies (worst/page/)
};

struct VariantRun {
    std::string name;      // the configuration's label: the variant's name, or e.g. cbr-cso_tol=0.01 in a sweep
    std::string variant;   // the variant in the table (full, drr, cbr-aso, cbr-cso)
    std::string baseline;  // the reference configuration its speedups are paired with (run_loop sets it)
    std::vector<SweepSetting> settings;  // swept settings (sweep only)
    std::optional<AlignmentCheck> alignment;
    std::string status = "ok";  // ok | unsteady | failed | skipped
    std::string note;
    std::vector<std::string> passes_ran;
    std::vector<std::pair<std::string, std::string>> left_out;  // (pass, reason)
    std::vector<std::pair<std::string, std::string>> description;  // route and such, for run.json
};

// What the run needed and had (run.json `memory`): the estimate made before the first frame
// against its limits, and the readings after each phase.
struct MemoryFigures {
    double host_estimate_mib = 0, device_estimate_mib = 0;
    double host_limit_mib = 0, device_limit_mib = 0;
    std::string host_limit_from, device_limit_from;  // the option, or what the machine reports
    double device_allocated_peak_mib = 0;             // cbrbench's device-local allocations, at most
    double host_visible_allocated_peak_mib = 0;       // its host-visible (mapped) allocations, at most
    double device_heap_mib = 0;                       // the device-local heaps' size
    std::optional<double> device_budget_mib;          // VK_EXT_memory_budget: what the process may use
    struct Reading {
        std::string after;
        double peak_rss_mib = 0;
        double device_allocated_mib = 0;
        std::optional<double> device_usage_mib;  // VK_EXT_memory_budget's heapUsage, device-local heaps
    };
    std::vector<Reading> after;
};

struct RunResults {
    FrameDigest digest;  // the frame rows' numbers (the rows themselves are in frames.csv)
    std::vector<VariantRun> variants;
    std::vector<std::string> order;  // variant order within each repetition
    int frames = 0;
    int repeats = 0;
    double seconds = 0;         // wall time of the run
    double first_frame_seconds = 0;  // wall time from the start (scene loading included) to the first rendered frame's result (the quality pass's)
    std::vector<double> reference_ms;        // the ssaa reference's frame times (not a variant)
    std::vector<WorstFrame> worst;           // per variant and kind, in variant order
    std::vector<std::string> worst_files;    // every distinct file under worst/
    vk::CopyBandwidth copy_bandwidth;        // measured after the variants, for the resolve's bandwidth
    SceneLoad scene_load;
    std::string scorer = "cpu";  // where the quality frames were scored: device | cpu
    double cvvdp_fps = 0;        // the frame rate ColorVideoVDP took the scored frames at (0: one frame, an image)
    std::string scorer_note;     // why, when --scorer auto chose, or the device could not
    MemoryFigures memory;
    RunHealth health;  // warm-up, drift and the machine while frames were timed (run.json health)
};

}  // namespace cbr::harness
