#pragma once
// Image-parallel rendering of one image over MPI (`strahl render --distributed`,
// docs/distributed.md). Every MPI process (rank) runs the same command line and
// loads the scene itself. Rank 0, the scheduler, hands out tiles on request and
// gathers the finished ones into its film; the other ranks, the workers, render
// whole tiles (all samples) with all their threads. With adaptive sampling the
// samples are rendered in rounds between the decision passes, rank 0 deciding
// on the whole film between rounds (docs/distributed.md#adaptive-sampling). A pixel depends only on
// (seed, pixel, sample index), so the gathered film is bit-identical to the one
// a single process renders.
//
// This header holds no MPI type: only src/distributed/ includes <mpi.h>, as only
// accel/ includes Embree. Without MPI (STRAHL_MPI=OFF) the module is one file
// whose run() and renderImage() refuse with "this strahl was built without MPI".

#include <functional>
#include <string>

#include "strahl/render/renderer.h"

namespace strahl::distributed {

// Whether this strahl was built with MPI (CMake option STRAHL_MPI).
bool available();

// What this process is: Local outside run(), else the scheduler (rank 0) or a worker.
enum class Role { Local, Scheduler, Worker };
Role role();

// Starts MPI, runs `command` on this rank and ends MPI; returns the exit status.
// Fewer than 2 ranks is an error (exit 2): nothing would render. A strahl::Error
// (or any exception) on rank 0 is printed as "strahl: error: <message>"; on a
// worker it is sent to rank 0, which prints "strahl: rank K: <message>". Either
// way rank 0 then aborts the whole job (MPI_Abort, exit status 1) before any
// output is written. Throws strahl::Error without MPI.
int run(const std::function<int()>& command);

struct Settings {
    // Everything that decides the image (scene hash, size, crop, spp, seed, ...):
    // a worker whose fingerprint differs from rank 0's is an error, so no image
    // is ever assembled from different scenes or settings.
    std::string fingerprint;
    // The scheduler prints one line at the end: tiles per worker, bytes gathered.
    bool report = true;
};

// Renders `film` (the scheduler's: the whole crop) distributed over the ranks.
//   Scheduler: returns when every tile is in `film`, with the ray counts of all
//   workers summed; options.progress counts tiles. options.cancel and passDone
//   are not used (the CLI rejects --checkpoint, --resume and --time-limit).
//   Worker: renders the tiles it is given with options.threads threads; `film`
//   only gives the image's size, crop and AOVs and is left untouched.
RenderStats renderImage(const World& world, const Camera& camera, const Integrator& integrator,
                        Film& film, const RenderOptions& options, const Settings& settings);

}  // namespace strahl::distributed
