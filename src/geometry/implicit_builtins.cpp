// The built-in implicit surfaces. Each is one template eval<T>() — the formula,
// evaluated in double, interval and dual arithmetic alike — plus a gradient
// written by hand, which the tests hold against automatic differentiation.

#include "strahl/geometry/implicit_builtins.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "strahl/core/error.h"

namespace strahl::implicit_detail {

using num::abs;
using num::cos;
using num::max;
using num::powi;
using num::powr;
using num::sin;
using num::sqr;
using num::sqrt;

void requireFinite(const char* name, double value) {
    if (!std::isfinite(value)) fail("parameter '", name, "' is not a finite number");
}
void requirePositive(const char* name, double value) {
    requireFinite(name, value);
    if (!(value > 0.0)) fail("parameter '", name, "' must be > 0 (got ", value, ")");
}

// Real roots of a t² + b t + c = 0 in increasing order, without the
// cancellation of the schoolbook formula: q = −(b + sign(b)·√Δ)/2 has no
// subtraction of near-equal numbers, and the roots are q/a and c/q (Press et
// al., Numerical Recipes §5.6). A vanishing `a` degrades to the linear root.
int solveQuadratic(double a, double b, double c, double discriminant, double roots[4]) {
    if (a == 0.0) {
        if (b == 0.0) return 0;
        roots[0] = -c / b;
        return 1;
    }
    if (discriminant < 0.0) return 0;
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    double t0 = q / a, t1 = q != 0.0 ? c / q : -t0;
    if (t0 > t1) std::swap(t0, t1);
    roots[0] = t0;
    roots[1] = t1;
    return 2;
}

// ---- sphere ---------------------------------------------------------------

class Sphere final : public ImplicitSurfaceOf<Sphere> {
public:
    explicit Sphere(double r) : r_(r) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        return sqr(p.x) + sqr(p.y) + sqr(p.z) - r_ * r_;
    }
    DVec3 gradient(const DVec3& x) const override { return 2.0 * x; }
    std::optional<Bounds3> bounds() const override {
        const float r = static_cast<float>(r_);
        return Bounds3{Vec3(-r), Vec3(r)};
    }
    bool hasClosedForm() const override { return true; }
    int closedFormRoots(const DVec3& o, const DVec3& d, double roots[4]) const override {
        // Δ/4 = (o·d)² − |d|²(|o|² − r²) loses every digit when the ray starts
        // far away; the equal form |d|²(r² − |o − (o·d/|d|²) d|²) measures the
        // distance of the ray to the centre directly (Haines et al., "Precision
        // Improvements for Ray/Sphere Intersection", Ray Tracing Gems ch. 7).
        const double a = glm::dot(d, d), halfB = glm::dot(o, d);
        const DVec3 closest = o - (halfB / a) * d;
        const double disc = a * (r_ * r_ - glm::dot(closest, closest));
        return solveQuadratic(a, 2.0 * halfB, glm::dot(o, o) - r_ * r_, 4.0 * disc, roots);
    }
    std::string describe() const override { return concat("sphere r=", r_); }

private:
    double r_;
};

// ---- quadric --------------------------------------------------------------

class Quadric final : public ImplicitSurfaceOf<Quadric> {
public:
    explicit Quadric(const QuadricCoefficients& q) : q_(q) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        return q_.xx * sqr(p.x) + q_.yy * sqr(p.y) + q_.zz * sqr(p.z) + q_.xy * p.x * p.y +
               q_.yz * p.y * p.z + q_.xz * p.x * p.z + q_.x * p.x + q_.y * p.y + q_.z * p.z + q_.c;
    }
    DVec3 gradient(const DVec3& v) const override {
        return DVec3(2 * q_.xx * v.x + q_.xy * v.y + q_.xz * v.z + q_.x,
                     2 * q_.yy * v.y + q_.xy * v.x + q_.yz * v.z + q_.y,
                     2 * q_.zz * v.z + q_.yz * v.y + q_.xz * v.x + q_.z);
    }
    std::optional<Bounds3> bounds() const override { return std::nullopt; }
    bool hasClosedForm() const override { return true; }
    int closedFormRoots(const DVec3& o, const DVec3& d, double roots[4]) const override {
        // f(o + t d) = a t² + b t + c with a = f₂(d) (the quadratic part at d),
        // b = ∇f(o)·d, c = f(o).
        const double a = q_.xx * d.x * d.x + q_.yy * d.y * d.y + q_.zz * d.z * d.z +
                         q_.xy * d.x * d.y + q_.yz * d.y * d.z + q_.xz * d.x * d.z;
        const double b = glm::dot(gradient(o), d);
        const double c = eval(Point3<double>{o.x, o.y, o.z});
        return solveQuadratic(a, b, c, b * b - 4.0 * a * c, roots);
    }
    std::string describe() const override { return "quadric"; }

