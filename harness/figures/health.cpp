// Warm-up steadiness, drift against the same poses, and the machine's load per timed pass.
#include "harness/figures/health.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "harness/figures/stats.h"

namespace cbr::harness {

const HealthRule& healthRule() {
    static const HealthRule rule;
    return rule;
}

bool healthStatusGate() {
    const char* v = std::getenv("CBR_HEALTH_STATUS");
    return !(v && std::string(v) == "off");
}

bool warmUpSteady(const std::vector<double>& times, const HealthRule& rule) {
    const size_t w = size_t(std::max(1, rule.warm_window));
    if (times.size() < 2 * w) return false;
    std::vector<double> last(times.end() - long(w), times.end()), before(times.end() - long(2 * w), times.end() - long(w));
    const double a = median(last), b = median(before);
    return b > 0 && std::abs(a / b - 1.0) <= rule.warm_tolerance;
}

namespace {

// 1.4826 * the median absolute deviation: the standard deviation of normal noise.
double robustSpread(const std::vector<double>& v) {
    if (v.size() < 2) return 0;
    const double m = median(v);
    std::vector<double> dev;
    dev.reserve(v.size());
    for (double x : v) dev.push_back(std::abs(x - m));
    return 1.4826 * median(dev);
}

// A drift as a change of time, "15.0% longer" or "12.0% shorter": written as a ratio
// ("1.15x") it would read as a second speed-up beside the paired one (reports/speedup.h).
std::string driftChangeText(double r) {
    char b[48];
    std::snprintf(b, sizeof b, "%.1f%% %s", std::abs(r - 1) * 100, r >= 1 ? "longer" : "shorter");
    return b;
}

std::string percentText(double fraction) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f%%", fraction * 100);
    return b;
}

// Per repetition, per frame: log(time / median of the same frame's time in the other
// repetitions). Frames only some repetitions have are left out.
std::map<int, std::map<int, double>> poseResiduals(const std::vector<double>& ms, const std::vector<int>& repeat,
                                                   const std::vector<int>& frame) {
    std::map<int, std::map<int, double>> by_frame;  // frame -> repeat -> ms
    for (size_t i = 0; i < ms.size() && i < repeat.size() && i < frame.size(); ++i)
        if (ms[i] > 0 && std::isfinite(ms[i])) by_frame[frame[i]][repeat[i]] = ms[i];
    std::map<int, std::map<int, double>> e;  // repeat -> frame -> residual
    std::vector<double> others;
    for (const auto& [f, reps] : by_frame) {
        if (reps.size() < 2) continue;
        for (const auto& [rep, t] : reps) {
            others.clear();
            for (const auto& [r2, t2] : reps)
                if (r2 != rep) others.push_back(t2);
            e[rep][f] = std::log(t / median(others));
        }
    }
    return e;
}

}  // namespace

DriftResult analyseDrift(const std::vector<double>& ms, const std::vector<int>& repeat, const std::vector<int>& frame,
                         const HealthRule& rule) {
    DriftResult out;
    const auto e = poseResiduals(ms, repeat, frame);
    if (e.size() < 2) {
        out.why_not = "fewer than 2 repetitions: no other repetition to pair its poses with";
        return out;
    }
    out.tested = true;
    std::vector<double> within;  // residuals about their repetition's level: the frame-level noise
    std::map<int, double> level;
    size_t frames = 0;
    for (const auto& [rep, fr] : e) {
        std::vector<double> v;
        for (const auto& [f, x] : fr) v.push_back(x);
        level[rep] = median(v);
        for (double x : v) within.push_back(x - level[rep]);
        frames = std::max(frames, v.size());
        out.levels.push_back(std::exp(level[rep]));
    }
    out.noise = robustSpread(within);
    out.level_limit = std::max(rule.level_floor, std::expm1(rule.level_noise_k * out.noise));
    out.span_limit = std::max(rule.span_floor, std::expm1(rule.span_noise_k * out.noise));
    // A quarter of the path: a burst shorter than half of it (a few frames of a lavapipe run
    // on a quiet machine) moves neither the span's median nor the variant's figures.
    const size_t span = std::max<size_t>(3, frames / 4);
    double worst_excess = -INFINITY;
    auto consider = [&](const DriftFinding& f, double limit) {
        (f.whole_repetition ? out.level_max : out.span_max) =
            std::max(f.whole_repetition ? out.level_max : out.span_max, std::abs(f.ratio - 1));
        const double excess = std::abs(std::log(f.ratio)) - std::log1p(limit);
        if (excess > worst_excess) worst_excess = excess, out.worst = f;
    };
    for (const auto& [rep, fr] : e) {
        consider({rep, fr.begin()->first, fr.rbegin()->first, std::exp(level[rep]), true}, out.level_limit);
        std::vector<std::pair<int, double>> seq(fr.begin(), fr.end());
        for (size_t j = 0; j + span <= seq.size(); ++j) {
            std::vector<double> v;
            for (size_t k = j; k < j + span; ++k) v.push_back(seq[k].second);
            consider({rep, seq[j].first, seq[j + span - 1].first, std::exp(median(v)), false}, out.span_limit);
        }
    }
    if (worst_excess > 0 && out.worst) {
        const DriftFinding& f = *out.worst;
        out.unsteady = true;
        const std::string where = f.whole_repetition ? "repetition " + std::to_string(f.repeat + 1) + " of " + std::to_string(e.size())
                                                     : "frames " + std::to_string(f.first_frame) + "-" + std::to_string(f.last_frame) +
                                                           " of repetition " + std::to_string(f.repeat + 1);
        out.note = where + " took " + driftChangeText(f.ratio) + " than the same poses in the other repetitions (steady within " +
                   percentText(f.whole_repetition ? out.level_limit : out.span_limit) + ")";
    }
    return out;
}

WindowLoad windowLoad(const std::vector<MachineSample>& samples, const TimedWindow& w) {
    WindowLoad load;
    if (samples.size() < 2) return load;
    size_t a = 0, b = samples.size() - 1;
    for (size_t i = 0; i < samples.size(); ++i) {
        if (samples[i].t <= w.t0) a = i;
        if (samples[i].t >= w.t1) {
            b = i;
            break;
        }
    }
    if (b <= a) b = std::min(a + 1, samples.size() - 1);
    const double dt = samples[b].t - samples[a].t;
    if (dt > 0) {
        load.own_cores = (samples[b].own_cpu_s - samples[a].own_cpu_s) / dt;
        const double busy = (samples[b].cpu_busy_s - samples[a].cpu_busy_s) / dt;
        load.other_cores = std::max(0.0, busy - load.own_cores);
        load.steal_cores = std::max(0.0, (samples[b].cpu_steal_s - samples[a].cpu_steal_s) / dt);
    }
    for (size_t i = a; i <= b; ++i) {
        const GpuReading& g = samples[i].gpu;
        const bool inside = samples[i].t >= w.t0 && samples[i].t <= w.t1;
        if (!inside && !(i == a && b == a + 1)) continue;
        if (g.sm_clock_mhz) {
            load.sm_min_mhz = std::min(load.sm_min_mhz.value_or(INFINITY), *g.sm_clock_mhz);
            load.sm_max_mhz = std::max(load.sm_max_mhz.value_or(0.0), *g.sm_clock_mhz);
        }
        if (g.throttle_reasons && throttleSlowsDown(*g.throttle_reasons)) load.slowdown = true;
    }
    return load;
}

}  // namespace cbr::harness
