// The run's measurement health once its frames are timed: per configuration the drift
// against the same poses and the machine's load in its passes; for the run the machine's
// state and the one line that says a run was disturbed (docs/method/measurement.md).
#include <algorithm>
#include <cstdio>

#include "harness/run/run_internal.h"
#include "harness/figures/stats.h"

namespace cbr::harness {

namespace {

std::string healthFigure(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

void widen(std::optional<double>& lo, std::optional<double>& hi, const std::optional<double>& v) {
    if (!v) return;
    lo = std::min(lo.value_or(*v), *v);
    hi = std::max(hi.value_or(*v), *v);
}

bool inTimedPass(const std::vector<TimedWindow>& windows, double t) {
    for (const auto& w : windows)
        if (t >= w.t0 && t <= w.t1) return true;
    return false;
}

// The GPU over the timed passes: clocks, temperature, power, throttle reasons.
void gpuState(MachineHealth& m, const std::vector<MachineSample>& samples, const std::vector<TimedWindow>& windows,
              const HealthRule& rule) {
    std::vector<double> sm;
    uint64_t reasons = 0;
    for (const auto& s : samples) {
        if (!inTimedPass(windows, s.t)) continue;
        const GpuReading& g = s.gpu;
        if (g.sm_clock_mhz) sm.push_back(*g.sm_clock_mhz);
        std::optional<double> unused;
        widen(m.mem_mhz_min, m.mem_mhz_max, g.mem_clock_mhz);
        widen(unused, m.temperature_c_max, g.temperature_c);
        widen(unused, m.power_w_max, g.power_w);
        if (g.throttle_reasons) reasons |= *g.throttle_reasons;
    }
    m.sm_mhz_before = samples.front().gpu.sm_clock_mhz;
    m.sm_mhz_after = samples.back().gpu.sm_clock_mhz;
    if (!sm.empty()) {
        m.sm_mhz_min = *std::min_element(sm.begin(), sm.end());
        m.sm_mhz_max = *std::max_element(sm.begin(), sm.end());
        m.sm_mhz_median = median(sm);
        // Two readings in a row below the band: NVML's clock can lag a GPU that just woke
        // (one stale 345 MHz reading inside a 4K pass whose frames were already steady).
        const double floor = *m.sm_mhz_median * (1 - rule.clock_band);
        for (size_t i = 1; i < sm.size(); ++i) m.clock_left_band |= sm[i - 1] < floor && sm[i] < floor;
    }
    m.throttle_reasons = throttleReasonNames(reasons & ~uint64_t(1));  // gpu_idle: between passes, not a slowdown
    m.throttled = throttleSlowsDown(reasons);
}

void machineState(RunState& s, const std::vector<MachineSample>& samples, const HealthRule& rule) {
    RunHealth& h = s.results.health;
    MachineHealth& m = h.machine;
    m.cores = s.sampler.cores();
    m.samples = samples.size();
    m.interval_s = s.ctx.description.is_lavapipe ? 0.1 : 0.05;
    if (const Nvml* nvml = s.sampler.nvml()) {
        m.nvml = nvml->available();
        m.nvml_note = nvml->available() ? nvml->name() : nvml->reason();
        m.sm_mhz_max_rated = nvml->maxSmClockMhz();
    } else {
        m.nvml_note = "a CPU device: no GPU to ask";
    }
    m.timestamp_deviation_ns = vk::timestampDeviationNs(s.ctx);
    if (samples.empty() || h.windows.empty()) return;
    TimedWindow all{"", 0, h.windows.front().t0, h.windows.back().t1};
    const WindowLoad load = windowLoad(samples, all);
    m.own_cores = load.own_cores;
    m.other_cores = load.other_cores;
    m.steal_cores = load.steal_cores;
    m.own_share = load.own_cores / m.cores;
    m.cpu_mhz_before = samples.front().cpu_mhz;
    m.cpu_mhz_after = samples.back().cpu_mhz;
    for (const auto& x : samples)
        if (inTimedPass(h.windows, x.t)) widen(m.cpu_mhz_min, m.cpu_mhz_max, x.cpu_mhz);
    if (m.nvml) gpuState(m, samples, h.windows, rule);
}

// Per configuration: drift against the same poses, and (on a CPU device, where other
// processes take the renderer's cores) its passes timed on a busy machine.
void configHealth(RunState& s, const std::vector<MachineSample>& samples, const HealthRule& rule) {
    RunHealth& h = s.results.health;
    const bool cpu_device = s.ctx.description.is_lavapipe;
    for (size_t vi = 0; vi < s.results.variants.size(); ++vi) {
        VariantRun& vr = s.results.variants[vi];
        ConfigHealth& c = h.configs[vi];
        if (const VariantSamples* t = s.results.digest.find(vr.name)) c.drift = analyseDrift(t->ms, t->repeat, t->frame, rule);
        for (const auto& w : h.windows) {
            if (w.config != vr.name) continue;
            const WindowLoad wl = windowLoad(samples, w);
            const double other = wl.other_cores + wl.steal_cores;  // both take the renderer's cores
            c.max_other_cores = std::max(c.max_other_cores, other);
            if (cpu_device && other > rule.busy_other_cores && c.busy_repeat < 0) c.busy_repeat = w.repeat;
        }
        h.machine.other_cores_max = std::max(h.machine.other_cores_max, c.max_other_cores);
        std::vector<std::string> why;
        if (c.drift.unsteady) why.push_back(c.drift.note);
        if (c.busy_repeat >= 0)
            why.push_back("other processes used up to " + healthFigure("%.2f", c.max_other_cores) + " cores while it was timed (repetition " +
                          std::to_string(c.busy_repeat + 1) + " first)");
        c.unsteady = !why.empty();
        for (const auto& w : why) c.note += (c.note.empty() ? "" : "; ") + w;
        if (c.unsteady && vr.status == "ok" && h.status_gate) {
            vr.status = "unsteady";
            vr.note = c.note;
        }
    }
}

// The clauses of the end line: what disturbed the run, in a reader's order.
void disturbances(RunState& s) {
    RunHealth& h = s.results.health;
    const MachineHealth& m = h.machine;
    std::vector<std::string> names;
    for (size_t vi = 0; vi < h.configs.size(); ++vi)
        if (h.configs[vi].unsteady) names.push_back(s.results.variants[vi].name);
    for (const auto& c : h.configs) h.busy |= c.busy_repeat >= 0;
    if (h.busy)
        h.disturbances.push_back("the machine was busy: other processes used up to " + healthFigure("%.2f", m.other_cores_max) + " of " +
                                 std::to_string(m.cores) + " cores while frames were timed");
    if (m.throttled) {
        std::string r;
        for (const auto& n : m.throttle_reasons) r += (r.empty() ? "" : ", ") + n;
        h.disturbances.push_back("the GPU was throttled (" + r + ")");
    }
    if (m.clock_left_band && m.sm_mhz_min && m.sm_mhz_median)
        h.disturbances.push_back("the GPU's SM clock fell to " + healthFigure("%.0f", *m.sm_mhz_min) + " MHz (median " +
                                 healthFigure("%.0f", *m.sm_mhz_median) + ") while frames were timed");
    if (!names.empty()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        h.unsteady = true;
        h.disturbances.push_back(list + " unsteady (see their notes)" +
                                 (h.status_gate ? "" : "; statuses kept as ok: CBR_HEALTH_STATUS=off"));
    }
    for (const auto& d : h.disturbances) h.line += (h.line.empty() ? "measurement disturbed: " : "; ") + d;
}

}  // namespace

void assessHealth(RunState& s) {
    const HealthRule& rule = healthRule();
    s.results.health.status_gate = healthStatusGate();
    const std::vector<MachineSample> samples = s.sampler.samples();
    s.results.health.configs.resize(s.results.variants.size());
    machineState(s, samples, rule);
    configHealth(s, samples, rule);
    disturbances(s);
}

}  // namespace cbr::harness
