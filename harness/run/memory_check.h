// Memory, before the first frame and along the run: an estimate of the run's peak against
// what the host and the device have (a run that cannot fit stops before rendering, with one
// line and no output), and the readings run.json `memory` and the report show.
#pragma once

#include <string>

#include "harness/figures/results.h"
#include "harness/base/wall_account.h"
#include "renderer/vk/context.h"

namespace cbr::harness {

// What a run will hold, as far as its memory goes (run.cpp fills it from the prepared run).
struct MemoryPlan {
    std::string resolution;  // "WxH", for the refusal's line
    int width = 0, height = 0;
    size_t configs = 0;      // configurations rendered
    size_t scored = 0;       // configurations scored against the reference
    size_t frames = 0;
    int repeat = 1;
    bool device_scorer = false;
    bool analysis = false;   // quality frames also read back motion and depths
    int cvvdp_window = 0;    // ColorVideoVDP's temporal window, frames (the CPU scorer keeps it per configuration)
    double host_limit_mib = 0, device_limit_mib = 0;  // the options; 0: what the machine has
};

// After the renderers and the scorer exist (their device memory is allocated, so counted
// exactly), before any frame: the estimate of the peak against the limits (--host-memory-limit
// or what the host has available; --device-memory-limit or the device's budget), recorded in
// `figures`. Throws std::invalid_argument with one line when the run would not fit.
void checkMemory(const MemoryPlan& plan, const vk::Context& ctx, MemoryFigures& figures);

// The process's peak RSS and the device's memory use after a phase (run.json memory.after).
void noteMemory(const vk::Context& ctx, const char* phase, MemoryFigures& figures, WallAccount& wall);

// VmRSS and MemAvailable, in MiB (0 where /proc does not say).
double currentRssMib();
double availableHostMib();

}  // namespace cbr::harness
