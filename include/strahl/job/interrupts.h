#pragma once
// SIGINT and SIGTERM during a render: the render job catches them, lets the
// tiles in flight finish, writes its checkpoint and partial images, and
// reports which signal stopped it (docs/reliability.md).

#include <atomic>
#include <csignal>
#include <string>

namespace strahl {

// While alive, SIGINT and SIGTERM set cancelFlag() instead of killing the
// process (a second signal kills it as usual); the previous handlers come
// back on destruction.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    static const std::atomic<bool>& cancelFlag();
    static int signalNumber();  // the signal that set the flag, 0 if none

private:
    using Handler = void (*)(int);
    Handler previousInt_, previousTerm_;
};

// "SIGINT", "SIGTERM" or "signal N".
std::string signalName(int signal);

}  // namespace strahl
