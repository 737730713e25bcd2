#pragma once
// Reading an OpenEXR image written by `strahl render` back into a Film, the
// inverse of image_output.h for EXR, for `strahl merge` (docs/farm.md).
//
// An image that carries the exact state of a part of a split render
// (exact_part.h) comes back bit for bit: the film is the one that was
// written. Any other strahl EXR carries only the resolved means, rounded to
// half or float; its film is rebuilt from them with every pixel's sample count
// taken from the metadata (strahl:samples, else strahl:spp), so merging it
// gives a sample-weighted mean, close to but not bit for bit the image of one
// render (depth and position are weighted by samples, as their true hit counts
// are unknown; the variance is recombined from the means by Chan's formula).

#include <filesystem>
#include <string>
#include <vector>

#include "strahl/core/pixel_rect.h"
#include "strahl/film/film.h"
#include "strahl/film/image_output.h"

namespace strahl {

struct ExrHeader {
    std::filesystem::path file;
    int fullWidth = 0, fullHeight = 0;     // the display window
    PixelRect dataWindow;                  // the crop that was rendered
    std::vector<std::string> channels;     // in file order (sorted by name)
    std::vector<std::string> channelTypes; // "half" or "float", per channel
    bool exrFloat = false;                 // the beauty channels are 32-bit float
    std::vector<AovKind> aovs;             // in enum order
    ImageMetadata metadata;                // metadata.part is set iff the exact state is there
    uint32_t samples = 0;                  // samples per pixel
    bool exact() const { return metadata.part.has_value(); }
};

// Reads and checks the header. Throws strahl::Error naming the file if it is
// missing, not OpenEXR, or not laid out as strahl writes images (a channel
// strahl does not write, an AOV with missing channels, no sample count, exact
// channels without their metadata or the reverse).
ExrHeader readExrHeader(const std::filesystem::path& file);

// Reads the pixels into a film of the header's size, data window and AOVs.
// Throws strahl::Error naming the file if they cannot be read, or if the
// exact state does not match the sample ranges (a part that was interrupted
// or stopped by --time-limit has pixels with fewer samples: it cannot be
// merged exactly).
Film readExrFilm(const ExrHeader& header);

}  // namespace strahl
