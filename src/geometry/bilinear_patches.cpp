// Bilinear patches as Bézier patches by degree elevation; the math is in
// include/strahl/geometry/bilinear_patches.h.

#include "strahl/geometry/bilinear_patches.h"

#include <cmath>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/geometry/bezier_patches.h"

namespace strahl {

ParametricSurfacePtr makeBilinearPatchSet(std::span<const DVec3> positions, std::span<const uint32_t> corners,
                                          std::string name) {
    const std::string what = name.empty() ? std::string("bilinear patches") : concat("bilinear patches '", name, "'");
    if (corners.empty()) fail(what, ": no patches");
    if (corners.size() % 4 != 0) fail(what, ": ", corners.size(), " corner indices, not a multiple of 4");
    for (size_t i = 0; i < positions.size(); ++i) {
        const DVec3& p = positions[i];
        if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
            fail(what, ": position ", i, " is not finite (", p.x, " ", p.y, " ", p.z, ")");
    }
    std::vector<BezierPatch> patches(corners.size() / 4);
    for (size_t p = 0; p < patches.size(); ++p) {
        DVec3 q[4];  // q00, q10, q11, q01
        for (size_t k = 0; k < 4; ++k) {
            const uint32_t index = corners[4 * p + k];
            if (index >= positions.size())
                fail(what, ": corner ", k, " of patch ", p, " is index ", index, ", but there are only ",
                     positions.size(), " positions");
            q[k] = positions[index];
        }
        // P_ij = f(i/3, j/3), i along u (q00 -> q10), j along v (q00 -> q01).
        for (int i = 0; i < 4; ++i) {
            for (int j = 0; j < 4; ++j) {
                const double u = i / 3.0, v = j / 3.0;
                patches[p].points[size_t(4 * i + j)] =
                    (1.0 - u) * (1.0 - v) * q[0] + u * (1.0 - v) * q[1] + u * v * q[2] + (1.0 - u) * v * q[3];
            }
        }
        // The corners exactly as given (the sums above round them): patches
        // that share a corner meet there bit for bit.
        patches[p].points[0] = q[0];
        patches[p].points[12] = q[1];
        patches[p].points[15] = q[2];
        patches[p].points[3] = q[3];
    }
    return makeBezierPatchSet(std::move(patches), std::move(name));
}

bool bilinearPatchIsFlat(const DVec3& q00, const DVec3& q10, const DVec3& q11, const DVec3& q01,
                         double tolerance) {
    // The diagonals span the patch's mean plane; the twist d = q00 - q10 +
    // q11 - q01 moves f by u v d, so its component along the plane's normal
    // is how far the patch leaves the plane (at most |d.n| / 4, at the centre).
    const DVec3 a = q11 - q00, b = q01 - q10;
    const DVec3 n = glm::cross(a, b);
    const double nLength = glm::length(n);
    const double size = std::max(glm::length(a), glm::length(b));
    if (!(nLength > 0.0)) return false;  // degenerate: let the exact surface decide
    const DVec3 d = q00 - q10 + q11 - q01;
    return std::abs(glm::dot(d, n / nLength)) / 4.0 <= tolerance * size;
}

}  // namespace strahl
