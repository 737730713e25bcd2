#pragma once
// The render loop: the crop window is cut into square tiles rendered in
// parallel by oneTBB, one sample pass at a time; inside a tile, camera rays are
// generated and traced as coherent packets (camera/tile_rays.h) and every
// lane's hit is shaded by the integrator. Pixels belong to exactly one tile and
// samples are accumulated in sample order, so the image is bit-identical for
// any thread count, tile order or pass structure, and a render resumed from a
// film that already holds samples (a checkpoint) continues it exactly.

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "strahl/camera/camera.h"
#include "strahl/core/filter.h"
#include "strahl/film/film.h"
#include "strahl/integrator/integrator.h"
#include "strahl/integrator/world.h"
#include "strahl/render/adaptive_sampling.h"
#include "strahl/render/progress.h"

namespace strahl {

// How camera rays are traced: packets of the native width (16 with AVX-512,
// else 8), a forced width, or one ray at a time (for comparison).
enum class PacketMode { Auto, Packet8, Packet16, Single };

struct RenderOptions {
    int threads = 0;     // 0: all hardware threads
    int tileSize = 32;   // pixels per tile side; a multiple of 4 keeps packets full
    int spp = 1;
    uint64_t seed = 0;
    PacketMode packets = PacketMode::Auto;
    PixelFilter filter = PixelFilter::box();  // where samples land around pixel centres
    ProgressSink* progress = nullptr;
    // Set (from a signal handler, say) to stop: tiles in flight finish, the
    // rest are skipped, and renderImage returns with `cancelled` set.
    const std::atomic<bool>* cancel = nullptr;
    // Called on the calling thread after each complete sample pass but the
    // last, with the samples per pixel done; returning false stops the render
    // there (time limits). Checkpoints are written from here.
    std::function<bool(int samplesDone)> passDone;
    // Sample splitting (docs/farm.md): pass s takes sample index
    // sampleOffset + s of every pixel, so a render of spp samples from offset
    // K uses exactly the samples K .. K+spp-1 of the render of K+spp samples.
    // The film counts only its own samples (s), so a checkpoint resumes the
    // part where it stopped.
    int sampleOffset = 0;
    // One part of such a split render: samples are placed as in a render of
    // more than one sample per pixel even if this part has one (a render of
    // one sample alone shoots it through the pixel centre), so that every
    // part's samples are those of the whole.
    bool samplePart = false;
    // Stop pixels whose noise is below a threshold (adaptive_sampling.h); the
    // film must track convergence (Film::trackConvergence). spp is then the
    // most samples a pixel takes. Not with sampleOffset/samplePart.
    AdaptiveSampling adaptive;
};

struct RenderStats {
    double seconds = 0.0;
    double firstTileSeconds = 0.0;  // from the start of renderImage to the first finished tile
    uint64_t cameraRays = 0;
    uint64_t shadowRays = 0;
    uint64_t bounceRays = 0;  // secondary rays that continue paths
    uint64_t totalRays() const { return cameraRays + shadowRays + bounceRays; }
    int packetWidth = 1;  // the width actually used
    // Sample passes done (after a resume: in all): every pixel has this many
    // samples, except those adaptive sampling stopped earlier.
    int completedPasses = 0;
    bool cancelled = false;   // stopped by `cancel` before the last pass
    bool stoppedEarly = false;  // stopped by passDone returning false
    bool converged = false;   // adaptive sampling stopped every pixel before the last pass
};

// The tiles of `crop`, size x size pixels (smaller at the right and bottom
// edges), row by row from the top left.
std::vector<PixelRect> cutTiles(const PixelRect& crop, int size);

// The packet width `mode` resolves to on this accelerator.
int resolvePacketWidth(PacketMode mode, const Accel& accel);

RenderStats renderImage(const World& world, const Camera& camera, const Integrator& integrator,
                        Film& film, const RenderOptions& options);

}  // namespace strahl
