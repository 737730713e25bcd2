// Benchmarks that judge images run the strahl binary, one process per render
// as a user would, and read what it wrote: these are the shared pieces.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace strahl::bench {

// Every channel of an image file by name ("R", "noisy.G", "variance.B"...),
// as float planes in scanline order. Throws strahl::Error if it cannot be read.
using Channels = std::map<std::string, std::vector<float>>;
Channels readChannels(const std::filesystem::path& file);

// 'text' for the shell, with every ' inside closed, escaped and reopened.
std::string quoted(const std::string& text);

// The planes prefix+"R", "G", "B" interleaved as RGB.
std::vector<float> rgb(const Channels& channels, const std::string& prefix);

// What a render's --stats file says about its time, in seconds.
struct RenderTimes {
    double render = 0.0, denoise = 0.0;
    double load = 0.0, bvh = 0.0, firstPixel = 0.0, total = 0.0;  // as timings.* (docs/farm.md)
};

// Runs `strahl render SCENE -q --exr-float -o OUT --stats ... ARGS` (the
// binary of STRAHL_BINARY, each argument quoted for the shell) and returns
// its timings. Throws strahl::Error if the render fails.
RenderTimes renderWithCli(const std::filesystem::path& scene, const std::filesystem::path& out,
                          const std::vector<std::string>& args);

// Writes the sphere scene of issue 20 (a grey sphere on a ground plane, one
// point light, black sky) with an implicit sphere in place of the 2 million
// triangles: bench_roulette's open scene, and bench_convergence's stand-in
// when bench/peer_embree_tutorials.sh has not cached the OBJ. Throws
// strahl::Error if the file cannot be written.
void writeOpenSphereScene(const std::filesystem::path& file);

}  // namespace strahl::bench
