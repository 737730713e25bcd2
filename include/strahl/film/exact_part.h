#pragma once
// What the EXR of one part of a render split by sample ranges carries so that
// `strahl merge` adds parts into exactly the single-machine image
// (docs/farm.md, "Sample splitting and merge"):
//  - metadata: the sample indices it holds (strahl:samples_begin,
//    strahl:samples_end and, for merged files whose ranges need not be
//    contiguous, strahl:sample_ranges "0-2,5-6") and a fingerprint of the
//    scene and every setting that decides the image (strahl:fingerprint);
//  - the film's exact state (film.h FilmPixel) as extra channels next to the
//    usual ones, so nothing has to be recovered from rounded means:
//      strahl.sum.<channel>.0 .. .5   each exact sum (R, G, B, normal.X, ...,
//                                     depth.Z, albedo.R, ..., position.X, ...)
//      strahl.count.samples.0 .. .1   the pixel's sample count
//      strahl.count.hits.0 .. .1      samples that hit (depth or position AOV)
//      strahl.welford.mean.R|G|B      Welford's running mean  } variance AOV
//      strahl.welford.m2.R|G|B        and M2, as floats        }
//    (the objectid AOV's own float channel is already exact).
//
// Encoding: the integers are cut into 24-bit pieces, least significant first,
// each stored as a 32-bit float channel: a float holds every integer below
// 2^24 exactly, so the encoding is lossless. A 128-bit sum takes 6 pieces
// (the last holds its top 8 bits), a 32-bit count 2. Float rather than
// OpenEXR's 32-bit UINT channels because OpenImageIO converts the float pixel
// buffer to each channel's type (half or float) on writing, and would convert
// floats to UINT by scaling (1.0 -> 2^32 - 1); keeping every channel float or
// half lets the beauty and AOV channels take exactly the same path as in any
// other strahl EXR.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/film/film.h"

namespace strahl {

// Sample indices [begin, end) of every pixel.
struct SampleRange {
    uint32_t begin = 0, end = 0;
    uint32_t size() const { return end - begin; }
};

struct SamplePart {
    std::vector<SampleRange> ranges;  // sorted, disjoint, adjacent ranges joined
    std::string fingerprint;          // the scene and every image-affecting setting
    uint64_t sampleCount() const;     // samples per pixel in all ranges
};

// Sorts the ranges and joins those that touch; the ranges must be disjoint
// and not empty.
std::vector<SampleRange> joinRanges(std::vector<SampleRange> ranges);

// "0-2,5-6" (half-open ranges), and back; nullopt for text that is not such
// a list of non-empty, sorted, disjoint ranges.
std::string formatRanges(const std::vector<SampleRange>& ranges);
std::optional<std::vector<SampleRange>> parseRanges(std::string_view text);

// The extra channels of `film`, one float plane (crop-sized, row-major) per
// channel, appended to `names` and `planes`.
void appendExactChannels(const Film& film, std::vector<std::string>& names,
                         std::vector<std::vector<float>>& planes);

// Whether `channels` (names) include the exact state at all.
bool hasExactChannels(const std::vector<std::string>& channels);

// Sets every pixel of `film` (made with the image's size, data window and
// AOVs) from the exact channels of an image read as interleaved floats with
// these channel names; the objectid AOV comes from "objectid.X". Throws
// strahl::Error naming `source` if a channel is missing or holds no piece of
// an integer.
void readExactChannels(Film& film, const std::vector<std::string>& channels,
                       const std::vector<float>& pixels, const std::string& source);

}  // namespace strahl
