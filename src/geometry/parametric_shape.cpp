#include "strahl/geometry/parametric_shape.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "double_box.h"
#include "strahl/core/error.h"
#include "strahl/core/transform.h"

namespace strahl {

namespace {

using geometry_detail::clipToBox;
using geometry_detail::isFiniteD;
using geometry_detail::roundDown;
using geometry_detail::roundUp;

// Newton converges quadratically from a planar seed on a nearly flat
// sub-patch: 5-6 steps in practice. The cap only bounds the work on rays that
// miss (no root to converge to) and on the linear convergence at a pole.
constexpr int kMaxIterations = 24;
// Steps taken after ‖F‖ first falls below the tolerance, to bring the root to
// full double precision (so two neighbours computing it agree to ~1e-15).
constexpr int kPolishSteps = 2;
// A planar seed is worth trying if its barycentrics are within this much of
// the triangle: a curved sub-patch bulges past its corners' planes.
constexpr double kSeedMargin = 0.5;
// Iterates may leave the sub-patch by this fraction of its size on each side.
constexpr double kIterateMargin = 0.25;
// A rectangle whose corners' plane the ray crosses at a cosine below this
// (about 75 degrees from the normal) counts as grazed and is split, at most
// kMaxSplitDepth times: 2^-8 of a sub-patch separates the two roots of a ray
// passing within ~1e-6 of the sub-patch's size of a silhouette.
constexpr double kGrazingCosine = 0.25;
constexpr int kMaxSplitDepth = 8;
// Roots this close to a breakpoint (fraction of the sub-patch size) are
// snapped onto it before ownership is decided.
constexpr double kSnapFraction = 1e-9;

// Where o + t·d crosses the plane of triangle (a, b, c): t and the
// barycentrics of b and c. False if the ray runs parallel to the plane.
bool planeCrossing(const DVec3& o, const DVec3& d, const DVec3& a, const DVec3& b, const DVec3& c,
                   double& t, double& beta, double& gamma) {
    const DVec3 e1 = b - a, e2 = c - a;
    const DVec3 n = glm::cross(e1, e2);
    const double denom = glm::dot(n, d);
    const double nn = glm::dot(n, n);
    if (!(std::abs(denom) > 1e-12 * std::sqrt(nn) * glm::length(d))) return false;
    t = glm::dot(n, a - o) / denom;
    const DVec3 x = o + t * d - a;
    beta = glm::dot(glm::cross(x, e2), n) / nn;
    gamma = glm::dot(glm::cross(e1, x), n) / nn;
    return std::isfinite(t) && std::isfinite(beta) && std::isfinite(gamma);
}


}  // namespace

ParametricShape::ParametricShape(ParametricSurfacePtr surface, const Mat4& objectToWorld,
                                 const ParametricShapeOptions& options)
    : surface_(std::move(surface)) {
    const glm::dmat4 toWorld(objectToWorld);
    const double det = glm::determinant(glm::dmat3(toWorld));
    if (!std::isfinite(det) || det == 0.0) fail("the transform is singular or not finite");
    toWorld_ = toWorld;
    toObject_ = glm::inverse(toWorld);
    normalToWorld_ = glm::transpose(glm::dmat3(toObject_));
    // A flipped front: every normal the shape reports is negated.
    if (options.flipNormals) normalToWorld_ = -normalToWorld_;
    if (!(options.relativeTolerance > 0.0 && options.relativeTolerance < 1e-2))
        fail("the tolerance must lie in (0, 0.01)");

    const double extent = parametricExtent(*surface_);
    tolerance_ = options.relativeTolerance * extent;

    ParametricGridOptions gridOptions;
    gridOptions.initialSegmentsU = gridOptions.initialSegmentsV = options.initialSegments;
    gridOptions.maxSegments = options.maxSegments;
    gridOptions.maxChordError = options.flatness * extent;
    const ParametricGrid grid = buildParametricGrid(*surface_, gridOptions);
    const ParamDomain& dom = surface_->domain();

    for (uint32_t p = 0; p < grid.patches.size(); ++p) {
        const PatchGrid& g = grid.patches[p];
        for (size_t j = 0; j + 1 < g.v.size(); ++j)
            for (size_t i = 0; i + 1 < g.u.size(); ++i) {
                Cell c;
                c.patch = p;
                c.u0 = g.u[i];
                c.u1 = g.u[i + 1];
                c.v0 = g.v[j];
                c.v1 = g.v[j + 1];
                c.closedU = i + 2 == g.u.size() && !dom.periodicU;
                c.closedV = j + 2 == g.v.size() && !dom.periodicV;
                c.corner[0] = surface_->point(p, c.u0, c.v0);
                c.corner[1] = surface_->point(p, c.u1, c.v0);
                c.corner[2] = surface_->point(p, c.u1, c.v1);
                c.corner[3] = surface_->point(p, c.u0, c.v1);
                cells_.push_back(c);
            }
    }

    // Boxes: interval evaluation over each quarter of the sub-patch (tighter
    // than over the whole), grown by the tolerance, mapped to world space by
    // the eight corners and rounded outwards to float.
    worldBounds_.reserve(cells_.size());
    for (Cell& c : cells_) {
        DVec3 blo(num::kInf), bhi(-num::kInf);
        const double um = 0.5 * (c.u0 + c.u1), vm = 0.5 * (c.v0 + c.v1);
        for (const auto& [ua, ub] : {std::pair{c.u0, um}, std::pair{um, c.u1}})
            for (const auto& [va, vb] : {std::pair{c.v0, vm}, std::pair{vm, c.v1}}) {
                const Point3<num::Interval> r =
                    surface_->evaluate(c.patch, num::Interval(ua, ub), num::Interval(va, vb));
                blo = glm::min(blo, DVec3(r.x.lo, r.y.lo, r.z.lo));
                bhi = glm::max(bhi, DVec3(r.x.hi, r.y.hi, r.z.hi));
            }
        blo -= tolerance_;
        bhi += tolerance_;
        c.boxMin = blo;
        c.boxMax = bhi;
        if (!isFiniteD(blo) || !isFiniteD(bhi))
            fail(surface_->describe(), ": not finite over (u, v) in [", c.u0, ", ", c.u1, "] x [",
                 c.v0, ", ", c.v1, "]");
        DVec3 wlo(num::kInf), whi(-num::kInf);
        for (int k = 0; k < 8; ++k) {
            const DVec3 x((k & 1) ? bhi.x : blo.x, (k & 2) ? bhi.y : blo.y, (k & 4) ? bhi.z : blo.z);
            const DVec3 w = DVec3(toWorld * glm::dvec4(x, 1.0));
            wlo = glm::min(wlo, w);
            whi = glm::max(whi, w);
        }
        if (!isFiniteD(wlo) || !isFiniteD(whi)) fail("the transformed surface is not finite");
        worldBounds_.push_back(Bounds3{roundDown(wlo), roundUp(whi)});
        bounds_.expand(worldBounds_.back());
    }
}

bool ParametricShape::owns(const Cell& cell, const Rect& rect, double& u, double& v) const noexcept {
    const ParamDomain& dom = surface_->domain();
    auto snap = [](double& x, double a, double b) {
        const double eps = kSnapFraction * (b - a);
        if (std::abs(x - a) <= eps) x = a;
        else if (std::abs(x - b) <= eps) x = b;
    };
    snap(u, cell.u0, cell.u1);
    snap(v, cell.v0, cell.v1);
    snap(u, rect.u0, rect.u1);
    snap(v, rect.v0, rect.v1);
    // Across a seam the root belongs to the sub-patch on the other side.
    if (dom.periodicU && (u < dom.u0 || u >= dom.u1)) {
        u = u >= dom.u1 ? (u == dom.u1 ? dom.u0 : u - dom.width()) : u + dom.width();
        if (dom.twistedU) v = dom.v0 + dom.v1 - v;
    }
    if (dom.periodicV && (v < dom.v0 || v >= dom.v1))
        v = v >= dom.v1 ? (v == dom.v1 ? dom.v0 : v - dom.height()) : v + dom.height();
    const bool inU = (u >= rect.u0 && u < rect.u1) || (rect.closedU && u == rect.u1);
    const bool inV = (v >= rect.v0 && v < rect.v1) || (rect.closedV && v == rect.v1);
    return inU && inV;
}

bool ParametricShape::solve(const Cell& cell, const Rect& rect, const DVec3& o, const DVec3& d,
                            double u, double v, double t, Root& root) const noexcept {
    const ParamDomain& dom = surface_->domain();
    const double du = kIterateMargin * (rect.u1 - rect.u0), dv = kIterateMargin * (rect.v1 - rect.v0);
    // Beyond a border that is not a seam f may be undefined (a formula's
    // domain), so iterates stop there.
    const double uLo = dom.periodicU ? rect.u0 - du : std::max(rect.u0 - du, dom.u0);
    const double uHi = dom.periodicU ? rect.u1 + du : std::min(rect.u1 + du, dom.u1);
    const double vLo = dom.periodicV ? rect.v0 - dv : std::max(rect.v0 - dv, dom.v0);
    const double vHi = dom.periodicV ? rect.v1 + dv : std::min(rect.v1 + dv, dom.v1);
    u = std::clamp(u, uLo, uHi);
    v = std::clamp(v, vLo, vHi);
    int polished = -1;  // steps taken since ‖F‖ fell below the tolerance
    for (int it = 0; it < kMaxIterations; ++it) {
        const SurfacePoint s = surface_->partials(cell.patch, u, v);
        const DVec3 F = o + t * d - s.p;
        const double residual = glm::length(F);
        if (!std::isfinite(residual)) return false;
        if (residual <= tolerance_) {
            if (++polished >= kPolishSteps || residual == 0.0) {
                root = Root{t, u, v};
                return true;
            }
        } else if (polished >= 0) {
            return false;  // polishing made it worse: rounding noise, not a root
        }
        const glm::dmat3 J(d, -s.dpdu, -s.dpdv);  // columns: ∂F/∂t, ∂F/∂u, ∂F/∂v
        const double det = glm::determinant(J);
        const double scale = glm::length(d) * glm::length(s.dpdu) * glm::length(s.dpdv);
        DVec3 step;
        if (std::abs(det) > 1e-10 * scale) {
            step = glm::inverse(J) * -F;
        } else {
            // Levenberg–Marquardt: damped normal equations stay solvable where
            // J loses rank (a pole: ∂φ f = 0; a grazing ray: d in the tangent plane).
            const glm::dmat3 JT = glm::transpose(J);
            glm::dmat3 A = JT * J;
            const double trace = A[0][0] + A[1][1] + A[2][2];
            for (int k = 0; k < 3; ++k) A[k][k] += 1e-3 * A[k][k] + 1e-12 * trace;
            if (!(glm::determinant(A) != 0.0)) return false;
            step = glm::inverse(A) * (JT * -F);
        }
        if (!isFiniteD(step)) return false;
        t += step.x;
        u = std::clamp(u + step.y, uLo, uHi);
        v = std::clamp(v + step.z, vLo, vHi);
    }
    return false;
}


void ParametricShape::search(const Cell& cell, const Rect& rect, const DVec3 (&corner)[4],
                             const DVec3& o, const DVec3& d, float tnear, Best& best,
                             int depth) const noexcept {
    // Seeds: the crossings with the planes of the two corner triangles, then
    // the centre should both fail.
    struct Seed {
        double t, u, v;
    };
    Seed seeds[3];
    int seedCount = 0;
    const double us[4] = {rect.u0, rect.u1, rect.u1, rect.u0};
    const double vs[4] = {rect.v0, rect.v0, rect.v1, rect.v1};
    for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        double t, beta, gamma;
        if (!planeCrossing(o, d, corner[tri[0]], corner[tri[1]], corner[tri[2]], t, beta, gamma)) continue;
        const double alpha = 1.0 - beta - gamma;
        if (alpha < -kSeedMargin || beta < -kSeedMargin || gamma < -kSeedMargin) continue;
        seeds[seedCount++] = {t, alpha * us[tri[0]] + beta * us[tri[1]] + gamma * us[tri[2]],
                              alpha * vs[tri[0]] + beta * vs[tri[1]] + gamma * vs[tri[2]]};
    }
    const double uc = 0.5 * (rect.u0 + rect.u1), vc = 0.5 * (rect.v0 + rect.v1);
    const int planarSeeds = seedCount;
    ++seedCount;  // the centre, made only if it is needed

