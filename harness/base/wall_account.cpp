// The wall-time account's names, its closing and its stderr line.
#include "harness/base/wall_account.h"

#include <cstdio>
#include <iterator>

#include "rundir/run_json_health.h"

namespace cbr::harness {

// run.json's wall.parts_s and wall.worker_cpu_s keys, in the enums' order (rundir/run_json_health.h).
static_assert(std::size(rundir::run::wall::kParts) == kWallParts);
static_assert(std::size(rundir::run::wall::kWorkerTasks) == kWorkerTasks);

const char* wallPartKey(WallPart part) { return rundir::run::wall::kParts[size_t(part)]; }

const char* workerTaskKey(WorkerTask task) { return rundir::run::wall::kWorkerTasks[size_t(task)]; }

void WallAccount::close() {
    total_ = elapsed();
    double claimed = 0;
    for (size_t i = 0; i + 1 < kWallParts; ++i) claimed += parts_[i];
    // Scopes never overlap on the main thread, so the remainder is what no scope covered;
    // clock reads between scopes can make it a hair negative.
    parts_[size_t(WallPart::Other)] = total_ > claimed ? total_ - claimed : 0.0;
}

std::string WallAccount::line() const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "wall %.1f s:", total_);
    std::string out = buf;
    const char* sep = " ";
    for (size_t i = 0; i < kWallParts; ++i) {
        if (parts_[i] < 0.05) continue;
        std::snprintf(buf, sizeof buf, "%s%s %.1f", sep, wallPartKey(WallPart(i)), parts_[i]);
        out += buf;
        sep = ", ";
    }
    out += "; worker CPU s:";
    sep = " ";
    for (size_t i = 0; i < kWorkerTasks; ++i) {
        std::snprintf(buf, sizeof buf, "%s%s %.1f", sep, workerTaskKey(WorkerTask(i)), worker(WorkerTask(i)));
        out += buf;
        sep = ", ";
    }
    return out;
}

}  // namespace cbr::harness
