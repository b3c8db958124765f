// Exports of a run directory (harness/export.h).
#include "harness/core/exports.h"

#include <cstdio>
#include <stdexcept>

#include "harness/core/options.h"
#include "reports/csv.h"
#include "reports/gbench.h"
#include "reports/report_data.h"

namespace cbr::harness {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormats = "gbench (Google Benchmark JSON)";

std::string fileName(const std::string& format) { return format + ".json"; }

std::string exportText(const reports::RunData& d, const std::string& format) {
    if (format == "gbench") return reports::gbenchJson(d).dump(2) + "\n";
    throw std::invalid_argument("export: unknown format " + format);
}

}  // namespace

std::vector<std::string> parseExportFormats(const std::string& list, const std::string& option) {
    std::vector<std::string> out;
    for (const auto& f : splitList(list)) {
        if (f != "gbench")
            throw std::invalid_argument(option + " '" + f + "': accepted: " + kFormats);
        out.push_back(f);
    }
    return out;
}

void writeExports(const fs::path& dir, const std::vector<std::string>& formats) {
    if (formats.empty()) return;
    reports::RunData d = reports::loadRun(dir);
    for (const auto& f : formats) reports::writeTextAtomically(dir / fileName(f), exportText(d, f));
}

int runExport(const std::string& run_dir, const std::string& format, const std::string& out_file) {
    auto formats = parseExportFormats(format, "export --format");
    if (formats.size() != 1) throw std::invalid_argument("export --format: give one format; accepted: " + std::string(kFormats));
    if (!fs::is_directory(run_dir))
        throw std::invalid_argument("export " + run_dir + ": not a directory; expected a run's output directory");
    fs::path out = out_file.empty() ? fs::path(run_dir) / fileName(formats[0]) : fs::path(out_file);
    fs::path parent = fs::absolute(out).parent_path();
    if (!fs::is_directory(parent) || fs::is_directory(out))
        throw std::invalid_argument("export --out " + out.string() + ": accepted: a file path in an existing directory");
    reports::RunData d;
    try {
        d = reports::loadRun(run_dir);
    } catch (const nlohmann::json::exception& e) {
        throw std::invalid_argument("export " + (fs::path(run_dir) / "run.json").string() + ": " + e.what());
    }
    reports::writeTextAtomically(out, exportText(d, formats[0]));
    std::printf("export: %s\n", out.c_str());
    return 0;
}

}  // namespace cbr::harness
