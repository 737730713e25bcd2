#pragma once
// Frame-numbered file names, as render farms use them: every run of '#' in a
// name stands for the frame number, zero-padded to the run's length
// ("shots/beauty.####.exr", frame 42 -> "shots/beauty.0042.exr"); a number
// with more digits than the run is written in full (frame 12345 ->
// "beauty.12345.exr"). The frame number only names files (and goes into the
// EXR metadata): strahl scenes have no animation (docs/farm.md).

#include <filesystem>
#include <string>

namespace strahl {

bool hasFramePattern(const std::string& name);

// `name` with every '#' run replaced by `frame` (>= 0).
std::string expandFramePattern(const std::string& name, int frame);

// The same for a path; throws strahl::Error "<what> <path>: ... no --frame"
// if it has a '#' run and `frame` is negative (not given).
std::filesystem::path expandFramePattern(const std::filesystem::path& path, int frame,
                                         const std::string& what);

}  // namespace strahl
