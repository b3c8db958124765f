// An output directory that appears whole or not at all: written under a temporary
// name beside the final one, renamed on commit, removed if the run fails.
#pragma once

#include <filesystem>

namespace cbr::reports {

class OutputDir {
public:
    // Throws std::invalid_argument when `final_path` exists already (never overwrite results),
    // unless `replace`: then an existing folder that cbrbench wrote (it holds run.json, or nothing)
    // is swapped for the new one in one step when commit() runs, and removed after; until then
    // it stays as it was, and a run that fails or is interrupted leaves it untouched.
    explicit OutputDir(std::filesystem::path final_path, bool replace = false);
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
    bool replace_ = false;
};

}  // namespace cbr::reports
