// Atomic output directories.
#include "reports/output_dir.h"

#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace cbr::reports {

OutputDir::OutputDir(std::filesystem::path final_path) : final_(std::move(final_path)) {
    if (std::filesystem::exists(final_))
        throw std::invalid_argument("--out " + final_.string() +
                                    ": already exists; expected a path that does not exist yet");
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
    std::filesystem::rename(temp_, final_);
    committed_ = true;
}

}  // namespace cbr::reports