    bool found = false;
    for (int s = 0; s < seedCount; ++s) {
        if (s == planarSeeds) {
            if (found) break;  // the centre only as a fallback
            const DVec3 centre = surface_->point(cell.patch, uc, vc);
            seeds[s] = {glm::dot(centre - o, d) / glm::dot(d, d), uc, vc};
        }
        Root root;
        if (!solve(cell, rect, o, d, seeds[s].u, seeds[s].v, seeds[s].t, root)) continue;
        const float t = static_cast<float>(root.t);
        if (!(t > tnear && t < best.t)) continue;
        if (!owns(cell, rect, root.u, root.v)) continue;
        best.root = root;
        best.t = t;
        best.found = found = true;
    }

    // A ray that grazes the rectangle may cross it twice, with both roots too
    // close for a planar seed to separate (a silhouette): split it in four and
    // search the quarters its box test lets through, nearest first. The
    // planar normal of the corners (their diagonals' cross product) tells.
    const DVec3 n = glm::cross(corner[2] - corner[0], corner[3] - corner[1]);
    const double cosine = std::abs(glm::dot(n, d)) / (glm::length(n) * glm::length(d));
    const bool grazing = !(cosine >= kGrazingCosine);
    if (depth >= kMaxSplitDepth || !grazing) return;
    struct Quarter {
        Rect rect;
        double entry;
    };
    Quarter quarters[4];
    int count = 0;
    const Rect parts[4] = {{rect.u0, uc, rect.v0, vc, false, false},
                           {uc, rect.u1, rect.v0, vc, rect.closedU, false},
                           {rect.u0, uc, vc, rect.v1, false, rect.closedV},
                           {uc, rect.u1, vc, rect.v1, rect.closedU, rect.closedV}};
    for (const Rect& part : parts) {
        const Point3<num::Interval> box =
            surface_->evaluate(cell.patch, num::Interval(part.u0, part.u1), num::Interval(part.v0, part.v1));
        const DVec3 lo = DVec3(box.x.lo, box.y.lo, box.z.lo) - tolerance_;
        const DVec3 hi = DVec3(box.x.hi, box.y.hi, box.z.hi) + tolerance_;
        double t0 = tnear, t1 = best.t;
        if (clipToBox(o, d, lo, hi, t0, t1)) quarters[count++] = {part, t0};
    }
    // Nearest first (insertion sort: at most four).
    for (int i = 1; i < count; ++i)
        for (int j = i; j > 0 && quarters[j].entry < quarters[j - 1].entry; --j)
            std::swap(quarters[j], quarters[j - 1]);
    for (int q = 0; q < count; ++q) {
        if (!(quarters[q].entry < best.t)) break;
        const Rect& part = quarters[q].rect;
        const DVec3 partCorner[4] = {surface_->point(cell.patch, part.u0, part.v0),
                                     surface_->point(cell.patch, part.u1, part.v0),
                                     surface_->point(cell.patch, part.u1, part.v1),
                                     surface_->point(cell.patch, part.u0, part.v1)};
        search(cell, part, partCorner, o, d, tnear, best, depth + 1);
    }
}

