#pragma once
// Bézier patch files in the common ".bpt" text format:
//
//     32                 the number of patches
//     3 3                patch 0: its degrees in u and v (only "3 3", bicubic)
//     1.4 0 2.4          its 16 control points "x y z", row-major: point
//     ...                4i + j is P_ij, i along u, j along v (BezierPatch)
//     3 3                patch 1 ...
//
// Numbers are separated by blanks; blank lines and '#' comments are skipped.
// Any malformed, truncated, non-finite or surplus input throws strahl::Error
// with "file:line: what". The count on the first line is checked against the
// file size (every patch takes at least 100 bytes) before anything is
// allocated from it, so a file claiming 10^12 patches fails at once.
//
// scenes/data/teapot.bpt is Newell's Utah teapot in this format: the full
// 32-patch version (rim 4, body 8, handle 4, spout 4, lid 8, bottom 4), z up,
// about x ∈ [−3, 3.43], y ∈ [−2, 2], z ∈ [0, 3.15]. Its patches' ∂u f × ∂v f
// point into the pot on all 32 patches (flip the normals to face outwards).
// Make a surface from it with makeBezierPatchSet(loadBezierFile(file), name).

#include <filesystem>
#include <vector>

#include "strahl/geometry/bezier_patches.h"

namespace strahl {

std::vector<BezierPatch> loadBezierFile(const std::filesystem::path& file);

}  // namespace strahl
