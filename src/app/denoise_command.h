#pragma once
// `strahl denoise IN.exr -o OUT.exr [-o OUT.png]`: denoises an EXR that strahl
// wrote with the denoiser's layers (a render with --denoise, or `strahl merge`
// of --denoise parts): the sample halves half0.* and half1.* and the variance
// AOV (film/denoise_layers.h, docs/denoising.md). The EXR output keeps every
// channel of the input, with the denoised beauty as R, G, B and the noisy one
// as noisy.R, noisy.G, noisy.B; display outputs show the denoised beauty.

#include <string>
#include <vector>

#include "strahl/film/display_transform.h"

namespace CLI {
class App;
}

namespace strahl::app {

struct DenoiseOptions {
    std::string input;
    std::vector<std::string> outputs;
    ColorSettings color;  // for display outputs
    int threads = 0;      // 0: all cores
    bool quiet = false;
};

CLI::App* addDenoiseCommand(CLI::App& app, DenoiseOptions& options);

// Returns the exit status; throws strahl::Error for bad input.
int runDenoise(const DenoiseOptions& options);

}  // namespace strahl::app
