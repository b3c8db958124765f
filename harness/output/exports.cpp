// Exports of a run directory (exports.h): each format's file and text, and run --export's files.
#include "harness/output/exports.h"

#include <stdexcept>

#include "reports/csv.h"
#include "reports/gbench.h"
#include "reports/report_data.h"

namespace cbr::harness {

namespace fs = std::filesystem;

std::string exportFileName(ExportFormat format) { return std::string(exportWord(format)) + ".json"; }

std::string exportText(const reports::RunData& d, ExportFormat format) {
    switch (format) {
    case ExportFormat::Gbench: return reports::gbenchJson(d).dump(2) + "\n";
    }
    throw std::logic_error("export: a format without a writer");
}

void writeExports(const fs::path& dir, const std::vector<ExportFormat>& formats) {
    if (formats.empty()) return;
    reports::RunData d = reports::loadRun(dir);
    for (const auto f : formats) reports::writeTextAtomically(dir / exportFileName(f), exportText(d, f));
}

}  // namespace cbr::harness
