// run.json `health`: warm-up, drift and the machine while frames were timed, with the
// thresholds they were judged by (docs/reference/outputs.md lists the keys).
#include <cmath>

#include "harness/output/outputs_internal.h"
#include "rundir/run_json_health.h"

namespace cbr::harness {

namespace {

using json = nlohmann::json;

json optionalNumber(const std::optional<double>& v) {
    if (!v || !std::isfinite(*v)) return nullptr;
    return *v;
}

json ruleJson(const HealthRule& r) {
    namespace k = rundir::run::health::rule;
    return {{k::kWarmUpWindow, r.warm_window},         {k::kWarmUpTolerance, r.warm_tolerance},
            {k::kWarmUpCapFrames, r.warm_cap_frames},  {k::kWarmUpCapSeconds, r.warm_cap_seconds},
            {k::kDriftLevelFloor, r.level_floor},      {k::kDriftSpanFloor, r.span_floor},
            {k::kDriftLevelNoiseK, r.level_noise_k},   {k::kDriftSpanNoiseK, r.span_noise_k},
            {k::kBusyOtherCores, r.busy_other_cores},  {k::kClockBand, r.clock_band}};
}

json largestJson(const std::optional<DriftFinding>& worst) {
    namespace k = rundir::run::health::drift::largest;
    if (!worst)
        return {{k::kRepetition, nullptr}, {k::kFirstFrame, nullptr}, {k::kLastFrame, nullptr}, {k::kRatio, nullptr},
                {k::kWholeRepetition, nullptr}};
    return {{k::kRepetition, worst->repeat}, {k::kFirstFrame, worst->first_frame}, {k::kLastFrame, worst->last_frame},
            {k::kRatio, worst->ratio}, {k::kWholeRepetition, worst->whole_repetition}};
}

json driftJson(const DriftResult& d) {
    namespace k = rundir::run::health::drift;
    // Every key always, null where not tested (one repetition), so the schema is one.
    json j = {{k::kTested, d.tested}, {k::kUnsteady, d.unsteady},
              {k::kWhyNot, d.tested ? json(nullptr) : json(d.why_not)}, {k::kNoise, nullptr},
              {k::kRepetitionRatios, json::array()}, {k::kLevelLimit, nullptr}, {k::kSpanLimit, nullptr},
              {k::kLevelMax, nullptr}, {k::kSpanMax, nullptr}, {k::kLargest, largestJson(std::nullopt)}};
    if (!d.tested) return j;
    j[k::kNoise] = d.noise;
    j[k::kRepetitionRatios] = d.levels;
    j[k::kLevelLimit] = d.level_limit;
    j[k::kSpanLimit] = d.span_limit;
    j[k::kLevelMax] = d.level_max;
    j[k::kSpanMax] = d.span_max;
    if (d.worst) j[k::kLargest] = largestJson(d.worst);
    return j;
}

json machineJson(const MachineHealth& m) {
    namespace k = rundir::run::health::machine;
    namespace c = k::cpu;
    json cpu = {{c::kCores, m.cores},
                {c::kOwnCores, m.own_cores},
                {c::kOwnShare, m.own_share},
                {c::kOtherCores, m.other_cores},
                {c::kOtherCoresMax, m.other_cores_max},
                {c::kStealCores, m.steal_cores},
                {c::kMhzBefore, optionalNumber(m.cpu_mhz_before)},
                {c::kMhzMin, optionalNumber(m.cpu_mhz_min)},
                {c::kMhzMax, optionalNumber(m.cpu_mhz_max)},
                {c::kMhzAfter, optionalNumber(m.cpu_mhz_after)}};
    // Every key always, null without NVML.
    namespace g = k::gpu;
    namespace clk = g::clock;
    json gpu = {{g::kNvml, m.nvml},
                {g::kNote, m.nvml_note},
                {g::kSmMhz,
                 {{clk::kBefore, optionalNumber(m.sm_mhz_before)},
                  {clk::kMin, optionalNumber(m.sm_mhz_min)},
                  {clk::kMedian, optionalNumber(m.sm_mhz_median)},
                  {clk::kMax, optionalNumber(m.sm_mhz_max)},
                  {clk::kAfter, optionalNumber(m.sm_mhz_after)},
                  {clk::kMaxRated, optionalNumber(m.sm_mhz_max_rated)}}},
                {g::kMemMhz, {{clk::kMin, optionalNumber(m.mem_mhz_min)}, {clk::kMax, optionalNumber(m.mem_mhz_max)}}},
                {g::kTemperatureCMax, optionalNumber(m.temperature_c_max)},
                {g::kPowerWMax, optionalNumber(m.power_w_max)},
                {g::kThrottleReasons, m.throttle_reasons},
                {g::kThrottled, m.throttled},
                {g::kClockLeftBand, m.clock_left_band}};
    return {{k::kCpu, cpu},
            {k::kGpu, gpu},
            {k::kTimestampDeviationNs, optionalNumber(m.timestamp_deviation_ns)},
            {k::kSamples, m.samples},
            {k::kSampleIntervalS, m.interval_s}};
}

}  // namespace

json healthJson(const RunResults& r) {
    namespace k = rundir::run::health;
    namespace kv = k::variant;
    const RunHealth& h = r.health;
    json configs = json::array();  // in run order, as run.json variants (a sweep's labels hold '=')
    for (size_t i = 0; i < h.configs.size() && i < r.variants.size(); ++i) {
        const ConfigHealth& c = h.configs[i];
        std::vector<bool> capped(c.warm_up_capped.begin(), c.warm_up_capped.end());
        configs.push_back({{kv::kName, r.variants[i].name},
                           {kv::kWarmUpFrames, c.warm_up_frames},
                           {kv::kWarmUpCapped, capped},
                           {kv::kDrift, driftJson(c.drift)},
                           {kv::kOtherCoresMax, c.max_other_cores},
                           {kv::kUnsteady, c.unsteady},
                           {kv::kNote, c.note}});
    }
    return {{k::kQuiet, h.line.empty()},
            {k::kBusy, h.busy},
            {k::kUnsteady, h.unsteady},
            {k::kStatusGate, h.status_gate},
            {k::kLine, h.line},
            {k::kDisturbances, h.disturbances},
            {k::kVariants, configs},
            {k::kMachine, machineJson(h.machine)},
            {k::kRule, ruleJson(healthRule())}};
}

}  // namespace cbr::harness
