// `cbrbench export RUN_DIR --format gbench [--out FILE]`: a finished run's results in another
// tool's format.
#pragma once

#include <string>

#include "harness/jobs/job_values.h"

namespace cbr::harness {

// Reads RUN_DIR, writes FILE (default RUN_DIR/gbench.json) whole or not at all, prints its
// path. Bad input throws std::invalid_argument (one line).
int runExport(const std::string& run_dir, ExportFormat format, const std::string& out_file);

}  // namespace cbr::harness
