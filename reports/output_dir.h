// An output directory that appears whole or not at all: written under a temporary
// name beside the final one, renamed on commit, removed if the run fails.
#pragma once

#include <filesystem>

namespace cbr::reports {

class OutputDir {
public:
    // Throws std::invalid_argument when `final_path` exists already (never overwrite results).
    explicit OutputDir(std::filesystem::path final_path);
    ~OutputDir();  // removes the temporary directory unless committed
    OutputDir(const OutputDir&) = delete;
    OutputDir& operator=(const OutputDir&) = delete;

    const std::filesystem::path& path() const { return temp_; }      // write here
    const std::filesystem::path& finalPath() const { return final_; }
    void commit();

private:
    std::filesystem::path final_;
    std::filesystem::path temp_;
    bool committed_ = false;
};

}  // namespace cbr::reports
