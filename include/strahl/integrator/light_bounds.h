#pragma once
// Bounds on where a group of lights is, which way it emits and how much: the
// node data of the light BVH (light_bvh.h), after Conty Estevez and Kulla,
// "Importance Sampling of Many Lights with Adaptive Tree Splitting" (2018),
// the scheme pbrt-v4 and Cycles use. docs/lights.md derives it.
//
// The emission is bounded by an orientation cone: every emitting surface's
// normal lies within angle thetaO of `axis`, and light leaves a surface at
// most thetaE away from its normal (pi/2 for a surface, the cone's width for
// a spot). So no light leaves the group at more than thetaO + thetaE from the
// axis. A two-sided group emits along -axis as well.

#include <optional>

#include "strahl/core/bounds.h"
#include "strahl/core/math.h"

namespace strahl {

struct Light;

struct LightBounds {
    Bounds3 box;                  // where the emitters are
    Vec3 axis{0.0f, 0.0f, 1.0f};  // unit
    float thetaO = kPi;           // normal spread around the axis, radians in [0, pi]
    float thetaE = 0.5f * kPi;    // emission spread around each normal, radians in [0, pi]
    float power = 0.0f;           // W (lightPower), > 0 for a light in the BVH
    bool twoSided = false;

    // An estimate of the light this group can send to a receiver at p with
    // unit normal n (n = 0: no surface, every direction counts): power x
    // cos(the smallest angle between the emission cone and the direction to
    // p) x cos(the smallest angle between n's line and the group) / d^2, with
    // d the distance to the box's centre (at least a tenth of its radius).
    // The angles widen by the angle the box subtends from p, so the result
    // is 0 only where no light of the group can reach p (the choice must
    // never miss a light that contributes); the distance is not a bound.
    float importance(const Vec3& p, const Vec3& n) const;
};

// LightBounds as the light BVH's walk evaluates it: the box as its centre and
// bounding-sphere radius, the cone's angles as cosines and sines, computed once
// when the tree is built. importance() is LightBounds::importance with the
// angle arithmetic done on cosines and sines (cos(a - b) = cos a cos b +
// sin a sin b, sines from square roots): no trigonometric function per visit
// (pbrt-v4's LightBounds::Importance works the same way). It agrees with the
// reference to rounding (tested).
struct ImportanceBounds {
    Vec3 center{0.0f};
    float radius = 0.0f;
    Vec3 axis{0.0f, 0.0f, 1.0f};
    float cosThetaO = -1.0f, sinThetaO = 0.0f, cosThetaE = 0.0f;
    float power = 0.0f;
    bool twoSided = false;

    ImportanceBounds() = default;
    explicit ImportanceBounds(const LightBounds& b);
    float importance(const Vec3& p, const Vec3& n) const;
};

// The bounds of both groups: the box and power add up, the cones merge into
// the smallest cone holding both (Conty Estevez and Kulla, algorithm 1).
LightBounds unite(const LightBounds& a, const LightBounds& b);

// The orientation part of the surface area orientation heuristic (the same
// paper, eq. 1): the solid-angle measure of the directions the cone emits
// into, weighted by the cosine to the nearest normal,
//   M = 2 pi (1 - cos thetaO)
//       + pi/2 (2 thetaW sin thetaO - cos(thetaO - 2 thetaW) - 2 thetaO sin thetaO + cos thetaO)
// with thetaW = min(thetaO + thetaE, pi).
float orientationMeasure(const LightBounds& b);

// The bounds of one light of a light set, or none for an infinite light
// (which the light BVH does not hold) and for one that emits nothing.
// `power` is its lightPower.
std::optional<LightBounds> boundsOf(const Light& light, float power);

}  // namespace strahl
