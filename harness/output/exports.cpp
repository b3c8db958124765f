// Exports of a run directory (exports.h): the formats, and run --export's files.
#include "harness/output/exports.h"

#include <stdexcept>

#include "harness/jobs/options.h"
#include "reports/csv.h"
#include "reports/gbench.h"
#include "reports/report_data.h"

namespace cbr::harness {

namespace fs = std::filesystem;

const char* const kExportFormats = "gbench (Google Benchmark JSON)";

std::string exportFileName(const std::string& format) { return format + ".json"; }

std::string exportText(const reports::RunData& d, const std::string& format) {
    if (format == "gbench") return reports::gbenchJson(d).dump(2) + "\n";
    throw std::invalid_argument("export: unknown format " + format);
}

std::vector<std::string> parseExportFormats(const std::string& list, const std::string& option) {
    std::vector<std::string> out;
    for (const auto& f : splitList(list)) {
        if (f != "gbench")
            throw std::invalid_argument(option + " '" + f + "': accepted: " + kExportFormats);
        out.push_back(f);
    }
    return out;
}

void writeExports(const fs::path& dir, const std::vector<std::string>& formats) {
    if (formats.empty()) return;
    reports::RunData d = reports::loadRun(dir);
    for (const auto& f : formats) reports::writeTextAtomically(dir / exportFileName(f), exportText(d, f));
}

}  // namespace cbr::harness
