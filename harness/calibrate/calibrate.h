// `cbrbench calibrate`: the false-alarm and detection rates of `compare`'s time verdicts,
// measured on the device at hand (method/timing.md: measured, not assumed).
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/options.h"

namespace cbr::harness {

struct CalibrateOptions {
    RunOptions run;                       // scene, path, resolution, frames, variants (default full), device
    int pairs = 20;                       // A/A pairs: two runs of the same settings
    int slow_pairs = 10;                  // pairs per injected slowdown
    std::string slowdowns = "opaque=10";  // PASS=PCT[,PCT...]: injected with --debug-slowdown
    std::string repeats = "3,5,10";       // repetition counts judged (each pair runs the largest)
    std::string threshold = "3%";
    double alpha = 0.05;
    std::string out;                      // "" -> out/calibrate-<scene>-<path>-<date-time>
    std::string from;                     // an earlier calibration's directory: judge its runs again
    bool settle = false;                  // pairs through `cbrbench ab` (calibrate_settle.h), not single runs
    int max_runs = 8;                     // --settle: ab's budget, runs per side
};

// Runs, in time order per pair i: baseline i, its A/A twin, then one run per injected
// slowdown (all sharing baseline i), each with the largest repetition count; judges every
// pair at every count from the runs' first repetitions with `compare`'s rule; writes
// calibrate.csv (rates with Wilson 95% intervals), calibrate_pairs.csv (every verdict) and
// calibrate.json (provenance) into the output directory. Returns the exit code; bad input
// throws std::invalid_argument before anything is written.
int runCalibrate(const CalibrateOptions& o);

}  // namespace cbr::harness
