// Google Benchmark JSON of a run directory (reports/gbench.h).
#include "reports/gbench.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace cbr::reports {

namespace {

namespace rj = run_json;

// run.json's value at the schema's keys as text ("" where absent).
template <typename... Keys>
std::string text(const nlohmann::json& run, const Keys&... keys) {
    const std::string pointer = rundir::pointer(keys...);
    const nlohmann::json* j = jsonAt(run, pointer);
    if (!j || j->is_null()) return "";
    return j->is_string() ? j->get<std::string>() : j->dump();
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Sample standard deviation (n - 1), as Google Benchmark's stddev aggregate; 0 for one value.
double stddev(const std::vector<double>& v) {
    if (v.size() < 2) return 0;
    double m = mean(v), s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / double(v.size() - 1));
}

nlohmann::json context(const RunData& d) {
    const auto& r = d.run;
    nlohmann::json c;
    c["date"] = text(r, rj::kDate);
    c["host_name"] = text(r, rj::kHost, rj::host::kName);
    c["executable"] = "cbrbench";
    const nlohmann::json* cpus = jsonAt(r, rundir::pointer(rj::kHost, rj::host::kCpus));
    c["num_cpus"] = cpus && cpus->is_number() ? cpus->get<int>() : 0;
    c["mhz_per_cpu"] = 0;
    c["cpu_scaling_enabled"] = false;
    c["caches"] = nlohmann::json::array();
    c["library_build_type"] = "release";
    // cbrbench's own context: what the times were measured on.
    c["device"] = text(r, rj::kDevice, rj::device::kName);
    c["driver"] = text(r, rj::kDevice, rj::device::kDriverName) + " " + text(r, rj::kDevice, rj::device::kDriverInfo);
    c["driver_version"] = text(r, rj::kDevice, rj::device::kDriverVersion);
    c["vulkan_api_version"] = text(r, rj::kDevice, rj::device::kApiVersion);
    c["cbrbench_version"] = text(r, rj::kTool, rj::tool::kVersion);
    c["cbrbench_commit"] = text(r, rj::kTool, rj::tool::kCommit);
    c["time_source"] = "GPU timestamps, ms per frame (an iteration is one frame)";
    return c;
}


}  // namespace

nlohmann::json gbenchJson(const RunData& d) {
    const auto& r = d.run;
    namespace ks = rj::settings;
    std::string prefix = text(r, rj::kScene, rj::scene::kName) + "/" + text(r, rj::kPath, rj::path::kName) + "/" +
                         text(r, rj::kSettings, ks::kPipeline) + "/" + text(r, rj::kSettings, ks::kWidth) + "x" +
                         text(r, rj::kSettings, ks::kHeight) + "/";
    nlohmann::json out;
    out["context"] = context(d);
    out["benchmarks"] = nlohmann::json::array();
    int family = 0;
    for (const auto& v : d.variants) {
        if (!variantOk(d, v)) continue;
        auto reps = gpuMsByRepetition(d, v);
        if (reps.empty()) continue;
        const std::string name = prefix + v;
        nlohmann::json counters = nlohmann::json::object();
        // The user counters: summary.csv's figures, the speed-up and JOD under summary.csv's names.
        using namespace summary_csv;
        for (auto [counter, column] : {std::pair{"psnr_db", kPsnrDbMean}, {"ssim", kSsimMean}, {"flip", kFlipMean},
                                       {kCvvdpJod, kCvvdpJod}, {kEci, kEci}, {kSpeedup, kSpeedup},
                                       {kSpeedupLow, kSpeedupLow}, {kSpeedupHigh, kSpeedupHigh}}) {
            auto x = summaryNum(d, v, column);
            // PSNR inf (full) has no JSON number; runs without ColorVideoVDP have no cvvdp_jod.
            if (x && std::isfinite(*x)) counters[counter] = *x;
        }
        auto entry = [&](double ms) {
            nlohmann::json b = {{"name", name},           {"family_index", family}, {"per_family_instance_index", 0},
                                {"run_name", name},       {"threads", 1},           {"repetitions", int(reps.size())},
                                {"real_time", ms},        {"cpu_time", ms},         {"time_unit", "ms"}};
            b.update(counters);
            return b;
        };
        std::vector<double> means;
        for (const auto& [rep, ms] : reps) {
            nlohmann::json b = entry(mean(ms));
            b["run_type"] = "iteration";
            b["repetition_index"] = rep;
            b["iterations"] = int(ms.size());
            out["benchmarks"].push_back(b);
            means.push_back(mean(ms));
        }
        const double m = mean(means), sd = stddev(means);
        for (auto [agg, value, unit] : {std::tuple{"mean", m, "time"}, {"median", median(means), "time"},
                                        {"stddev", sd, "time"}, {"cv", m > 0 ? sd / m : 0.0, "percentage"}}) {
            nlohmann::json b = entry(value);
            b["name"] = name + "_" + agg;
            b["run_type"] = "aggregate";
            b["aggregate_name"] = agg;
            b["aggregate_unit"] = unit;
            b["iterations"] = int(means.size());
            out["benchmarks"].push_back(b);
        }
        ++family;
    }
    return out;
}

}  // namespace cbr::reports
