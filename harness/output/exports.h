// A run's results in the formats other tools read (reports/gbench.h): written by
// `run --export gbench` as the run's last step, and by the export command (harness/export).
// The formats are typed where the command line is read (harness/jobs/job_values.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/jobs/job_values.h"
#include "reports/report_data.h"

namespace cbr::harness {

// The file a format is written to in a run directory (gbench -> gbench.json).
std::string exportFileName(ExportFormat format);

// One format's text from a loaded run.
std::string exportText(const reports::RunData& d, ExportFormat format);

// Writes DIR/<format's file> for each format from the run files in DIR (run's last step,
// before the output directory is committed).
void writeExports(const std::filesystem::path& dir, const std::vector<ExportFormat>& formats);

}  // namespace cbr::harness
