// `cbrbench ab`: two builds, or two option sets, on one machine, in ABBA order, with runs
// added to both sides until every cell's time verdict settles or the budget is spent
// (method/timing.md, "A/B of two builds"; the rule: harness/figures/settle.h).
#pragma once

#include <string>
#include <vector>

#include "harness/base/exit_codes.h"

namespace cbr::harness {

struct AbOptions {
    std::string a_bin, b_bin;            // the cbrbench binary of each side ("": this one)
    std::string a_args, b_args;          // run arguments of one side only, split at spaces
    std::vector<std::string> run_args;   // run arguments of both sides (after --)
    std::string threshold = "3%";        // time change that counts
    double alpha = 0.05;                 // false-alarm rate over all looks and cells
    int repeat = 3;                      // --repeat of every run
    int max_runs = 12;                   // budget: runs per side (even: ABBA blocks)
    double max_seconds = 0;              // budget: seconds (0: none); no block starts past it
    std::string unit = "run";            // the sample: run or repetition (settle.h)
    double psnr_db = 0.1, ssim = 0.001;  // quality thresholds, as compare's
    std::string eci = "5%";
    std::string out;                     // "" -> out/ab-<date-time>
    std::string junit;                   // --junit FILE
    bool quiet = false;                  // no line per run on stdout
    bool no_stop = false;                // run the whole budget (calibrate --settle replays it); same verdicts
    std::vector<std::string> argv;       // the command line, for ab.json
};

// Checks everything (binaries, thresholds, budget, both sides' run arguments through
// `BIN plan`) before any output, then renders blocks A B B A into OUT/runs/{a,b}-NN, judges
// after each block and stops when settled or the budget is spent; writes OUT/ab.csv,
// ab.html, ab.json (and the --junit file). Returns a kAb* code; bad input prints one line
// and leaves no output directory.
int runAb(const AbOptions& o);

}  // namespace cbr::harness
