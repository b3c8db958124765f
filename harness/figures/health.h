// Measurement health (docs/method/measurement.md, "Measurement health"): whether a run's
// times can be trusted. Warm-up until the frame time is steady, drift and ramps in the
// timed frames against the same poses in the other repetitions, and the machine's state
// (other processes' CPU load, GPU clocks and throttling) while the frames were timed.
// Pure functions of the numbers: the sampler that gathers them is machine_sampler.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/base/nvml.h"

namespace cbr::harness {

// Every threshold in one place; docs/method/measurement.md gives the measurements they
// were chosen from.
struct HealthRule {
    // Warm-up: steady once the median of the last `warm_window` frame times is within
    // `warm_tolerance` of the median of the `warm_window` before; at most `warm_cap_frames`
    // frames or `warm_cap_seconds` of them beyond the minimum.
    int warm_window = 4;
    double warm_tolerance = 0.03;
    int warm_cap_frames = 120;
    double warm_cap_seconds = 3.0;
    // Drift: a repetition's median time against its poses' median over the repetitions
    // (the repetition level), and a span of frames (at least 3, a quarter of the path)
    // against the same poses in the others. Unsteady beyond the larger of the floor and
    // e^(k x noise) - 1, the noise being the frame-level residuals' robust spread.
    double level_floor = 0.02;
    double span_floor = 0.05;
    double level_noise_k = 3.0;
    double span_noise_k = 5.0;
    // The machine: other processes' CPU load in cores during a timed pass, on a CPU device
    // (lavapipe), beyond which the pass ran on a busy machine.
    double busy_other_cores = 0.30;
    // A GPU's SM clock during the timed frames more than this below its median: the clock
    // left its band.
    double clock_band = 0.10;
};
const HealthRule& healthRule();

// Whether an unsteady variant's status becomes `unsteady`: yes, unless the environment has
// CBR_HEALTH_STATUS=off, where health is measured and reported but every status stays as it
// ran (cbrbench's own tests, which ctest runs side by side on shared cores).
bool healthStatusGate();

// Warm-up: true once `times` (ms, in order) is steady under the rule.
bool warmUpSteady(const std::vector<double>& times, const HealthRule& rule = healthRule());

struct DriftFinding {
    int repeat = 0;                   // 0-based
    int first_frame = 0, last_frame = 0;  // the span; the whole path for a repetition level
    double ratio = 1;                 // its time against the same poses in the other repetitions
    bool whole_repetition = false;
};

struct DriftResult {
    bool tested = false;
    std::string why_not;               // e.g. "one repetition: no other repetition to pair poses with"
    double noise = 0;                  // robust spread of the log residuals (about a relative sd)
    std::vector<double> levels;        // per repetition: its median ratio to the pose medians
    std::optional<DriftFinding> worst; // the largest departure against its limit, judged or not
    double level_max = 0, span_max = 0;  // the largest |ratio - 1| of a repetition and of a span
    double level_limit = 0, span_limit = 0;  // the thresholds as applied
    bool unsteady = false;
    std::string note;                  // what drifted and by how much, when unsteady
};
// One configuration's timed frames, parallel: time (ms), repetition and frame of each (as
// VariantSamples keeps them), paired by pose across repetitions.
DriftResult analyseDrift(const std::vector<double>& ms, const std::vector<int>& repeat, const std::vector<int>& frame,
                         const HealthRule& rule = healthRule());

// A reading of the machine, `t` seconds after the sampler started.
struct MachineSample {
    double t = 0;
    double cpu_busy_s = 0, cpu_total_s = 0;  // the whole machine, cumulative (all cores), steal left out
    double cpu_steal_s = 0;                  // time the hypervisor ran other machines on these cores
    double own_cpu_s = 0;                    // this process, cumulative
    std::optional<double> cpu_mhz;           // mean over the cores, where the kernel says
    GpuReading gpu;
};

// A timed pass: one configuration's repetition, in the sampler's seconds.
struct TimedWindow {
    std::string config;
    int repeat = 0;
    double t0 = 0, t1 = 0;
};

struct WindowLoad {
    double own_cores = 0, other_cores = 0, steal_cores = 0;
    std::optional<double> sm_min_mhz, sm_max_mhz;
    bool slowdown = false;  // a throttle reason that slows a busy GPU
};
// The machine's load over [w.t0, w.t1], from the samples around it.
WindowLoad windowLoad(const std::vector<MachineSample>& samples, const TimedWindow& w);

}  // namespace cbr::harness

namespace cbr::harness {

// One configuration's health over the run.
struct ConfigHealth {
    std::vector<int> warm_up_frames;  // per repetition: untimed frames before its timed ones
    std::vector<bool> warm_up_capped; // per repetition: the cap was reached before the time was steady
    DriftResult drift;
    double max_other_cores = 0;       // other processes' load during its timed passes, at most
    int busy_repeat = -1;             // the first repetition timed on a busy machine (CPU device)
    bool unsteady = false;
    std::string note;
};

// The machine over the timed frames (run.json health.machine).
struct MachineHealth {
    int cores = 0;
    double own_cores = 0, other_cores = 0, other_cores_max = 0;  // over the timed passes
    double own_share = 0;                                        // own_cores / cores
    double steal_cores = 0;  // the hypervisor's other machines on these cores (/proc/stat steal)
    std::optional<double> cpu_mhz_before, cpu_mhz_min, cpu_mhz_max, cpu_mhz_after;
    bool nvml = false;
    std::string nvml_note;  // why not, or the GPU's NVML name
    std::optional<double> sm_mhz_before, sm_mhz_min, sm_mhz_median, sm_mhz_max, sm_mhz_after, sm_mhz_max_rated;
    std::optional<double> mem_mhz_min, mem_mhz_max, temperature_c_max, power_w_max;
    std::vector<std::string> throttle_reasons;  // seen during the timed passes
    bool throttled = false, clock_left_band = false;
    std::optional<double> timestamp_deviation_ns;  // VK_EXT_calibrated_timestamps
    size_t samples = 0;
    double interval_s = 0;
};

struct RunHealth {
    std::vector<ConfigHealth> configs;  // parallel to RunResults::variants
    std::vector<TimedWindow> windows;
    MachineHealth machine;
    bool busy = false, unsteady = false;
    bool status_gate = true;  // an unsteady variant's status becomes `unsteady` (healthStatusGate)
    std::vector<std::string> disturbances;  // each a clause of the line
    std::string line;                       // "" for a quiet run
};

}  // namespace cbr::harness
