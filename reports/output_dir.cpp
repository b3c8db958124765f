// Atomic output directories.
#include "reports/output_dir.h"

#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

#include "rundir/files.h"

namespace cbr::reports {
namespace {

// What --replace may replace: a folder cbrbench wrote, or an empty one.

bool wroteIt(const std::filesystem::path& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) return false;
    for (const char* mark : {rundir::kRunJson, "matrix.json", "stress.csv"})
        if (std::filesystem::exists(dir / mark, ec)) return true;
    return std::filesystem::is_empty(dir, ec);
}

}  // namespace

OutputDir::OutputDir(std::filesystem::path final_path, bool replace) : final_(std::move(final_path)) {
    if (std::filesystem::exists(final_)) {
        if (!replace)
            throw std::invalid_argument("--out " + final_.string() +
                                        ": already exists; expected a path that does not exist yet (or --replace)");
        if (!wroteIt(final_))
            throw std::invalid_argument("--out " + final_.string() +
                                        ": --replace replaces only a folder cbrbench wrote (with run.json, "
                                        "matrix.json or stress.csv) or an empty one; this is neither");
        replace_ = true;
    }
    std::filesystem::path parent = final_.parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    temp_ = final_;
    temp_ += ".partial-" + std::to_string(::getpid());
    std::filesystem::remove_all(temp_);
    std::filesystem::create_directories(temp_);
}

OutputDir::~OutputDir() {
    if (committed_) return;
    std::error_code ec;
    std::filesystem::remove_all(temp_, ec);
    // Parents we created stay: they may hold other runs.
}

void OutputDir::commit() {
    if (replace_ && std::filesystem::exists(final_)) {
        // One step: the new folder takes the old one's name, the old one the temporary's.
        if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0)
            throw std::system_error(errno, std::generic_category(), "--replace " + final_.string());
        committed_ = true;
        std::error_code ec;
        std::filesystem::remove_all(temp_, ec);
        return;
    }
    std::filesystem::rename(temp_, final_);
    committed_ = true;
}

}  // namespace cbr::reports
