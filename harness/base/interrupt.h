// SIGINT and SIGTERM: the run stops at the next frame, its output directory (still under
// its temporary name) is removed, and the command says so and exits 130. A second signal
// ends the process at once.
#pragma once

#include <stdexcept>

namespace cbr::harness {

struct Interrupted : std::runtime_error {
    Interrupted() : std::runtime_error("interrupted") {}
};

void installInterruptHandler();
bool interruptRequested();
// Throws Interrupted once a signal arrived; the run loop calls it between frames.
void throwIfInterrupted();

}  // namespace cbr::harness
