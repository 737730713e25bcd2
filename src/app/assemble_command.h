#pragma once
// `strahl assemble REGION.exr... -o OUT.exr`: stitches the EXRs of
// `strahl render --region` runs (one image cut into rectangles, rendered on
// several machines) into the full image. The regions must be pieces of one
// image — same display window, channels and channel types, and the same
// strahl:fingerprint and strahl:frame where they carry them — and must not
// overlap. Pixels are copied, never resampled, so the result is bit-identical
// to a single full render. A gap (pixels no region covers) is an error
// unless --allow-gaps, and a partial (interrupted) region is an error unless
// --allow-partial; either way the result is then marked strahl:partial = 1,
// never presented as complete (docs/farm.md).

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strahl::app {

struct AssembleOptions {
    std::vector<std::string> inputs;  // region EXRs
    std::string output;               // the full image, .exr
    bool allowGaps = false;           // fill uncovered pixels with 0, mark the result partial
    bool allowPartial = false;        // accept interrupted regions, mark the result partial
    bool quiet = false;
};

// Adds the `assemble` subcommand and its options to `app`.
CLI::App* addAssembleCommand(CLI::App& app, AssembleOptions& options);

// Runs it; returns the exit status, throws strahl::Error for bad input.
int runAssemble(const AssembleOptions& options);

}  // namespace strahl::app
