// `cbrbench export RUN_DIR --format gbench [--out FILE]` and `run --export gbench`: a run's
// results in the formats other tools read (reports/gbench.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cbr::harness {

// The accepted --export / --format names, checked; throws std::invalid_argument with one
// line naming the option, the value and what is accepted. "" gives an empty list.
std::vector<std::string> parseExportFormats(const std::string& list, const std::string& option);

// Writes DIR/<format's file> for each format from the run files in DIR (run's last step,
// before the output directory is committed).
void writeExports(const std::filesystem::path& dir, const std::vector<std::string>& formats);

// The export command: reads RUN_DIR, writes FILE (default RUN_DIR/gbench.json) whole or not
// at all, prints its path. Bad input throws std::invalid_argument (one line).
int runExport(const std::string& run_dir, const std::string& format, const std::string& out_file);

}  // namespace cbr::harness
