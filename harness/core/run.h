// `cbrbench run`: inputs checked up front, then variants interleaved over repetitions.
#pragma once

#include "harness/core/options.h"

namespace cbr::harness {

// Returns the process exit code. Bad input throws std::invalid_argument before any
// output exists; the caller prints it as one line and exits 2.
int runBenchmark(const RunOptions& options);

// Checks a run's options and inputs (scene, path, settings) as runBenchmark does before
// it writes anything; throws std::invalid_argument for bad input.
void checkRunOptions(const RunOptions& options);

}  // namespace cbr::harness
