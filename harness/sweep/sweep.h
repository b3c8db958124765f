// `cbrbench sweep`: the run's configurations over swept settings (harness/jobs/sweep_configs.h),
// and the outer dimensions (several paths, reference kinds) that each get a run of their own.
#pragma once

#include <string>
#include <vector>

#include "harness/jobs/options.h"

namespace cbr::harness {

// `options.control.sweep` set, `options.path` the first of `paths` (--path's list): one run
// when nothing outer is swept, else one run per combination into OUT/<dir>/ with
// OUT/sweep.csv and the index sweep.html; every input is checked before the first renders
// and OUT appears whole or not at all. Returns the exit code.
int runSweep(const RunOptions& options, const std::vector<std::string>& paths);

}  // namespace cbr::harness
