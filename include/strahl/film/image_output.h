#pragma once
// Writing a Film to disk through OpenImageIO; the format follows the extension.
//   .exr            scene-linear RGB (half by default, float on request), AOVs as
//                   named channels ("normal.X", "depth.Z", "albedo.R",
//                   "position.X", "objectid.X", "variance.R", ...; objectid is
//                   always 32-bit float, so ids stay exact) and metadata
//                   (render time, spp, camera, strahl version).
//   .png .jpg .jpeg .tif .tiff
//                   display-referred: the OpenColorIO display/view transform is
//                   applied (see display_transform.h), then quantised.
// Files are written to a temporary name in the destination folder and renamed,
// so a failure never leaves a partial file behind.

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/film/display_transform.h"
#include "strahl/film/exact_part.h"
#include "strahl/film/film.h"

namespace strahl {

struct OutputSettings {
    bool exrFloat = false;  // 32-bit float EXR channels instead of half
    ColorSettings color;
};

// Free-form metadata stored in EXR headers ("strahl:<key>") and as far as the
// format allows elsewhere.
struct ImageMetadata {
    double renderSeconds = 0.0;
    int spp = 0;
    std::string integrator;
    std::string camera;  // human-readable camera description
    Mat4 worldToCamera{1.0f};
    std::map<std::string, std::string> extra;
    // Set for a part of a render split by sample ranges (--sample-offset) and
    // for merges of such parts: EXR outputs then also carry the film's exact
    // state and strahl:samples_begin, strahl:samples_end (ints: the first and
    // one past the last sample index), strahl:sample_ranges ("0-2,5-6") and
    // strahl:split_fingerprint, for `strahl merge` (film/exact_part.h).
    std::optional<SamplePart> part;
};

// The EXR channel suffixes of an AOV, one letter per channel: "XYZ" for
// normal and position, "Z" for depth, "RGB" for albedo and variance, "X" for
// objectid (channel "normal.X", ...).
const char* exrChannelSuffixes(AovKind kind);

// The extensions writeImage accepts, lower case with the dot (".exr", ...).
std::span<const std::string_view> supportedImageExtensions();

// Throws strahl::Error if the extension is not supported or the folder is not
// writable (checked by creating and removing a temporary file), so a render can
// fail before it starts rather than after.
void checkOutputPath(const std::filesystem::path& file);

// `denoised`, if given (crop-sized RGB), is written as the beauty and the
// film's own beauty as the EXR layer "noisy" (film/denoise_layers.h); display
// formats show the denoised image. A film that keeps the sample halves also
// writes their layers to EXR.
void writeImage(const Film& film, const std::filesystem::path& file, const OutputSettings& settings,
                const ImageMetadata& metadata, const std::vector<float>* denoised = nullptr);

// A display-referred image (PNG, JPEG or TIFF, by extension) of scene-linear
// RGB pixels (width x height, interleaved), through the display transform
// exactly as writeImage writes a film's beauty.
void writeDisplayImage(std::vector<float> rgb, int width, int height,
                       const std::filesystem::path& file, const OutputSettings& settings,
                       const ImageMetadata& metadata);

// The temp-then-rename writer behind writeImage, for every other file strahl
// writes whole (assembled images, statistics): `write` creates the file at the
// temporary path it is given (in the destination folder, same extension) and
// returns an error message, empty on success; then the file is renamed to
// `file`. On any failure (an error message, an exception, a failed rename) the
// temporary file is removed and strahl::Error "<file>: cannot write: ..." is
// thrown, so no partial file is ever left under either name.
void writeFileAtomically(const std::filesystem::path& file,
                         const std::function<std::string(const std::filesystem::path& temp)>& write);

// writeFileAtomically for a text file (a stats file, a converted scene).
void writeTextFileAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace strahl
