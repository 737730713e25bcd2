#pragma once
// A worker rank: asks the scheduler for tiles and renders each whole (every
// sample) on its own thread, sending the pixels back as soon as it is done.

#include <string>

#include "fault_injection.h"
#include "strahl/render/renderer.h"

namespace strahl::distributed {

// Returns when the scheduler says no tiles are left and every tile of this
// worker has been sent; the ray counts are this worker's. Throws the first
// error of any render thread (after stopping and joining them all).
RenderStats work(const World& world, const Camera& camera, const Integrator& integrator,
                 const Film& film, const RenderOptions& options, const std::string& fingerprint,
                 FaultInjection& fault);

}  // namespace strahl::distributed
