// The HTML report of one run directory: one self-contained file, readable offline.
#pragma once

#include <filesystem>
#include <string>

namespace cbr::reports {

// Reads summary.csv, frames.csv, run.json (and worst/ or frames/ images when present)
// from `run_dir` and writes run_dir/report.html through a temporary name and a rename.
// Bad input (a missing file, a malformed CSV row or cell, malformed JSON) throws
// std::invalid_argument with one line naming the file, the line or JSON part, and what
// is accepted; report.html is then left as it was.
void writeReport(const std::filesystem::path& run_dir);

// The report's HTML without writing it (same errors as writeReport).
std::string reportHtml(const std::filesystem::path& run_dir);

}  // namespace cbr::reports
