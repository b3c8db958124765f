// run.json `health`: warm-up, drift and the machine while frames were timed, with the
// thresholds they were judged by (docs/reference/outputs.md lists the keys).
#include <cmath>

#include "harness/output/outputs_internal.h"

namespace cbr::harness {

namespace {

using json = nlohmann::json;

json optionalNumber(const std::optional<double>& v) {
    if (!v || !std::isfinite(*v)) return nullptr;
    return *v;
}

json ruleJson(const HealthRule& r) {
    return {{"warm_up_window", r.warm_window},          {"warm_up_tolerance", r.warm_tolerance},
            {"warm_up_cap_frames", r.warm_cap_frames},  {"warm_up_cap_seconds", r.warm_cap_seconds},
            {"drift_level_floor", r.level_floor},       {"drift_span_floor", r.span_floor},
            {"drift_level_noise_k", r.level_noise_k}, {"drift_span_noise_k", r.span_noise_k},         {"busy_other_cores", r.busy_other_cores},
            {"clock_band", r.clock_band}};
}

json driftJson(const DriftResult& d) {
    // Every key always, null where not tested (one repetition), so the schema is one.
    json j = {{"tested", d.tested}, {"unsteady", d.unsteady}, {"why_not", d.tested ? json(nullptr) : json(d.why_not)},
              {"noise", nullptr}, {"repetition_ratios", json::array()}, {"level_limit", nullptr},
              {"span_limit", nullptr}, {"level_max", nullptr}, {"span_max", nullptr},
              {"largest", {{"repetition", nullptr}, {"first_frame", nullptr}, {"last_frame", nullptr}, {"ratio", nullptr},
                           {"whole_repetition", nullptr}}}};
    if (!d.tested) return j;
    j["noise"] = d.noise;
    j["repetition_ratios"] = d.levels;
    j["level_limit"] = d.level_limit;
    j["span_limit"] = d.span_limit;
    j["level_max"] = d.level_max;
    j["span_max"] = d.span_max;
    if (d.worst)
        j["largest"] = {{"repetition", d.worst->repeat}, {"first_frame", d.worst->first_frame},
                        {"last_frame", d.worst->last_frame}, {"ratio", d.worst->ratio},
                        {"whole_repetition", d.worst->whole_repetition}};
    return j;
}

json machineJson(const MachineHealth& m) {
    json cpu = {{"cores", m.cores},
                {"own_cores", m.own_cores},
                {"own_share", m.own_share},
                {"other_cores", m.other_cores},
                {"other_cores_max", m.other_cores_max},
                {"steal_cores", m.steal_cores},
                {"mhz_before", optionalNumber(m.cpu_mhz_before)},
                {"mhz_min", optionalNumber(m.cpu_mhz_min)},
                {"mhz_max", optionalNumber(m.cpu_mhz_max)},
                {"mhz_after", optionalNumber(m.cpu_mhz_after)}};
    // Every key always, null without NVML.
    json gpu = {{"nvml", m.nvml},
                {"note", m.nvml_note},
                {"sm_mhz",
                 {{"before", optionalNumber(m.sm_mhz_before)},
                  {"min", optionalNumber(m.sm_mhz_min)},
                  {"median", optionalNumber(m.sm_mhz_median)},
                  {"max", optionalNumber(m.sm_mhz_max)},
                  {"after", optionalNumber(m.sm_mhz_after)},
                  {"max_rated", optionalNumber(m.sm_mhz_max_rated)}}},
                {"mem_mhz", {{"min", optionalNumber(m.mem_mhz_min)}, {"max", optionalNumber(m.mem_mhz_max)}}},
                {"temperature_c_max", optionalNumber(m.temperature_c_max)},
                {"power_w_max", optionalNumber(m.power_w_max)},
                {"throttle_reasons", m.throttle_reasons},
                {"throttled", m.throttled},
                {"clock_left_band", m.clock_left_band}};
    return {{"cpu", cpu},
            {"gpu", gpu},
            {"timestamp_deviation_ns", optionalNumber(m.timestamp_deviation_ns)},
            {"samples", m.samples},
            {"sample_interval_s", m.interval_s}};
}

}  // namespace

json healthJson(const RunResults& r) {
    const RunHealth& h = r.health;
    json configs = json::array();  // in run order, as run.json variants (a sweep's labels hold '=')
    for (size_t i = 0; i < h.configs.size() && i < r.variants.size(); ++i) {
        const ConfigHealth& c = h.configs[i];
        std::vector<bool> capped(c.warm_up_capped.begin(), c.warm_up_capped.end());
        configs.push_back({{"name", r.variants[i].name},
                                       {"warm_up_frames", c.warm_up_frames},
                                       {"warm_up_capped", capped},
                                       {"drift", driftJson(c.drift)},
                                       {"other_cores_max", c.max_other_cores},
                                       {"unsteady", c.unsteady},
                                       {"note", c.note}});
    }
    return {{"quiet", h.line.empty()},
            {"busy", h.busy},
            {"unsteady", h.unsteady},
            {"status_gate", h.status_gate},
            {"line", h.line},
            {"disturbances", h.disturbances},
            {"variants", configs},
            {"machine", machineJson(h.machine)},
            {"rule", ruleJson(healthRule())}};
}

}  // namespace cbr::harness
