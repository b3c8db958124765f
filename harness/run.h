// `cbrbench run`: inputs checked up front, then variants interleaved over repetitions.
#pragma once

#include "harness/options.h"

namespace cbr::harness {

// Returns the process exit code. Bad input throws std::invalid_argument before any
// output exists; the caller prints it as one line and exits 2.
int runBenchmark(const RunOptions& options);

}  // namespace cbr::harness
