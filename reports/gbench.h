// A run as Google Benchmark's JSON, the format benchmark dashboards and Google Benchmark's
// own tools/compare.py read (github-action-benchmark, Bencher, compare.py).
#pragma once

#include <nlohmann/json.hpp>

#include "reports/report_data.h"

namespace cbr::reports {

// `context`: date, host, the device and driver, the tool's version and commit, time units.
// `benchmarks`: per configuration (variant, with the run's scene, path, pipeline, resolution
// and swept settings in its name) one `iteration` entry per repetition (real_time and
// cpu_time: the mean GPU frame time of that repetition in ms, iterations: its frames) and
// the mean, median, stddev and cv aggregates over the repetitions, Google Benchmark's
// aggregate definitions. Quality (psnr_db, ssim, flip, eci, and cvvdp_jod: ColorVideoVDP's
// JOD, higher is better, where the run scored it, reports/jod.h) and the paired speed-up with
// its interval (speedup_vs_full, speedup_ci_low, speedup_ci_high: summary.csv's numbers,
// reports/speedup.h) are user counters of every entry. Failed or skipped configurations are left out.
nlohmann::json gbenchJson(const RunData& d);

}  // namespace cbr::reports
