#pragma once
// Orthographic and perspective cameras exactly as Shirley & Marschner,
// "Fundamentals of Computer Graphics", 4.3 define them (derivation in
// docs/camera.md).
//
// Frame: eye e, right u, up v, back w, orthonormal and right-handed (u = v x w).
// Image window on the plane at focal distance d: l < 0 < r, b < 0 < t.
// Pixel (i, j), i from the left, j from the TOP row, has its centre at raster
// position (x, y) = (i + 0.5, j + 0.5), and
//     u = l + (r - l) x / nx,      v = t + (b - t) y / ny.
// Orthographic: origin e + u U + v V, direction -W.
// Perspective:  direction -d W + u U + v V, normalised; the origin is moved onto
//               the image plane, e - d W + u U + v V, so t is the Euclidean
//               distance from the image plane along the ray.
//
// Thin lens (depth of field, docs/camera.md "Thin lens"): a lens of radius R in
// the plane through e perpendicular to w, focused on the plane at distance f
// along -w. A lens sample maps to the disk point (dx, dy) (concentric map), the
// lens point is L = R (dx U + dy V), and s = -d W + u U + v V as above:
//   Perspective:  direction (f/d) s - L, normalised: through the point where the
//                 pinhole ray meets the focus plane. The origin is where this
//                 ray crosses the image plane (distance d along -w), e + s +
//                 (1 - d/f) L, so the same space is clipped as with the pinhole
//                 and t is again the distance from the image plane.
//   Orthographic: the lens is centred on each pinhole origin o = e + u U + v V
//                 (pbrt's orthographic lens): origin o + L, direction
//                 -f W - L, normalised, through the focus point o - f W.
// R = 0 (the default) is the pinhole camera: every ray is bit-identical to the
// one generateRay(x, y) gives, whatever the lens sample.

#include <optional>

#include "strahl/core/math.h"
#include "strahl/core/packet.h"
#include "strahl/core/ray.h"

namespace strahl {

enum class Projection { Orthographic, Perspective };

struct CameraFrame {
    Vec3 e{0.0f}, u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f}, w{0.0f, 0.0f, 1.0f};

    // From the eye, the back direction w (the camera looks along -w) and an up
    // hint that need not be orthogonal to w. Throws strahl::Error if w is zero
    // or parallel to up.
    static CameraFrame fromBackUp(const Vec3& eye, const Vec3& back, const Vec3& up);
    // From the eye and a point it looks at: w = normalise(eye - target).
    static CameraFrame lookAt(const Vec3& eye, const Vec3& target, const Vec3& up);
};

struct ImageWindow {
    float l = -1.0f, r = 1.0f, b = -1.0f, t = 1.0f;
};

// When the camera sees, in frame time (core/motion.h: 0 and 1 are a moving
// instance's first and last keyframe): a camera ray's time is uniform in
// [open, close]. open == close renders one instant, without motion blur.
struct Shutter {
    float open = 0.0f, close = 1.0f;

    float timeAt(float u) const { return open + (close - open) * u; }
};

// The lens of a depth-of-field camera (see the header comment).
struct ThinLens {
    float apertureRadius = 0.0f;         // R in world units, >= 0; 0 is a pinhole
    std::optional<float> focusDistance;  // f > 0 along -w from e; none: the focal distance d
};

class Camera {
public:
    // Throws strahl::Error for a non-positive size, a window without l < 0 < r and
    // b < 0 < t, a focal or focus distance that is not positive and finite, or a
    // negative or non-finite aperture radius.
    Camera(const CameraFrame& frame, Projection projection, ImageWindow window,
           float focalDistance, int nx, int ny, const ThinLens& lens = {});

    // The window of a perspective camera with vertical field of view fovY
    // (radians): t = d tan(fovY/2), b = -t, r = t nx/ny, l = -r.
    static ImageWindow windowFromFov(float fovY, float focalDistance, int nx, int ny);

    // The ray through continuous raster position (x, y) and the centre of the lens:
    // the pinhole ray of the header comment, whatever the aperture.
    Ray generateRay(float x, float y) const;
    // The thin-lens ray through raster position (x, y) and the lens point that
    // lensSample in [0, 1)^2 maps to; identical to generateRay(x, y) when the
    // aperture radius is 0.
    Ray generateRay(float x, float y, const Vec2& lensSample) const;

    // generateRay(x[i], y[i]) for every lane i of a packet, without a lens
    // (apertureRadius() must be 0): the origins and directions only (the
    // caller sets the rest of the lanes). The same arithmetic in the same
    // order as the scalar function, so every ray is bit for bit the one it
    // gives, written as loops over the lanes that the compiler vectorises
    // (the square root and division of the normalisation were most of a
    // camera ray's cost one lane at a time). Defined for N = 8 and 16.
    template <int N>
    void generatePinholeRays(const float (&x)[N], const float (&y)[N],
                             RayHitPacket<N>& packet) const;

    const CameraFrame& frame() const { return frame_; }
    Projection projection() const { return projection_; }
    const ImageWindow& window() const { return window_; }
    float focalDistance() const { return d_; }
    float apertureRadius() const { return lensRadius_; }
    float focusDistance() const { return focus_; }  // resolved: d if the lens gave none
    int width() const { return nx_; }
    int height() const { return ny_; }
    // Throws strahl::Error unless 0 <= open <= close <= 1.
    void setShutter(const Shutter& shutter);
    const Shutter& shutter() const { return shutter_; }
    Mat4 worldToCamera() const;  // rows u, v, w; camera looks down -z

private:
    CameraFrame frame_;
    Projection projection_;
    ImageWindow window_;
    float d_;
    int nx_, ny_;
    float du_, dv_;  // (r - l) / nx and (b - t) / ny, the window's extent per pixel
    float lensRadius_;
    float focus_;
    Shutter shutter_;
};

}  // namespace strahl
