#pragma once
// Internal to the scene module: the placements of an instance array — one
// "instance" shape that places its group many times, with the placements read
// from a text file or scattered procedurally from a seed
// (docs/scene-format.md, "Instance arrays").

#include <cstdint>
#include <filesystem>
#include <vector>

#include "strahl/core/math.h"

namespace strahl::scene_detail {

// A placement file: one placement per line, '#' starts a comment, blank lines
// are skipped. A line holds 3, 4, 5 or 12 numbers:
//   x y z                  a translation
//   x y z yaw              then a rotation of yaw degrees about +y
//   x y z yaw scale        then a uniform scale (> 0)
//   m00 m01 m02 m03 m10 ... m23   an affine 3x4 matrix, row by row (invertible)
// Each becomes translate · rotate_y · scale (or the matrix): group space to
// the array's space. Throws strahl::Error "file:line: ..." for anything else,
// and before reading past `maxPlacements` lines of placements.
std::vector<Mat4> readPlacementFile(const std::filesystem::path& file, uint64_t maxPlacements);

// `count` placements scattered uniformly over the rectangle [min.x, max.x] x
// [min.y, max.y] of the xz plane at height `height`, each turned by a yaw
// uniform in [yawMin, yawMax] degrees about +y and scaled uniformly in
// [scaleMin, scaleMax]. The same seed gives the same placements on every
// machine (Pcg32, one stream per array).
struct Scatter {
    uint64_t count = 0;
    uint64_t seed = 0;
    Vec2 min{0.0f}, max{0.0f};  // (x, z)
    float height = 0.0f;
    float yawMin = 0.0f, yawMax = 360.0f;
    float scaleMin = 1.0f, scaleMax = 1.0f;
};
std::vector<Mat4> scatterPlacements(const Scatter& scatter);

}  // namespace strahl::scene_detail
