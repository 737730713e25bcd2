#pragma once
// Unattended-render controls of `strahl render`: SIGINT/SIGTERM handling,
// checkpoints and resume, and the time limit (docs/reliability.md).

#include <atomic>
#include <csignal>
#include <string>

#include "options.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"

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
// with one fingerprint can only be resumed by a render with the same one: the
// image fingerprint (imageFingerprint below) plus what is not in the scene
// document: the crop, the tile size and the first sample index.
std::string renderFingerprint(const Options& options, const std::string& imageFingerprint,
                              const PixelRect& crop);

// What decides the pixel values of the image, whatever part of it is
// rendered: the scene file's name and a 64-bit FNV-1a hash of its document
// with every command-line patch applied (SceneDocument::hash), leaving out
// only /film/outputs (where the image goes, not what it is). So every scene
// setting, from the file or from a flag or --set, is part of it, with no list
// to keep; the files the scene refers to are not hashed (change them and a
// resumed image is a mix). Stored in EXR outputs as strahl:fingerprint;
// `strahl assemble` stitches only regions that agree on it, and
// --skip-existing re-renders an output made with another one.
std::string imageFingerprint(const SceneDocument& document);

// What the parts of a render split by sample ranges (--sample-offset,
// `strahl merge`, docs/farm.md) must share, stored in their EXRs as
// strahl:split_fingerprint: the document hashed also without /render/spp (the
// parts differ in it), plus the accelerator (the naive tracer need not round
// hits as Embree does). Not the tile size, threads or packet width: they
// leave the image bit-identical; the crop is compared separately.
std::string splitFingerprint(const Options& options, const SceneDocument& document);

}  // namespace strahl::app
