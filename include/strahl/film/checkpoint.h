#pragma once
// Render checkpoints: a film's whole accumulation state (film.h writeState)
// in one binary file, with a fingerprint of everything that decides the image
// (scene, resolution, crop, spp, seed, integrator settings, tile size, ...;
// the caller builds it). Resuming from a checkpoint continues every pixel's
// sums exactly where they stopped, so the final image is bit-identical to an
// uninterrupted render (docs/reliability.md).
//
// File layout: "STRAHLCK", format version (u32), fingerprint length (u32) and
// bytes, then the film buffers, each as a u64 count and raw values (native
// byte order: a checkpoint is for resuming on the same kind of machine).

#include <filesystem>
#include <string>

#include "strahl/film/film.h"

namespace strahl {

// Writes atomically: to a temporary name in the same folder, then renamed, so
// an interrupted write never leaves a broken checkpoint behind.
void writeCheckpoint(const Film& film, const std::filesystem::path& file,
                     const std::string& fingerprint);

// Loads `file` into `film`. Throws strahl::Error naming the file if it is
// missing, not a checkpoint, of another format version, made with other
// settings (fingerprint mismatch, both shown), or truncated.
void readCheckpoint(Film& film, const std::filesystem::path& file, const std::string& fingerprint);

}  // namespace strahl
