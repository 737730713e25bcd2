#pragma once
// A lat-long (equirectangular) radiance map and its importance-sampling
// distribution (pbrt-v3 13.6.7): piecewise constant in (u, v), weighted by
// luminance times sin(theta) so that sampling follows radiance per solid angle.
//
// Map space is right-handed with +y up. Texel (column x, row y), rows counted
// from the top, covers u in [x/w, (x+1)/w) and v in [y/h, (y+1)/h), and
//     theta = pi v        (polar angle from +y: the top row is the zenith)
//     phi   = 2 pi u
//     dir   = (-sin theta cos phi, cos theta, -sin theta sin phi)
// Inverse: u = 1/2 + atan2(z, x) / (2 pi), v = atan2(sqrt(x^2 + z^2), y) / pi.
// So the image centre (u = 1/2) maps to +x, the left and right edges (u = 0, 1)
// to -x, the column u = 1/4 to -z and u = 3/4 to +z. Seen from inside, facing
// +x with +y up, +z is to the right, so the image is not mirrored. This is the
// convention of Blender (where Poly Haven HDRIs are made: centre towards +x,
// sky up) under the usual z-up to y-up conversion (x, y, z) -> (x, z, -y), and
// that of three.js. docs/lights.md tabulates it.
//
// Where the rows sit (RowLayout): by default each texel is an area and its
// value sits at its centre, v = (y + 1/2)/h, as in every image texture. Some
// renderers (Mitsuba's envmap) stretch the rows from pole to pole instead:
// the top row's values on the zenith, the bottom row's on the nadir,
// v = y/(h - 1). Columns sit at their centres, u = (x + 1/2)/w, either way, and
// between values the map is bilinear.

#include <vector>

#include "strahl/core/distribution.h"
#include "strahl/core/math.h"

namespace strahl {

enum class RowLayout { Centred, PoleToPole };

class EnvironmentMap {
public:
    // width x height linear RGB texels, row-major from the top row. Throws
    // strahl::Error on an empty image, a size mismatch, or a non-finite or
    // negative texel (and for PoleToPole, fewer than two rows).
    EnvironmentMap(int width, int height, std::vector<Color> texels,
                   RowLayout rows = RowLayout::Centred);

    int width() const { return width_; }
    int height() const { return height_; }
    const Color& texel(int x, int y) const {
        return texels_[static_cast<size_t>(y) * static_cast<size_t>(width_) +
                       static_cast<size_t>(x)];
    }

    RowLayout rows() const { return rows_; }

    // Bilinearly interpolated radiance towards a map-space direction (need not be
    // unit): texel values sit where the row layout puts them; columns wrap
    // around in phi, rows clamp at the poles.
    Color lookup(const Vec3& dir) const;
    // A unit map-space direction with density proportional to the luminance of
    // the bilinear radiance averaged over each texel, times solid angle; pdf is
    // per unit solid angle, 0 only where lookup() is black.
    Vec3 sample(const Vec2& u, float& pdf) const;
    float pdf(const Vec3& dir) const;
    // Mean radiance over the sphere (texels weighted by their solid angle), for
    // power estimates.
    Color average() const;

    // The map-space direction of (u, v) and back (the convention above).
    static Vec3 direction(const Vec2& uv);
    static Vec2 uv(const Vec3& dir);

private:
    int width_, height_;
    std::vector<Color> texels_;
    RowLayout rows_;
    Distribution2D distribution_;
};

}  // namespace strahl
