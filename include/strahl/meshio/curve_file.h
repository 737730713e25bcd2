#pragma once
// Strand files: the text format Mitsuba 3's `bsplinecurve` and `linearcurve`
// read, one control point per line and a blank line between strands:
//
//     x y z radius      a control point of the current strand
//     ...
//                       (a blank line ends the strand)
//     x y z radius      the first point of the next strand
//
// '#' starts a comment. Any malformed, non-finite or negative value throws
// strahl::Error with "file:line: what"; a file without points is an error.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "strahl/core/math.h"

namespace strahl {

struct StrandFile {
    std::vector<Vec4> points;             // x, y, z, radius
    std::vector<uint32_t> strandPoints;   // points of each strand, in order
};

StrandFile loadStrandFile(const std::filesystem::path& file);

}  // namespace strahl