bool ParametricShape::intersect(const Ray& ray, uint32_t prim, Hit& hit) const noexcept {
    const Cell& cell = cells_[prim];
    const DVec3 o = DVec3(toObject_ * glm::dvec4(DVec3(ray.origin), 1.0));
    const DVec3 d = glm::dmat3(toObject_) * DVec3(ray.dir);
    // The accelerator tested the world box; the object box is tighter.
    double t0 = ray.tnear, t1 = ray.tfar;
    if (!clipToBox(o, d, cell.boxMin, cell.boxMax, t0, t1)) return false;
    Best best;
    best.t = ray.tfar;
    const Rect whole{cell.u0, cell.u1, cell.v0, cell.v1, cell.closedU, cell.closedV};
    search(cell, whole, cell.corner, o, d, ray.tnear, best, 0);
    if (!best.found) return false;

    const DVec3 n = surface_->normal(cell.patch, best.root.u, best.root.v);
    Vec3 Ng = Vec3(normalToWorld_ * n);
    if (!isFinite(Ng) || Ng == Vec3(0.0f)) Ng = -ray.dir;
    hit.t = best.t;
    hit.u = static_cast<float>((best.root.u - cell.u0) / (cell.u1 - cell.u0));
    hit.v = static_cast<float>((best.root.v - cell.v0) / (cell.v1 - cell.v0));
    hit.Ng = Ng;
    return true;
}