private:
    QuadricCoefficients q_;
};

// ---- torus ----------------------------------------------------------------

// The quartic is intersected by the generic interval root finder rather than a
// closed-form quartic solver: Ferrari's formulas lose most digits exactly where
// rays graze the tube, while interval isolation + Newton is both robust and
// accurate to the tolerance asked for.
class Torus final : public ImplicitSurfaceOf<Torus> {
public:
    Torus(double R, double r) : R_(R), r_(r) {}

    // The quartic (x² + y² + z² + R² − r²)² − 4R²ρ², ρ = √(x² + y²), evaluated
    // in its factored form ((ρ − R)² + z² − r²)·((ρ + R)² + z² − r²): the same
    // polynomial, but without the cancellation of two large squares, which in
    // interval arithmetic made almost every cell of the box look like it holds
    // surface. The second factor is ≥ R² − r² > 0, so the zero set is the
    // first factor's: the tube around the circle ρ = R.
    template <class T>
    T eval(const Point3<T>& p) const {
        const T rho = sqrt(sqr(p.x) + sqr(p.y));
        const T z2 = sqr(p.z) - r_ * r_;
        return (sqr(rho - R_) + z2) * (sqr(rho + R_) + z2);
    }
    DVec3 gradient(const DVec3& v) const override {
        const double s = glm::dot(v, v) + R_ * R_ - r_ * r_;
        return DVec3(4.0 * v.x * s - 8.0 * R_ * R_ * v.x, 4.0 * v.y * s - 8.0 * R_ * R_ * v.y,
                     4.0 * v.z * s);
    }
    std::optional<Bounds3> bounds() const override {
        const float outer = static_cast<float>(R_ + r_), tube = static_cast<float>(r_);
        return Bounds3{Vec3(-outer, -outer, -tube), Vec3(outer, outer, tube)};
    }
    std::string describe() const override { return concat("torus R=", R_, " r=", r_); }

private:
    double R_, r_;
};

// ---- superellipsoid --------------------------------------------------------

class Superellipsoid final : public ImplicitSurfaceOf<Superellipsoid> {
public:
    Superellipsoid(const DVec3& radii, double e1, double e2)
        : radii_(radii), e1_(e1), e2_(e2), p_(2.0 / e2), q_(2.0 / e1), s_(e2 / e1) {}

    template <class T>
    T eval(const Point3<T>& v) const {
        const T planar = powr(abs(v.x / radii_.x), p_) + powr(abs(v.y / radii_.y), p_);
        return powr(planar, s_) + powr(abs(v.z / radii_.z), q_) - 1.0;
    }
    DVec3 gradient(const DVec3& v) const override {
        // d/dx |x/a|^p = p |x/a|^(p-1) sign(x) / a, zero at x = 0 for p > 1.
        auto term = [](double x, double a, double p) {
            if (x == 0.0) return 0.0;
            return p * std::pow(std::abs(x / a), p - 1.0) * (x > 0.0 ? 1.0 : -1.0) / a;
        };
        const double planar = std::pow(std::abs(v.x / radii_.x), p_) +
                              std::pow(std::abs(v.y / radii_.y), p_);
        const double outer = planar > 0.0 ? s_ * std::pow(planar, s_ - 1.0) : 0.0;
        return DVec3(outer * term(v.x, radii_.x, p_), outer * term(v.y, radii_.y, p_),
                     term(v.z, radii_.z, q_));
    }
    std::optional<Bounds3> bounds() const override {
        const Vec3 r(radii_);
        return Bounds3{-r, r};
    }
    std::string describe() const override {
        return concat("superellipsoid e1=", e1_, " e2=", e2_);
    }

private:
    DVec3 radii_;
    double e1_, e2_, p_, q_, s_;
};

