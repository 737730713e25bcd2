#include "strahl/geometry/parametric_builtins.h"

#include <cmath>
#include <memory>

#include "strahl/core/error.h"

namespace strahl {

namespace {

using num::cos;
using num::sin;

constexpr double kTwoPi = 2.0 * num::kPiD;

void requirePositive(const char* name, double value) {
    if (!(std::isfinite(value) && value > 0.0))
        fail(name, " must be a positive finite number, got ", value);
}

class Sphere final : public ParametricSurfaceOf<Sphere> {
public:
    explicit Sphere(double r) : r_(r) { domain_ = {0.0, num::kPiD, 0.0, kTwoPi, false, true}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& rho, const T& phi) const {
        const T s = sin(rho);
        return {T(r_) * s * cos(phi), T(r_) * s * sin(phi), T(r_) * cos(rho)};
    }
    SurfacePoint partials(uint32_t, double rho, double phi) const override {
        const double sr = std::sin(rho), cr = std::cos(rho), sp = std::sin(phi), cp = std::cos(phi);
        return {r_ * DVec3(sr * cp, sr * sp, cr), r_ * DVec3(cr * cp, cr * sp, -sr),
                r_ * DVec3(-sr * sp, sr * cp, 0.0)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("sphere r=", r_); }

private:
    double r_;
    ParamDomain domain_;
};

class Torus final : public ParametricSurfaceOf<Torus> {
public:
    Torus(double R, double r) : R_(R), r_(r) { domain_ = {0.0, kTwoPi, 0.0, kTwoPi, true, true}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& v) const {
        const T ring = T(R_) + T(r_) * cos(v);
        return {ring * cos(u), ring * sin(u), T(r_) * sin(v)};
    }
    SurfacePoint partials(uint32_t, double u, double v) const override {
        const double su = std::sin(u), cu = std::cos(u), sv = std::sin(v), cv = std::cos(v);
        const double ring = R_ + r_ * cv;
        return {DVec3(ring * cu, ring * su, r_ * sv), DVec3(-ring * su, ring * cu, 0.0),
                DVec3(-r_ * sv * cu, -r_ * sv * su, r_ * cv)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("torus R=", R_, " r=", r_); }

private:
    double R_, r_;
    ParamDomain domain_;
};

class Cylinder final : public ParametricSurfaceOf<Cylinder> {
public:
    Cylinder(double r, double z0, double z1) : r_(r) { domain_ = {0.0, kTwoPi, z0, z1, true, false}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& phi, const T& z) const {
        return {T(r_) * cos(phi), T(r_) * sin(phi), z};
    }
    SurfacePoint partials(uint32_t, double phi, double z) const override {
        const double s = std::sin(phi), c = std::cos(phi);
        return {DVec3(r_ * c, r_ * s, z), DVec3(-r_ * s, r_ * c, 0.0), DVec3(0.0, 0.0, 1.0)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override {
        return concat("cylinder r=", r_, " z=[", domain_.v0, ", ", domain_.v1, "]");
    }

private:
    double r_;
    ParamDomain domain_;
};

class Cone final : public ParametricSurfaceOf<Cone> {
public:
    Cone(double r, double h) : r_(r), h_(h) { domain_ = {0.0, kTwoPi, 0.0, 1.0, true, false}; }

    template <class T>
    Point3<T> eval(uint32_t, const T& phi, const T& s) const {
        const T radius = T(r_) * (T(1.0) - s);
        return {radius * cos(phi), radius * sin(phi), T(h_) * s};
    }
    SurfacePoint partials(uint32_t, double phi, double s) const override {
        const double sp = std::sin(phi), cp = std::cos(phi), radius = r_ * (1.0 - s);
        return {DVec3(radius * cp, radius * sp, h_ * s), DVec3(-radius * sp, radius * cp, 0.0),
                DVec3(-r_ * cp, -r_ * sp, h_)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override { return concat("cone r=", r_, " h=", h_); }

private:
    double r_, h_;
    ParamDomain domain_;
};

class Mobius final : public ParametricSurfaceOf<Mobius> {
public:
    Mobius(double R, double w) : R_(R) {
        domain_ = {0.0, kTwoPi, -w, w, true, false};
        domain_.twistedU = true;
    }

    template <class T>
    Point3<T> eval(uint32_t, const T& u, const T& s) const {
        const T half = T(0.5) * u;
        const T ring = T(R_) + s * cos(half);
        return {ring * cos(u), ring * sin(u), s * sin(half)};
    }
    SurfacePoint partials(uint32_t, double u, double s) const override {
        const double su = std::sin(u), cu = std::cos(u);
        const double sh = std::sin(0.5 * u), ch = std::cos(0.5 * u);
        const double ring = R_ + s * ch;
        // d(ring)/du = −s sin(u/2)/2
        const double dring = -0.5 * s * sh;
        return {DVec3(ring * cu, ring * su, s * sh),
                DVec3(dring * cu - ring * su, dring * su + ring * cu, 0.5 * s * ch),
                DVec3(ch * cu, ch * su, sh)};
    }
    const ParamDomain& domain() const override { return domain_; }
    std::string describe() const override {
        return concat("mobius R=", R_, " w=", domain_.v1);
    }

private:
    double R_;
    ParamDomain domain_;
};

}  // namespace

ParametricSurfacePtr makeParametricSphere(double radius) {
    requirePositive("radius", radius);
    return std::make_shared<Sphere>(radius);
}

ParametricSurfacePtr makeParametricTorus(double majorRadius, double minorRadius) {
    requirePositive("major_radius", majorRadius);
    requirePositive("minor_radius", minorRadius);
    if (!(minorRadius < majorRadius))
        fail("minor_radius (", minorRadius, ") must be below major_radius (", majorRadius,
             "): a self-intersecting torus has no single outside");
    return std::make_shared<Torus>(majorRadius, minorRadius);
}

ParametricSurfacePtr makeParametricCylinder(double radius, double zMin, double zMax) {
    requirePositive("radius", radius);
    if (!(std::isfinite(zMin) && std::isfinite(zMax) && zMin < zMax))
        fail("z_min must be below z_max, both finite (got ", zMin, " and ", zMax, ")");
    return std::make_shared<Cylinder>(radius, zMin, zMax);
}

ParametricSurfacePtr makeParametricCone(double radius, double height) {
    requirePositive("radius", radius);
    requirePositive("height", height);
    return std::make_shared<Cone>(radius, height);
}

ParametricSurfacePtr makeMobiusStrip(double radius, double halfWidth) {
    requirePositive("radius", radius);
    requirePositive("half_width", halfWidth);
    if (!(halfWidth < radius))
        fail("half_width (", halfWidth, ") must be below radius (", radius, ")");
    return std::make_shared<Mobius>(radius, halfWidth);
}

}  // namespace strahl
