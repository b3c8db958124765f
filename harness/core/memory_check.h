// Memory, before the first frame and along the run: an estimate of the run's peak against
// what the host and the device have (a run that cannot fit stops before rendering, with one
// line and no output), and the readings run.json `memory` and the report show.
#pragma once

#include "harness/core/run_internal.h"

namespace cbr::harness {

// After the renderers and the scorer exist (their device memory is allocated, so counted
// exactly), before any frame: the estimate of the peak against the limits (--host-memory-limit
// or what the host has available; --device-memory-limit or the device's budget). Throws
// std::invalid_argument with one line when the run would not fit.
void checkMemory(RunState& s);

// The process's peak RSS and the device's memory use after a phase (run.json memory.after).
void noteMemory(RunState& s, const char* phase);

// VmRSS and MemAvailable, in MiB (0 where /proc does not say).
double currentRssMib();
double availableHostMib();

}  // namespace cbr::harness
