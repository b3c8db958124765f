// The interrupt flag, set from the signal handler (async-signal-safe: one atomic store).
#include "harness/base/interrupt.h"

#include <atomic>
#include <csignal>

namespace cbr::harness {
namespace {

std::atomic<int> g_signal{0};

extern "C" void onSignal(int sig) {
    g_signal.store(sig);
    // The next one is not caught: a second Ctrl-C ends a stuck run.
    std::signal(sig, SIG_DFL);
}

}  // namespace

void installInterruptHandler() {
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool interruptRequested() { return g_signal.load() != 0; }

void throwIfInterrupted() {
    if (interruptRequested()) throw Interrupted();
}

}  // namespace cbr::harness
