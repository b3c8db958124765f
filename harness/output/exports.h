// A run's results in the formats other tools read (reports/gbench.h): written by
// `run --export gbench` as the run's last step, and by the export command (harness/export).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "reports/report_data.h"

namespace cbr::harness {

// What --export and --format accept, for messages: "gbench (Google Benchmark JSON)".
extern const char* const kExportFormats;

// The file a format is written to in a run directory (gbench -> gbench.json).
std::string exportFileName(const std::string& format);

// One format's text from a loaded run.
std::string exportText(const reports::RunData& d, const std::string& format);

// The accepted --export / --format names, checked; throws std::invalid_argument with one
// line naming the option, the value and what is accepted. "" gives an empty list.
std::vector<std::string> parseExportFormats(const std::string& list, const std::string& option);

// Writes DIR/<format's file> for each format from the run files in DIR (run's last step,
// before the output directory is committed).
void writeExports(const std::filesystem::path& dir, const std::vector<std::string>& formats);

}  // namespace cbr::harness
