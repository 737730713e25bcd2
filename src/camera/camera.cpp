#include "strahl/camera/camera.h"

#include <immintrin.h>  // SSE: the packet rays' square roots (x86-64 only, as Embree's packets)

#include <cmath>

#include "strahl/core/error.h"
#include "strahl/core/sampling.h"

namespace strahl {

CameraFrame CameraFrame::fromBackUp(const Vec3& eye, const Vec3& back, const Vec3& up) {
    const float backLength = glm::length(back);
    if (!(backLength > 0.0f) || !std::isfinite(backLength))
        fail("camera: the back (w) direction must be a finite non-zero vector");
    CameraFrame f;
    f.e = eye;
    f.w = back / backLength;
    // u = up x w, normalised; the hint need not be orthogonal to w, only not parallel.
    const Vec3 u = glm::cross(up, f.w);
    const float uLength = glm::length(u);
    // sin(angle(up, w)) below ~1e-6 leaves u dominated by rounding: reject it.
    if (!(uLength > 1e-6f * glm::length(up)))
        fail("camera: the up vector is zero or parallel to the viewing direction");
    f.u = u / uLength;
    f.v = glm::cross(f.w, f.u);  // completes the right-handed frame, so u = v x w
    return f;
}

CameraFrame CameraFrame::lookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
    if (eye == target) fail("camera: eye and look_at are the same point");
    return fromBackUp(eye, eye - target, up);
}

Camera::Camera(const CameraFrame& frame, Projection projection, ImageWindow window,
               float focalDistance, int nx, int ny, const ThinLens& lens)
    : frame_(frame),
      projection_(projection),
      window_(window),
      d_(focalDistance),
      nx_(nx),
      ny_(ny),
      du_((window.r - window.l) / static_cast<float>(nx)),
      dv_((window.b - window.t) / static_cast<float>(ny)),
      lensRadius_(lens.apertureRadius),
      focus_(lens.focusDistance.value_or(focalDistance)) {
    if (nx <= 0 || ny <= 0) fail("camera: image size must be positive, got ", nx, "x", ny);
    if (!(window.l < 0.0f && 0.0f < window.r && window.b < 0.0f && 0.0f < window.t))
        fail("camera: the image window must satisfy l < 0 < r and b < 0 < t");
    if (!(focalDistance > 0.0f) || !std::isfinite(focalDistance))
        fail("camera: the focal distance must be positive and finite");
    if (!(lensRadius_ >= 0.0f) || !std::isfinite(lensRadius_))
        fail("camera: the aperture radius must be finite and >= 0 (0 is a pinhole), got ",
             lensRadius_);
    if (!(focus_ > 0.0f) || !std::isfinite(focus_))
        fail("camera: the focus distance must be positive and finite, got ", focus_);
}

void Camera::setShutter(const Shutter& shutter) {
    if (!(0.0f <= shutter.open && shutter.open <= shutter.close && shutter.close <= 1.0f))
        fail("camera: the shutter must open and close within the frame, 0 <= open <= close <= 1, got [",
             shutter.open, ", ", shutter.close, "]");
    shutter_ = shutter;
}

ImageWindow Camera::windowFromFov(float fovY, float focalDistance, int nx, int ny) {
    ImageWindow w;
    w.t = focalDistance * std::tan(0.5f * fovY);
    w.b = -w.t;
    w.r = w.t * static_cast<float>(nx) / static_cast<float>(ny);
    w.l = -w.r;
    return w;
}

Ray Camera::generateRay(float x, float y) const {
    const float u = window_.l + du_ * x;  // = l + (r - l) x / nx
    const float v = window_.t + dv_ * y;  // = t + (b - t) y / ny
    Ray ray;
    if (projection_ == Projection::Orthographic) {
        ray.origin = frame_.e + u * frame_.u + v * frame_.v;
        ray.dir = -frame_.w;
    } else {
        const Vec3 onPlane = -d_ * frame_.w + u * frame_.u + v * frame_.v;
        ray.origin = frame_.e + onPlane;
        ray.dir = glm::normalize(onPlane);
    }
    ray.tnear = 0.0f;
    ray.tfar = kInfinity;
    return ray;
}

