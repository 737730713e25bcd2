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

// What decides the pixel values of the image, whatever part of it is
// rendered: the scene (hashed as above), resolution, samples, seed,
// integrator, filter and AOVs, but not the region, tiles or threads. Stored
// in EXR outputs as strahl:fingerprint; `strahl assemble` stitches only
// regions that agree on it, and --skip-existing re-renders an output made
// with another one.
std::string imageFingerprint(const SceneDesc& desc);

// What the parts of a render split by sample ranges (--sample-offset,
// `strahl merge`, docs/farm.md) must share, stored in their EXRs as
// strahl:split_fingerprint: imageFingerprint without the samples per pixel
// (the parts differ in them), plus the accelerator (the naive tracer need not
// round hits as Embree does). Not the tile size, threads or packet width:
// they leave the image bit-identical; the crop is compared separately.
std::string splitFingerprint(const Options& options, const SceneDesc& desc);

}  // namespace strahl::app
