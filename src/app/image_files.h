#pragma once
// What the commands that write images share: the display-transform options
// (render, merge, denoise), writing a whole float EXR under a temporary name
// (assemble, denoise) and telling EXR outputs by their extension (merge,
// denoise).

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <vector>

#include "strahl/film/display_transform.h"

namespace CLI {
class App;
}

namespace strahl::app {

// --ocio-config, --display and --view into `color`.
void addDisplayOptions(CLI::App& command, ColorSettings& color);

// Writes `pixels` (interleaved float, spec's size and channels; OpenImageIO
// converts them to the spec's channel formats) as OpenEXR, atomically
// (film/image_output.h writeFileAtomically): no partial file on failure.
void writeExrFile(const std::filesystem::path& file, const OIIO::ImageSpec& spec,
                  const std::vector<float>& pixels);

// Whether `file` has the extension .exr, in any letter case.
bool isExr(const std::filesystem::path& file);

}  // namespace strahl::app
