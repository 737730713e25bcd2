#pragma once
// What decides an image, as one line of text, so that files made by different
// renders are never mixed: a checkpoint resumes only the render that wrote it,
// `strahl assemble` stitches only regions of one image, `strahl merge` sums
// only parts of one split render, and --skip-existing re-renders an output
// made with other settings (docs/farm.md, docs/reliability.md).

#include <optional>
#include <string>

#include "strahl/core/pixel_rect.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_document.h"

namespace strahl {

// What decides the pixel values of the image, whatever part of it is
// rendered: the scene file's name and a 64-bit FNV-1a hash of its document
// with every patch applied (SceneDocument::hash), leaving out only
// /film/outputs (where the image goes, not what it is). So every scene
// setting, from the file or from a flag or --set, is part of it, with no list
// to keep; the files the scene refers to are not hashed (change them and a
// resumed image is a mix). Stored in EXR outputs as strahl:fingerprint.
std::string imageFingerprint(const SceneDocument& document);

// A checkpoint's: the image fingerprint plus what is not in the scene
// document and changes how samples land in the film: the crop, the tile size
// and the first sample index of a split render.
std::string checkpointFingerprint(const std::string& imageFingerprint, const PixelRect& crop,
                                  int tileSize, std::optional<int> sampleOffset);

// What the parts of a render split by sample ranges (--sample-offset,
// `strahl merge`, docs/farm.md) must share, stored in their EXRs as
// strahl:split_fingerprint: the document hashed also without /render/spp (the
// parts differ in it), plus the accelerator (the naive tracer need not round
// hits as Embree does). Not the tile size, threads or packet width: they
// leave the image bit-identical; the crop is compared separately.
std::string splitFingerprint(AccelKind accel, const SceneDocument& document);

}  // namespace strahl
