#include "harness/base/process.h"

#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <sys/wait.h>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <fstream>
#include <malloc.h>
#include <thread>

#include "rundir/run_json.h"
#include <unistd.h>

#include "renderer/vk/sanitizers.h"

namespace cbr::harness {
namespace {

constexpr const char* kHugeTunable = "glibc.malloc.hugetlb=1";

// The kernel's THP mode, the bracketed word of /sys/kernel/mm/transparent_hugepage/enabled
// ("always", "madvise", "never"), or "" where it cannot be read.
std::string thpMode() {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(f, line);
    size_t open = line.find('['), close = line.find(']');
    return open != std::string::npos && close > open ? line.substr(open + 1, close - open - 1) : "";
}

// glibc's hugetlb tunable as the environment sets it: -1 unset, else its value (1: madvise
// the heap, 2: hugetlbfs pages). A value the user set is kept.
int hugeTunable() {
    const char* t = std::getenv("GLIBC_TUNABLES");
    const char* at = t ? std::strstr(t, "glibc.malloc.hugetlb=") : nullptr;
    return at ? std::atoi(at + std::strlen("glibc.malloc.hugetlb=")) : -1;
}

// Off on request, and in sanitizer builds, whose allocator is not glibc's.
bool hugePagesOff() {
#if defined(CBR_SANITIZED)
    return true;
#else
    const char* v = std::getenv("CBR_HUGE_PAGES");
    return v && std::strcmp(v, "0") == 0;
#endif
}

}  // namespace

// Why: on a virtual machine a page fault costs several microseconds, and lavapipe renders
// into malloc'd memory. glibc returns freed blocks above its mmap threshold and the heap's
// free top to the kernel, so each next large buffer (a decoded texture, a vertex array, a
// frame read back) was faulted in again page by page: loading the 1M-triangle test scene
// took 0.84 s (0.69 s keeping freed memory) with 186k faults, and lavapipe's timed frames
// were 7-11% faster once freed memory was kept (docs/history/development-record.md, "Loading large scenes", sessions 11
// and 14). Huge pages fault 2 MiB at a time: the same load in 0.20 s.
void setUpProcessMemory(char** argv) {
    if (!hugePagesOff() && hugeTunable() < 0 && thpMode() == "madvise") {
        const char* env = std::getenv("GLIBC_TUNABLES");
        const bool had = env != nullptr;
        const std::string old = had ? env : "";
        const std::string tunables = old.empty() ? kHugeTunable : old + ":" + kHugeTunable;
        if (::setenv("GLIBC_TUNABLES", tunables.c_str(), 1) == 0) {
            ::execv("/proc/self/exe", argv);
            // No exec (no /proc): go on without huge pages, and say so in run.json.
            if (had)
                ::setenv("GLIBC_TUNABLES", old.c_str(), 1);
            else
                ::unsetenv("GLIBC_TUNABLES");
        }
    }
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest accepted value
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_TOP_PAD, 64 << 20);
}

nlohmann::json hostJson() {
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) != 0) host[0] = 0;
    std::string thp = thpMode();
    // Huge pages for the heap: the kernel gives them to everything ("always"), or to what asks
    // and glibc asked ("madvise" with the tunable at 1), or glibc maps hugetlbfs pages (2).
    const int tunable = hugeTunable();
    bool huge = tunable == 2 || (tunable != 0 && thp == "always") || (tunable == 1 && thp == "madvise");
    namespace k = rundir::run::host;
    return {{k::kName, std::string(host)},
            {k::kCpus, std::thread::hardware_concurrency()},
            {k::kMemory,
             {{k::memory::kKeepsFreedMemory, true},
              {k::memory::kTransparentHugePages, thp.empty() ? "unknown" : thp},
              {k::memory::kHeapHugePages, huge}}}};
}

ChildExit runChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& out_log,
                          const std::filesystem::path& err_log) {
    std::fflush(nullptr);
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed: " + std::string(std::strerror(errno)));
    if (pid == 0) {
        int o = ::open(out_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int e = ::open(err_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (o >= 0) dup2(o, 1);
        if (e >= 0) dup2(e, 2);
        std::vector<std::string> copy = argv;
        std::vector<char*> cargv;
        for (auto& a : copy) cargv.push_back(a.data());
        cargv.push_back(nullptr);
        execv(cargv[0], cargv.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    ChildExit r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
    return r;
}

}  // namespace cbr::harness
