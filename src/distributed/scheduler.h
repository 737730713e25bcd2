#pragma once
// The scheduler (rank 0): hands out tiles to the workers on request and
// gathers the finished ones into the film.

#include "fault_injection.h"
#include "strahl/distributed/distributed.h"

namespace strahl::distributed {

// Returns when every tile of film.crop() is in `film` and every worker has
// been told that none are left. Throws WorkerFailed for a worker's error and
// strahl::Error for a worker that breaks the protocol (another fingerprint, a
// tile it was not given, pixel state of the wrong size).
RenderStats schedule(Film& film, const RenderOptions& options, const Settings& settings,
                     int ranks, FaultInjection& fault);

// For a rank 0 whose command ended without scheduling (nothing to render):
// answers every worker until each has been told that no tiles are left or has
// left itself, so none waits forever. Throws WorkerFailed for a worker's error.
void releaseWorkers(int ranks);

}  // namespace strahl::distributed
