#include "render_control.h"

#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>

#include "strahl/core/error.h"
#include "strahl/core/hash.h"

namespace strahl::app {

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

std::string renderFingerprint(const Options& o, const SceneDesc& desc, const PixelRect& crop) {
    std::ostringstream f;
    f << imageFingerprint(desc) << ", crop " << crop.x0 << "," << crop.y0 << "," << crop.x1
      << "," << crop.y1 << ", tile " << o.tileSize;
    if (o.sampleOffset) f << ", samples from " << *o.sampleOffset;
    return f.str();
}

std::string splitFingerprint(const Options& o, const SceneDesc& desc) {
    SceneDesc whole = desc;
    whole.render.spp = 0;
    std::string f = imageFingerprint(whole);
    // imageFingerprint names the samples per pixel as ", N spp".
    const std::string spp = ", 0 spp";
    if (const size_t at = f.find(spp); at != std::string::npos) f.erase(at, spp.size());
    return f + ", accel " + o.accel;
}

std::string imageFingerprint(const SceneDesc& desc) {
    std::ifstream in(desc.file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ostringstream f;
    f << "scene " << desc.file.filename().string() << " fnv1a " << std::hex << fnv1a(bytes)
      << std::dec << ", " << desc.film.width << "x" << desc.film.height << ", "
      << desc.render.spp << " spp, seed " << desc.render.seed << ", " << desc.render.integrator
      << " depth " << desc.render.maxDepth << (desc.render.russianRoulette ? " rr" : " no-rr")
      << ", filter " << desc.film.filter;
    if (desc.film.filterRadius) f << " r " << *desc.film.filterRadius;
    f << ", aovs";
    for (AovKind a : desc.film.aovs) f << " " << aovName(a);
    return f.str();
}

}  // namespace strahl::app
