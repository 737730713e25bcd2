#include "strahl/geometry/implicit_shape.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/matrix.hpp>

#include "double_box.h"
#include "strahl/core/error.h"
#include "strahl/geometry/implicit_root_finder.h"

namespace strahl {

namespace {

using geometry_detail::clipToBox;
using geometry_detail::isFiniteD;
using geometry_detail::roundDown;
using geometry_detail::roundUp;

// Finer grids cull more empty space but cost Embree primitives and build time;
// 32³ = 32768 candidate cells keeps the build in milliseconds while a typical
// surface keeps only a few thousand of them.
constexpr int kDefaultCells = 32;
constexpr int kMaxCells = 256;

}  // namespace

ImplicitShape::ImplicitShape(ImplicitSurfacePtr surface, const Mat4& objectToWorld,
                             const ImplicitShapeOptions& options)
    : surface_(std::move(surface)) {
    const glm::dmat4 toWorld(objectToWorld);
    const double det = glm::determinant(glm::dmat3(toWorld));
    if (!std::isfinite(det) || det == 0.0)
        fail("the transform is singular or not finite");
    toObject_ = glm::inverse(toWorld);
    toWorldLinear_ = glm::dmat3(toWorld);
    normalToWorld_ = glm::transpose(glm::dmat3(toObject_));

    // Domain: the surface's own bounds clipped to the box.
    std::optional<Bounds3> domain = surface_->bounds();
    if (options.box) {
        if (domain) {
            domain->min = glm::max(domain->min, options.box->min);
            domain->max = glm::min(domain->max, options.box->max);
        } else {
            domain = options.box;
        }
    }
    if (!domain)
        fail("the surface ", surface_->describe(), " is unbounded: give the shape a \"box\"");
    if (!isFinite(domain->min) || !isFinite(domain->max))
        fail("the surface's domain is not finite");
    if (domain->empty())
        fail("the surface ", surface_->describe(),
             " has no point inside the shape's box (they do not overlap)");
    domainMin_ = DVec3(domain->min);
    domainMax_ = DVec3(domain->max);
    const DVec3 extent = domainMax_ - domainMin_;
    if (!(options.relativeTolerance > 0.0 && options.relativeTolerance < 1.0))
        fail("the tolerance must lie in (0, 1)");
    tolerance_ = options.relativeTolerance * std::max(glm::length(extent), 1e-30);

    closedForm_ = surface_->hasClosedForm();
    const int n = options.cellsPerAxis > 0 ? options.cellsPerAxis : (closedForm_ ? 1 : kDefaultCells);
    if (n > kMaxCells) fail("at most ", kMaxCells, " cells per axis (got ", n, ")");

    // Keep the cells the interval range cannot clear of the surface. Each cell
    // is grown by the tolerance, so roots on a shared face belong to both
    // neighbours and float rounding of the clip never opens a crack.
    const DVec3 cellSize = extent / static_cast<double>(n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                Cell cell;
                cell.min = domainMin_ + DVec3(i, j, k) * cellSize - tolerance_;
                cell.max = domainMin_ + DVec3(i + 1, j + 1, k + 1) * cellSize + tolerance_;
                const num::Interval range = surface_->range(IntervalBox{
                    num::Interval(cell.min.x, cell.max.x), num::Interval(cell.min.y, cell.max.y),
                    num::Interval(cell.min.z, cell.max.z)});
                // A NaN range (0·inf inside f) cannot be cleared either.
                if (!(range.lo > 0.0 || range.hi < 0.0)) cells_.push_back(cell);
            }
    if (cells_.empty())
        fail("the surface ", surface_->describe(), " has no point inside its domain");

    // A function that is infinite or NaN wherever it is evaluated (1/(x - x) is
    // +inf everywhere) has no surface to find, yet its interval ranges, which
    // span (-inf, inf), clear no cell. Sampling the centres of up to 4096 kept
    // cells, spread over all of them, tells it apart from a function with
    // isolated singularities; the first finite value ends the scan.
    const size_t stride = std::max<size_t>(1, cells_.size() / 4096);
    bool finiteSomewhere = false;
    for (size_t c = 0; c < cells_.size() && !finiteSomewhere; c += stride)
        finiteSomewhere = std::isfinite(surface_->value(0.5 * (cells_[c].min + cells_[c].max)));
    if (!finiteSomewhere) {
        const DVec3 p = 0.5 * (cells_[0].min + cells_[0].max);
        const double f = surface_->value(p);
        fail("the surface ", surface_->describe(), " is not finite anywhere in its domain (",
             std::isnan(f) ? std::string("NaN") : concat(f), " at (", p.x, ", ", p.y, ", ", p.z,
             ") and at every other point sampled)");
    }

    // World boxes: the eight transformed corners, rounded outwards to float.
    worldBounds_.reserve(cells_.size());
    for (const Cell& c : cells_) {
        DVec3 lo(num::kInf), hi(-num::kInf);
        for (int corner = 0; corner < 8; ++corner) {
            const DVec3 p((corner & 1) ? c.max.x : c.min.x, (corner & 2) ? c.max.y : c.min.y,
                          (corner & 4) ? c.max.z : c.min.z);
            const DVec3 w = DVec3(toWorld * glm::dvec4(p, 1.0));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
        if (!isFiniteD(lo) || !isFiniteD(hi)) fail("the transformed surface is not finite");
        worldBounds_.push_back(Bounds3{roundDown(lo), roundUp(hi)});
        bounds_.expand(worldBounds_.back());
    }
}

bool ImplicitShape::intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept {
    const Cell& cell = cells_[prim];
    const DVec3 o = DVec3(toObject_ * glm::dvec4(DVec3(ray.origin), 1.0));
    const DVec3 d = glm::dmat3(toObject_) * DVec3(ray.dir);
    double t0 = ray.tnear, t1 = ray.tfar;
    if (!clipToBox(o, d, cell.min, cell.max, t0, t1)) return false;

    std::optional<ImplicitRoot> root =
        closedForm_ ? closedFormRoot(ray, o, d, t0, t1) : searchedRoot(ray, o, d, t0, t1);
    if (!root) return false;

    const DVec3 pObject = o + root->t * d;
    DVec3 gradient = surface_->gradient(pObject);
    if (closedForm_) {
        // The quadratic's rounding error, estimated by one Newton step.
        const double slope = glm::dot(gradient, d);
        const double step = slope != 0.0 ? surface_->value(pObject) / slope : 0.0;
        root->tError = 2.0 * std::abs(step) + 1e-12 * std::abs(root->t);
    }
    if (!isFiniteD(gradient) || gradient == DVec3(0.0)) gradient = -d;  // face the ray
    Vec3 Ng = Vec3(normalToWorld_ * gradient);
    if (!isFinite(Ng) || Ng == Vec3(0.0f)) Ng = -ray.dir;
    hit.t = static_cast<float>(root->t);
    hit.u = static_cast<float>(root->tError);
    hit.v = 0.0f;
    hit.Ng = Ng;
    return true;
}

std::optional<ImplicitRoot> ImplicitShape::closedFormRoot(const Ray& ray, const DVec3& o,
                                                          const DVec3& d, double t0,
                                                          double t1) const noexcept {
    double roots[4];
    const int count = surface_->closedFormRoots(o, d, roots);
    for (int i = 0; i < count; ++i) {
        const float t = static_cast<float>(roots[i]);
        if (roots[i] >= t0 && roots[i] <= t1 && t > ray.tnear && t < ray.tfar)
            return ImplicitRoot{roots[i], 0.0};
    }
    return std::nullopt;
}

std::optional<ImplicitRoot> ImplicitShape::searchedRoot(const Ray& ray, const DVec3& o,
                                                        const DVec3& d, double t0,
                                                        double t1) const noexcept {
    const double tolT = tolerance_ / glm::length(d);
    const double tfar = std::min(t1, static_cast<double>(ray.tfar));
    double from = std::max(t0, static_cast<double>(ray.tnear));
    // A root whose float t rounds onto tnear or tfar is outside the open
    // interval; search on past it (at most a few times: roots are isolated).
    for (int attempt = 0; attempt < 4; ++attempt) {
        const std::optional<ImplicitRoot> root = findFirstRoot(*surface_, o, d, from, tfar, tolT);
        if (!root) return std::nullopt;
        const float t = static_cast<float>(root->t);
        if (t > ray.tnear && t < ray.tfar) return root;
        if (t >= ray.tfar) return std::nullopt;
        from = root->t + std::max(root->tError, tolT);
    }
    return std::nullopt;
}

SurfaceInteraction ImplicitShape::interaction(const Ray& ray, const Hit& hit) const {
    SurfaceInteraction si;
    si.p = ray.at(hit.t);
    // Error of p: the float evaluation of o + t·d (gamma(3) per component), the
    // rounding of t to float (half an ulp, i.e. gamma(1)·|t|) and the root's own
    // uncertainty tError = hit.u, each scaled by |d|.
    const Vec3 absTd = glm::abs(hit.t * ray.dir);
    si.pError = gammaBound(3) * (glm::abs(ray.origin) + absTd) +
                glm::abs(ray.dir) * (hit.u + gammaBound(1) * std::abs(hit.t));
    if (!closedForm_) {
        // The root finder's resolution, which tError does not carry (a refined
        // root's is ~1e-15): findFirstRoot() reports as a hit any segment of
        // width <= tolerance_/‖d‖ that interval arithmetic cannot clear of the
        // surface (that is how tangent hits are kept), so a ray spawned closer
        // than tolerance_ to the surface can find it again at t ≈ 0 — and not
        // only at grazing angles, as interval bounds are loose. The box must
        // reach tolerance_ (object space) from p along the normal. tolerance_
        // per object axis mapped by |L| (L: objectToWorld's linear part) does:
        // with n the unit object normal and m = L⁻ᵀn/‖L⁻ᵀn‖ the world one, the
        // box's support along m is Σᵢ|mᵢ|(|L|·τ)ᵢ >= τ·|mᵀLn| = τ/‖L⁻ᵀn‖ (as
        // |nⱼ| <= 1), and a world step s·m moves the object point s·‖L⁻ᵀn‖
        // along n: at least τ. Summed in double, rounded up to float. (Closed
        // forms have no resolution limit: their tError is the whole error.)
        const glm::dmat3& L = toWorldLinear_;
        const glm::dmat3 absL(glm::abs(L[0]), glm::abs(L[1]), glm::abs(L[2]));
        si.pError = roundUp(DVec3(si.pError) + absL * DVec3(tolerance_));
    }
    const float len = glm::length(hit.Ng);
    si.Ng = len > 0.0f ? hit.Ng / len : -glm::normalize(ray.dir);
    si.Ns = si.Ng;
    // Spherical coordinates of the object-space point, a usable default uv.
    const DVec3 o = DVec3(toObject_ * glm::dvec4(DVec3(si.p), 1.0));
    const DVec3 c = 0.5 * (domainMin_ + domainMax_);
    const DVec3 r = o - c;
    si.uv = Vec2(static_cast<float>(0.5 + std::atan2(r.y, r.x) / (2.0 * num::kPiD)),
                 static_cast<float>(std::acos(std::clamp(r.z / std::max(glm::length(r), 1e-300),
                                                         -1.0, 1.0)) / num::kPiD));
    si.materialSlot = 0;
    return si;
}

std::string ImplicitShape::describe() const { return "implicit " + surface_->describe(); }

size_t ImplicitShape::memoryBytes() const {
    return sizeof(*this) + cells_.capacity() * sizeof(Cell) +
           worldBounds_.capacity() * sizeof(Bounds3);
}

}  // namespace strahl
