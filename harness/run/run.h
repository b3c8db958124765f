// `cbrbench run`: inputs checked up front, then variants interleaved over repetitions.
#pragma once

#include "harness/jobs/options.h"

namespace cbr::harness {

// Returns the process exit code. Bad input throws std::invalid_argument before any
// output exists; the caller prints it as one line and exits 2.
int runBenchmark(const RunOptions& options);

// Checks a run's options without loading its scene (settings, variants, sweep parameters,
// exports, the output directory; the scene and path named: a built-in or a file that is
// there, a path file parsed); throws std::invalid_argument for bad input. runBenchmark
// checks the rest (the scene's contents) when it loads it, before it writes anything.
void checkRunOptions(const RunOptions& options);

}  // namespace cbr::harness
