// `cbrbench calibrate --settle` (calibrate_settle.cpp): the rates of self-settling verdicts.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/jobs/options.h"

namespace cbr::harness {

struct SettleCalibration {
    std::vector<std::string> argv;  // calibrate's command line: its run options go to every ab side
    std::string variants;           // calibrate's variant list, comma-separated
    int pairs = 0, slow_pairs = 0;
    std::vector<Slowdown> slowdowns;
    std::string threshold;          // as given ("3%")
    double threshold_fraction = 0;
    double alpha = 0.05;
    int max_runs = 8;               // ab's --max-runs
    int repeat = 3;                 // ab's --repeat: the smallest of --repeats
};

// Per pair one `cbrbench ab --no-stop` into DIR/settles/NAME (A/A, and B with each slowdown),
// replayed with unit run and unit repetition; writes DIR/calibrate_settle.csv (rates) and
// calibrate_settle_pairs.csv (every cell). Returns 0; a pair's ab failing throws.
int runSettleCalibration(const SettleCalibration& c, const std::filesystem::path& dir);

}  // namespace cbr::harness