// ---- blobs ----------------------------------------------------------------

class Blobs final : public ImplicitSurfaceOf<Blobs> {
public:
    Blobs(std::vector<Blob> blobs, double threshold)
        : blobs_(std::move(blobs)), threshold_(threshold) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        T field(0.0);
        for (const Blob& b : blobs_) {
            const T q = (sqr(p.x - b.center.x) + sqr(p.y - b.center.y) + sqr(p.z - b.center.z)) *
                        (1.0 / (b.radius * b.radius));
            field += b.strength * powi(max(T(0.0), 1.0 - q), 3);
        }
        return threshold_ - field;
    }
    DVec3 gradient(const DVec3& x) const override {
        // ∇(s (1 − ‖x−c‖²/R²)³) = −6 s (1 − q)² (x − c)/R², negated by f = T − Σ.
        DVec3 g(0.0);
        for (const Blob& b : blobs_) {
            const DVec3 rel = x - b.center;
            const double w = 1.0 - glm::dot(rel, rel) / (b.radius * b.radius);
            if (w > 0.0) g += 6.0 * b.strength * w * w / (b.radius * b.radius) * rel;
        }
        return g;
    }
    std::optional<Bounds3> bounds() const override {
        // Outside every ball the field is 0 and f = threshold > 0.
        Bounds3 box;
        for (const Blob& b : blobs_) {
            box.expand(Vec3(b.center - b.radius));
            box.expand(Vec3(b.center + b.radius));
        }
        return box;
    }
    std::string describe() const override {
        return concat("blobs n=", blobs_.size(), " threshold=", threshold_);
    }

private:
    std::vector<Blob> blobs_;
    double threshold_;
};

// ---- triply periodic surfaces ---------------------------------------------

class Periodic final : public ImplicitSurfaceOf<Periodic> {
public:
    Periodic(PeriodicSurface kind, double period, double level, double thickness)
        : kind_(kind), k_(2.0 * num::kPiD / period), period_(period), level_(level),
          thickness_(thickness) {}

    template <class T>
    T eval(const Point3<T>& p) const {
        const T g = levelFunction(p);
        return thickness_ > 0.0 ? abs(g) - thickness_ : g;
    }

    // g(x) − level, before the optional thickening into a sheet.
    template <class T>
    T levelFunction(const Point3<T>& p) const {
        const T x = k_ * p.x, y = k_ * p.y, z = k_ * p.z;
        T g(0.0);
        switch (kind_) {
        case PeriodicSurface::Gyroid:
            g = sin(x) * cos(y) + sin(y) * cos(z) + sin(z) * cos(x);
            break;
        case PeriodicSurface::SchwarzP:
            g = cos(x) + cos(y) + cos(z);
            break;
        case PeriodicSurface::SchwarzD:
            g = sin(x) * sin(y) * sin(z) + sin(x) * cos(y) * cos(z) + cos(x) * sin(y) * cos(z) +
                cos(x) * cos(y) * sin(z);
            break;
        case PeriodicSurface::Neovius:
            g = 3.0 * (cos(x) + cos(y) + cos(z)) + 4.0 * cos(x) * cos(y) * cos(z);
            break;
        }
        return g - level_;
    }
    DVec3 gradient(const DVec3& v) const override {
        const double x = k_ * v.x, y = k_ * v.y, z = k_ * v.z;
        const double sx = std::sin(x), sy = std::sin(y), sz = std::sin(z);
        const double cx = std::cos(x), cy = std::cos(y), cz = std::cos(z);
        DVec3 g(0.0);
        switch (kind_) {
        case PeriodicSurface::Gyroid:
            g = DVec3(cx * cy - sz * sx, cy * cz - sx * sy, cz * cx - sy * sz);
            break;
        case PeriodicSurface::SchwarzP:
            g = DVec3(-sx, -sy, -sz);
            break;
        case PeriodicSurface::SchwarzD:
            g = DVec3(cx * sy * sz + cx * cy * cz - sx * sy * cz - sx * cy * sz,
                      sx * cy * sz - sx * sy * cz + cx * cy * cz - cx * sy * sz,
                      sx * sy * cz - sx * cy * sz - cx * sy * sz + cx * cy * cz);
            break;
        case PeriodicSurface::Neovius:
            g = DVec3(-3.0 * sx - 4.0 * sx * cy * cz, -3.0 * sy - 4.0 * cx * sy * cz,
                      -3.0 * sz - 4.0 * cx * cy * sz);
            break;
        }
        g *= k_;
        if (thickness_ > 0.0) g *= num::signOf(levelFunction(Point3<double>{v.x, v.y, v.z}));
        return g;
    }
    std::optional<Bounds3> bounds() const override { return std::nullopt; }
    std::string describe() const override {
        static const char* names[] = {"gyroid", "schwarz_p", "schwarz_d", "neovius"};
        return concat(names[static_cast<int>(kind_)], " period=", period_, " level=", level_,
                      thickness_ > 0.0 ? concat(" thickness=", thickness_) : std::string());
    }

private:
    PeriodicSurface kind_;
    double k_, period_, level_, thickness_;
};

}  // namespace strahl::implicit_detail

