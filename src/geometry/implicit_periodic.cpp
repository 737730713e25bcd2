// "gyroid", "schwarz_p", "schwarz_d", "neovius": triply periodic minimal-surface
// approximations (implicit_builtins.h has their formulas). Unbounded: the
// shape needs a box.
// docs/implicit-surfaces.md has the derivations.
//
//   key         value                                          default
//   period      > 0, the cell size                              1
//   level       the level set                                   0
//   thickness   >= 0; > 0 makes the solid sheet |g| = thickness  0

#include <array>
#include <memory>
#include <string_view>
#include <vector>

#include "implicit_builtin.h"

namespace strahl::implicit_detail {

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

ImplicitSurfacePtr makePeriodicSurface(PeriodicSurface kind, double period, double level,
                                       double thickness) {
    implicit_detail::requirePositive("period", period);
    implicit_detail::requireFinite("level", level);
    implicit_detail::requireFinite("thickness", thickness);
    if (thickness < 0.0) fail("parameter 'thickness' must be ≥ 0 (got ", thickness, ")");
    return std::make_shared<implicit_detail::Periodic>(kind, period, level, thickness);
}

namespace {

ImplicitSurfacePtr parseImplicitPeriodic(const SurfaceParameters& p) {
    p.requireKeys({"type", "transform", "period", "level", "thickness"});
    const std::string_view type = p.type();
    const PeriodicSurface kind = type == "gyroid"      ? PeriodicSurface::Gyroid
                                 : type == "schwarz_p" ? PeriodicSurface::SchwarzP
                                 : type == "schwarz_d" ? PeriodicSurface::SchwarzD
                                                       : PeriodicSurface::Neovius;
    const double period = p.number("period", 1.0), level = p.number("level", 0.0);
    const double thickness = p.number("thickness", 0.0);
    return p.checked([&] { return makePeriodicSurface(kind, period, level, thickness); });
}

constexpr std::array<std::string_view, 4> kImplicitPeriodicNames = {"gyroid", "schwarz_p",
                                                                    "schwarz_d", "neovius"};

}  // namespace

extern const ImplicitKind kImplicitPeriodic;
const ImplicitKind kImplicitPeriodic{kImplicitPeriodicNames, &parseImplicitPeriodic};

}  // namespace strahl
