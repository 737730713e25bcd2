#pragma once
// The first root of F(t) = f(o + t·d) on a ray segment, found so that no root
// is missed: interval isolation, then safeguarded Newton refinement.
//
// Isolation (Mitchell 1990; Knoll et al. 2009): evaluate F and F' over a
// segment T = [a, b] in interval arithmetic (one RayDual evaluation).
//   0 ∉ F(T)            no root in T: skip it — this is a proof, not a guess.
//   0 ∉ F'(T)           F is monotone on T: it has a root iff F(a), F(b) differ
//                       in sign, and Newton safeguarded by bisection converges
//                       to it quadratically.
//   width(T) ≤ tol      a root cannot be excluded at the resolution asked for:
//                       report the midpoint with error width/2 (this is how
//                       tangent hits and features thinner than tol are kept).
//   otherwise           split T in halves, nearer half first.
// Segments are visited depth first, nearer half first, so the first root
// reported is the nearest. A budget bounds the work on pathological functions;
// when it runs out the nearest segment still undecided is reported as a hit,
// because a spurious hit is visible and a hole is not.

#include <optional>

#include "strahl/geometry/implicit_surface.h"

namespace strahl {

struct ImplicitRoot {
    double t = 0.0;
    double tError = 0.0;  // |t - true root| ≤ tError
};

struct RootFinderStats {
    int segments = 0;   // interval evaluations
    int newtonSteps = 0;
};

// The smallest root of f(o + t·d) with t in [tmin, tmax], located to within
// `tolerance` in t. Never throws; NaN inputs give no root.
std::optional<ImplicitRoot> findFirstRoot(const ImplicitSurface& f, const DVec3& o, const DVec3& d,
                                          double tmin, double tmax, double tolerance,
                                          RootFinderStats* stats = nullptr) noexcept;

// Refines a bracketed root of F on [a, b] (F(a) and F(b) of opposite signs or
// zero) by Newton's method, falling back to bisection whenever a Newton step
// leaves the bracket.
ImplicitRoot refineRoot(const ImplicitSurface& f, const DVec3& o, const DVec3& d, double a,
                        double b, double fa, double fb, RootFinderStats* stats = nullptr) noexcept;

}  // namespace strahl
