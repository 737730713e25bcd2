#pragma once
// Unattended-render controls of `strahl render`: SIGINT/SIGTERM handling,
// checkpoints and resume, and the time limit (docs/reliability.md).

#include <atomic>
#include <csignal>
#include <string>

#include "options.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::app {

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

// Everything that decides the rendered image, as one line: a checkpoint made
// with one fingerprint can only be resumed by a render with the same one. The
// scene file is identified by a 64-bit FNV-1a hash of its bytes (the files it
// refers to are not hashed: change them and the resumed image is a mix).
std::string renderFingerprint(const Options& options, const SceneDesc& desc,
                              const PixelRect& crop);

}  // namespace strahl::app
