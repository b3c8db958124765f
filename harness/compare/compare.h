// `cbrbench compare`: regression verdicts between two run directories (method/timing.md).
#pragma once

#include <string>

#include "harness/base/exit_codes.h"
#include "reports/jod.h"

namespace cbr::harness {

struct CompareOptions {
    std::string baseline_dir;
    std::string current_dir;
    std::string threshold = "3%";  // time change that counts, relative ("3%" or 0.03)
    double alpha = 0.05;           // false discovery rate across cells (Benjamini-Hochberg)
    double psnr_db = 0.1;          // PSNR change that counts, dB
    double ssim = 0.001;           // SSIM change that counts, absolute
    std::string eci = "5%";        // ECI change that counts, relative to the baseline
    double jod = reports::kJodThreshold;  // ColorVideoVDP JOD change that counts, absolute (higher is better)
    bool strict = false;           // UNKNOWN cells make the exit code 2
    std::string junit;             // --junit FILE: the verdicts as JUnit XML (empty: none)
};

// Reads both directories, writes CURRENT_DIR/compare.csv and compare.html (and the
// --junit file: one testcase per cell, SLOWER and WORSE verdicts as failures, UNKNOWN and
// unmatched cells skipped) only after every input parsed, prints a short table. Returns one of the kCompare* codes (exit_codes.h); bad
// input prints one line on stderr and writes nothing.
int runCompare(const CompareOptions& o);

}  // namespace cbr::harness
