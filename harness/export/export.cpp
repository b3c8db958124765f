// `cbrbench export RUN_DIR --format gbench [--out FILE]`: a finished run's results in another
// tool's format (the formats are the core's, harness/output/exports.h, which run --export uses).
#include "harness/export/export.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "harness/base/exit_codes.h"
#include "harness/output/exports.h"
#include "reports/csv.h"
#include "reports/report_data.h"
#include "rundir/files.h"

namespace cbr::harness {

namespace fs = std::filesystem;

int runExport(const std::string& run_dir, ExportFormat format, const std::string& out_file) {
    if (!fs::is_directory(run_dir))
        throw std::invalid_argument("export " + run_dir + ": not a directory; expected a run's output directory");
    fs::path out = out_file.empty() ? fs::path(run_dir) / exportFileName(format) : fs::path(out_file);
    fs::path parent = fs::absolute(out).parent_path();
    if (!fs::is_directory(parent) || fs::is_directory(out))
        throw std::invalid_argument("export --out " + out.string() + ": accepted: a file path in an existing directory");
    reports::RunData d;
    try {
        d = reports::loadRun(run_dir);
    } catch (const nlohmann::json::exception& e) {
        throw std::invalid_argument("export " + (fs::path(run_dir) / rundir::kRunJson).string() + ": " + e.what());
    }
    reports::writeTextAtomically(out, exportText(d, format));
    std::printf("export: %s\n", out.c_str());
    return kExitDone;
}

}  // namespace cbr::harness
