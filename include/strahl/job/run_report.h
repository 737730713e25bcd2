#pragma once
// What one render job did (RenderJob's result): written as a JSON file with
// `strahl render --stats FILE.json` for farm managers and scripts (every field
// is documented in docs/farm.md); the CLI's final JSON progress line ("done" /
// "interrupted") is made from it too.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "strahl/core/pixel_rect.h"

namespace strahl {

struct RunReport {
    std::string scene;
    std::optional<int> frame;
    int width = 0, height = 0;
    PixelRect region;
    int spp = 0;
    uint64_t seed = 0;
    std::string integrator, algorithm, accel;
    int sampleBegin = 0, sampleEnd = 0;  // the samples [begin, end) this image is asked to hold
    int samplesDone = 0;                 // samples per pixel every pixel has
    int threads = 0;                     // worker threads actually used
    double loadSeconds = 0, bvhSeconds = 0, renderSeconds = 0, firstPixelSeconds = 0,
           totalSeconds = 0;
    double denoiseSeconds = 0;  // render.denoise: the denoiser's time (0: not denoised)
    uint64_t cameraRays = 0, shadowRays = 0, bounceRays = 0;
    size_t peakResidentBytes = 0;
    std::vector<std::string> outputs;
    std::string stopped;  // "" (complete), "SIGINT", "SIGTERM", "time limit"
    int exitStatus = 0;
    std::string statsFile;  // where the report is written ("": nowhere); not a field of it
};

// "complete", "interrupted" (by a signal) or "time limit".
std::string runStatus(const RunReport& report);

// Throws strahl::Error "<file>: ..." unless `file` can be written (its folder
// exists and takes a new file): checked before the render, not after it.
void checkStatsPath(const std::filesystem::path& file);

// Writes the report as indented JSON (docs/farm.md) through a temporary file and a rename.
void writeStatsFile(const std::filesystem::path& file, const RunReport& report);

}  // namespace strahl