DVec3 ParametricShape::hitParameters(const Hit& hit) const {
    const Cell& cell = cells_[hit.primID];
    return DVec3(cell.u0 + static_cast<double>(hit.u) * (cell.u1 - cell.u0),
                 cell.v0 + static_cast<double>(hit.v) * (cell.v1 - cell.v0), cell.patch);
}

SurfaceInteraction ParametricShape::interaction(const Ray& ray, const Hit& hit) const {
    const DVec3 params = hitParameters(hit);
    const Cell& cell = cells_[hit.primID];
    const SurfacePoint s = surface_->partials(cell.patch, params.x, params.y);
    const DVec3 pWorld = DVec3(toWorld_ * glm::dvec4(s.p, 1.0));

    SurfaceInteraction si;
    si.p = Vec3(pWorld);
    // Error of p: the solver's tolerance, the float rounding of the stored local
    // (u, v) (half an ulp of a number in [0, 1], times the sub-patch's size and
    // the partials), both mapped by the transform, plus the rounding of p to
    // float and of the transform (gamma(3) of its magnitude).
    //
    // The tolerance is not an error of f(u, v) itself but the solver's
    // resolution, and secondary rays need it: Newton accepts a root once
    // ‖o + t·d − f(u, v)‖ <= tolerance_, so a ray spawned closer than that to
    // the surface can be accepted as hitting it again at t ≈ 0. The box must
    // therefore reach tolerance_ (object space) from p along the normal.
    // tolerance_ per object axis does, through the map: with L the linear part,
    // n the unit object normal and m = L⁻ᵀn/‖L⁻ᵀn‖ the unit world normal, the
    // world box e = |L|·(τ, τ, τ) has support along m of Σᵢ|mᵢ|eᵢ >= τ·|mᵀLn|
    // = τ/‖L⁻ᵀn‖ (as |nⱼ| <= 1), and a world step s·m moves the object point by
    // s·nᵀL⁻¹m = s·‖L⁻ᵀn‖ along n: at least τ. Summed in double and rounded up
    // so the float box is no smaller.
    const double paramError = 0x1p-24 * (glm::length(s.dpdu) * (cell.u1 - cell.u0) +
                                         glm::length(s.dpdv) * (cell.v1 - cell.v0));
    const glm::dmat3 linear(toWorld_);
    const glm::dmat3 absLinear(glm::abs(linear[0]), glm::abs(linear[1]), glm::abs(linear[2]));
    const DVec3 objectError(tolerance_ + paramError);
    si.pError = roundUp(absLinear * objectError +
                        static_cast<double>(gammaBound(3)) * glm::abs(DVec3(si.p)));
    // intersect() already mapped the exact normal at this root into hit.Ng.
    const float len = glm::length(hit.Ng);
    si.Ng = len > 0.0f && std::isfinite(len) ? hit.Ng / len : -glm::normalize(ray.dir);
    si.Ns = si.Ng;
    surface_->setTextureFrame(si, s, params.x, params.y, linear);
    si.materialSlot = 0;
    return si;
}

std::string ParametricShape::describe() const { return "parametric " + surface_->describe() + " (direct)"; }

size_t ParametricShape::memoryBytes() const {
    return sizeof(*this) + cells_.capacity() * sizeof(Cell) + worldBounds_.capacity() * sizeof(Bounds3);
}

}  // namespace strahl