Ray Camera::generateRay(float x, float y, const Vec2& lensSample) const {
    // The pinhole takes the unchanged code path, so its rays stay bit-identical.
    if (lensRadius_ == 0.0f) return generateRay(x, y);
    const Vec2 disk = lensRadius_ * sampleConcentricDisk(lensSample);
    const Vec3 lens = disk.x * frame_.u + disk.y * frame_.v;  // L, relative to the lens centre
    const float u = window_.l + du_ * x;
    const float v = window_.t + dv_ * y;
    Ray ray;
    if (projection_ == Projection::Orthographic) {
        // Lens centred on the pinhole origin o; focus point o - f w.
        ray.origin = frame_.e + u * frame_.u + v * frame_.v + lens;
        ray.dir = glm::normalize(-focus_ * frame_.w - lens);
    } else {
        // The pinhole ray e + lambda s meets the focus plane at lambda = f / d; the
        // ray from e + L to that point crosses the image plane at e + s + (1 - d/f) L.
        const Vec3 onPlane = -d_ * frame_.w + u * frame_.u + v * frame_.v;
        ray.origin = frame_.e + onPlane + (1.0f - d_ / focus_) * lens;
        ray.dir = glm::normalize((focus_ / d_) * onPlane - lens);
    }
    ray.tnear = 0.0f;
    ray.tfar = kInfinity;
    return ray;
}

template <int N>
void Camera::generatePinholeRays(const float (&x)[N], const float (&y)[N],
                                 RayHitPacket<N>& packet) const {
    const CameraFrame& f = frame_;
    float u[N], v[N];
    for (int i = 0; i < N; ++i) {
        u[i] = window_.l + du_ * x[i];
        v[i] = window_.t + dv_ * y[i];
    }
    if (projection_ == Projection::Orthographic) {
        for (int i = 0; i < N; ++i) {
            packet.org_x[i] = f.e.x + u[i] * f.u.x + v[i] * f.v.x;
            packet.org_y[i] = f.e.y + u[i] * f.u.y + v[i] * f.v.y;
            packet.org_z[i] = f.e.z + u[i] * f.u.z + v[i] * f.v.z;
            packet.dir_x[i] = -f.w.x;
            packet.dir_y[i] = -f.w.y;
            packet.dir_z[i] = -f.w.z;
        }
        return;
    }
    // glm's (-d W + u U + v V), e + s and normalize(s) = s * (1 / sqrt(dot(s, s))),
    // component by component, with dot summed as (x x + y y) + z z.
    const Vec3 back = -d_ * f.w;
    alignas(16) float sx[N], sy[N], sz[N], inverseLength[N];
    for (int i = 0; i < N; ++i) {
        sx[i] = back.x + u[i] * f.u.x + v[i] * f.v.x;
        sy[i] = back.y + u[i] * f.u.y + v[i] * f.v.y;
        sz[i] = back.z + u[i] * f.u.z + v[i] * f.v.z;
        packet.org_x[i] = f.e.x + sx[i];
        packet.org_y[i] = f.e.y + sy[i];
        packet.org_z[i] = f.e.z + sz[i];
        inverseLength[i] = sx[i] * sx[i] + sy[i] * sy[i] + sz[i] * sz[i];
    }
    // std::sqrt may set errno, which keeps the compiler from vectorising it;
    // SSE's square root and division round exactly as the scalar ones do.
    static_assert(N % 4 == 0);
    for (int i = 0; i < N; i += 4)
        _mm_store_ps(inverseLength + i,
                     _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(_mm_load_ps(inverseLength + i))));
    for (int i = 0; i < N; ++i) {
        packet.dir_x[i] = sx[i] * inverseLength[i];
        packet.dir_y[i] = sy[i] * inverseLength[i];
        packet.dir_z[i] = sz[i] * inverseLength[i];
    }
}

template void Camera::generatePinholeRays<8>(const float (&)[8], const float (&)[8],
                                              RayHitPacket<8>&) const;
template void Camera::generatePinholeRays<16>(const float (&)[16], const float (&)[16],
                                               RayHitPacket<16>&) const;

Mat4 Camera::worldToCamera() const {
    // Rows are u, v, w; the translation moves e to the origin. GLM is column-major.
    Mat4 m(1.0f);
    for (int c = 0; c < 3; ++c) {
        m[c][0] = frame_.u[c];
        m[c][1] = frame_.v[c];
        m[c][2] = frame_.w[c];
    }
    m[3] = Vec4(-glm::dot(frame_.u, frame_.e), -glm::dot(frame_.v, frame_.e),
                -glm::dot(frame_.w, frame_.e), 1.0f);
    return m;
}

}  // namespace strahl