namespace strahl {

using namespace implicit_detail;

ImplicitSurfacePtr makeImplicitSphere(double radius) {
    requirePositive("radius", radius);
    return std::make_shared<Sphere>(radius);
}

ImplicitSurfacePtr makeImplicitQuadric(const QuadricCoefficients& q) {
    const double all[] = {q.xx, q.yy, q.zz, q.xy, q.yz, q.xz, q.x, q.y, q.z, q.c};
    const char* names[] = {"xx", "yy", "zz", "xy", "yz", "xz", "x", "y", "z", "c"};
    bool anyNonZero = false;
    for (int i = 0; i < 10; ++i) {
        requireFinite(names[i], all[i]);
        anyNonZero = anyNonZero || (i < 9 && all[i] != 0.0);
    }
    if (!anyNonZero) fail("quadric coefficients are all zero apart from the constant");
    return std::make_shared<Quadric>(q);
}

ImplicitSurfacePtr makeImplicitTorus(double majorRadius, double minorRadius) {
    requirePositive("major_radius", majorRadius);
    requirePositive("minor_radius", minorRadius);
    return std::make_shared<Torus>(majorRadius, minorRadius);
}

ImplicitSurfacePtr makeSuperellipsoid(const DVec3& radii, double e1, double e2) {
    requirePositive("radii.x", radii.x);
    requirePositive("radii.y", radii.y);
    requirePositive("radii.z", radii.z);
    requirePositive("e1", e1);
    requirePositive("e2", e2);
    // Exponents 2/e must stay representable: below 0.01 the surface is a box to
    // within rounding and the powers overflow.
    if (e1 < 0.01 || e2 < 0.01 || e1 > 10.0 || e2 > 10.0)
        fail("superellipsoid exponents e1, e2 must lie in [0.01, 10]");
    return std::make_shared<Superellipsoid>(radii, e1, e2);
}

ImplicitSurfacePtr makeBlobs(std::vector<Blob> blobs, double threshold) {
    if (blobs.empty()) fail("blobs need at least one blob");
    requirePositive("threshold", threshold);
    for (const Blob& b : blobs) {
        requireFinite("center", b.center.x);
        requireFinite("center", b.center.y);
        requireFinite("center", b.center.z);
        requirePositive("radius", b.radius);
        requireFinite("strength", b.strength);
    }
    return std::make_shared<Blobs>(std::move(blobs), threshold);
}

ImplicitSurfacePtr makePeriodicSurface(PeriodicSurface kind, double period, double level,
                                       double thickness) {
    requirePositive("period", period);
    requireFinite("level", level);
    requireFinite("thickness", thickness);
    if (thickness < 0.0) fail("parameter 'thickness' must be ≥ 0 (got ", thickness, ")");
    return std::make_shared<Periodic>(kind, period, level, thickness);
}

}  // namespace strahl
