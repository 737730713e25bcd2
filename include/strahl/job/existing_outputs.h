#pragma once
// `strahl render --skip-existing`: is an output already there, finished, and
// the image this render would write? Only the file is read, never the scene's
// meshes or textures, so a farm can re-queue a whole job cheaply.

#include <filesystem>
#include <string>

#include "strahl/core/pixel_rect.h"

namespace strahl {

struct ExpectedImage {
    int fullWidth = 0, fullHeight = 0;  // the film
    PixelRect region;                   // the pixels rendered (the EXR data window)
    std::string fingerprint;            // imageFingerprint() of the render
};

// Empty if `file` is complete: it exists, every pixel decodes, its size (for
// EXR, its display and data windows) is the expected one, it is not marked
// strahl:partial = 1 (an interrupted or time-limited render), and, if it has
// a strahl:fingerprint, that is the expected one. Otherwise why it is not,
// for the log ("is partial (stopped by SIGINT)").
std::string incompleteReason(const std::filesystem::path& file, const ExpectedImage& expected);

// Whether strahl's images of this kind carry strahl:partial: EXR and PNG do
// (EXR attributes, PNG text chunks); JPEG and TIFF lose it, so a partial one
// cannot be told from a complete one by itself.
bool recordsPartial(const std::filesystem::path& file);

}  // namespace strahl
