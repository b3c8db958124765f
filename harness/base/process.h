// The process cbrbench runs in: its memory policy, set before anything allocates, and the
// host description run.json carries.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cbr::harness {

// First thing in main. Keeps freed memory for reuse, and where the kernel gives transparent
// huge pages only to memory that asks for them (THP "madvise", Debian's default), asks for
// them on every heap allocation: glibc reads that wish (GLIBC_TUNABLES glibc.malloc.hugetlb=1)
// only at start, so the process starts itself again once with it. CBR_HUGE_PAGES=0 turns
// this off. Returns normally unless that exec happens.
void setUpProcessMemory(char** argv);

// "name", "cpus" and "memory" (what setUpProcessMemory did) for run.json files.
nlohmann::json hostJson();

// A child process's end: its exit code (-1 when killed) and the signal that killed it (0: none).
struct ChildExit {
    int code = -1;
    int signal = 0;
};

// fork + exec of argv[0] with `argv`, stdout and stderr to the two files (created or
// truncated), waited for. `stress` and `ab` run their `cbrbench run` children this way.
ChildExit runChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& out_log,
                          const std::filesystem::path& err_log);

}  // namespace cbr::harness
