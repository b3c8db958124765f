// Google Benchmark JSON of a run directory (reports/gbench.h).
#include "reports/gbench.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace cbr::reports {

namespace {

std::string text(const nlohmann::json& run, const std::string& pointer) {
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
    c["date"] = text(r, "/date");
    c["host_name"] = text(r, "/host/name");
    c["executable"] = "cbrbench";
    const nlohmann::json* cpus = jsonAt(r, "/host/cpus");
    c["num_cpus"] = cpus && cpus->is_number() ? cpus->get<int>() : 0;
    c["mhz_per_cpu"] = 0;
    c["cpu_scaling_enabled"] = false;
    c["caches"] = nlohmann::json::array();
    c["library_build_type"] = "release";
    // cbrbench's own context: what the times were measured on.
    c["device"] = text(r, "/device/name");
    c["driver"] = text(r, "/device/driver_name") + " " + text(r, "/device/driver_info");
    c["driver_version"] = text(r, "/device/driver_version");
    c["vulkan_api_version"] = text(r, "/device/api_version");
    c["cbrbench_version"] = text(r, "/tool/version");
    c["cbrbench_commit"] = text(r, "/tool/commit");
    c["time_source"] = "GPU timestamps, ms per frame (an iteration is one frame)";
    return c;
}


}  // namespace

nlohmann::json gbenchJson(const RunData& d) {
    const auto& r = d.run;
    std::string prefix = text(r, "/scene/name") + "/" + text(r, "/path/name") + "/" + text(r, "/settings/pipeline") +
                         "/" + text(r, "/settings/width") + "x" + text(r, "/settings/height") + "/";
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
        for (auto [counter, column] : {std::pair{"psnr_db", "psnr_db_mean"}, {"ssim", "ssim_mean"}, {"flip", "flip_mean"},
                                       {"cvvdp_jod", kJodColumn}, {"eci", "eci"}, {"speedup_vs_full", "speedup_vs_full"},
                                       {"speedup_ci_low", "speedup_ci_low"}, {"speedup_ci_high", "speedup_ci_high"}}) {
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
