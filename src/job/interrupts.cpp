#include "strahl/job/interrupts.h"

namespace strahl {

namespace {

std::atomic<bool> gCancel{false};
// Written by the handler, read after the render: sig_atomic_t is what a
// handler may write.
volatile std::sig_atomic_t gSignal = 0;

static_assert(std::atomic<bool>::is_always_lock_free,
              "the signal handler may only touch lock-free atomics");

extern "C" void onInterrupt(int signal) {
    gSignal = signal;
    gCancel.store(true, std::memory_order_relaxed);
    // A second signal is not caught: it kills the process as usual.
    std::signal(signal, SIG_DFL);
}

}  // namespace

InterruptGuard::InterruptGuard() {
    gCancel.store(false);
    gSignal = 0;
    previousInt_ = std::signal(SIGINT, onInterrupt);
    previousTerm_ = std::signal(SIGTERM, onInterrupt);
}

InterruptGuard::~InterruptGuard() {
    std::signal(SIGINT, previousInt_ == SIG_ERR ? SIG_DFL : previousInt_);
    std::signal(SIGTERM, previousTerm_ == SIG_ERR ? SIG_DFL : previousTerm_);
}

const std::atomic<bool>& InterruptGuard::cancelFlag() { return gCancel; }
int InterruptGuard::signalNumber() { return gSignal; }

std::string signalName(int signal) {
    if (signal == SIGINT) return "SIGINT";
    if (signal == SIGTERM) return "SIGTERM";
    return "signal " + std::to_string(signal);
}

}  // namespace strahl
