#pragma once
// Keyframed motion: an affine transform given at n >= 2 keyframes equally
// spaced over frame time [0, 1] (keyframe k at time k / (n - 1)), linearly
// interpolated between them, entry by entry — what Embree does with a
// multi-segment motion-blurred instance (rtcSetGeometryTimeStepCount with one
// matrix per step), so that the naive tracer and shading, which evaluate it
// here, place the object where Embree traced it.
//
// Linear interpolation of matrices moves every point of the object along a
// straight line between its keyframe positions: exact for translation and
// scaling, while a rotation is followed along its chords (a point at radius r
// turning by an angle φ between two keyframes passes r(1 - cos(φ/2)) inside its
// arc at mid-segment: 1.7 % of r for 30°), so fast spins need more keyframes.

#include <span>
#include <vector>

#include "strahl/core/bounds.h"
#include "strahl/core/math.h"

namespace strahl {

// Where frame time `time` (clamped to [0, 1]) falls among `count` >= 2
// keyframes: between keyframe `index` and index + 1, at `fraction` of the
// way. Keyframe k covers segment [k, k + 1) of time · (count - 1), as Embree
// splits it (for instances and for the vertex time steps of deforming meshes).
struct KeyframeSegment {
    size_t index = 0;
    float fraction = 0.0f;
};
KeyframeSegment keyframeSegment(size_t count, float time);

// The transform at frame time `time`: keyframeSegment's two keyframes, blended.
Mat4 keyframeAt(std::span<const Mat4> keys, float time);

// A motion given by its start and end transforms that turns rotations as
// rotations (pbrt-v4's AnimatedTransform; Shoemake and Duff 1992): each is
// split as M = T R S — translation, the rotation of M's polar decomposition,
// and the stretch S = R⁻¹ M — and at fraction f, T and S are interpolated
// linearly and R by spherical linear interpolation. Sampled as keyframes
// (first `start`, last `end`), one per at most maxStepRadians of rotation
// (at least 2, at most kMaxKeyframes), so that keyframeAt follows the arc to
// within its chord error. A transform that mirrors (negative determinant) has
// no rotation quaternion: then just {start, end}.
inline constexpr size_t kMaxKeyframes = 129;  // Embree's RTC_MAX_TIME_STEP_COUNT
std::vector<Mat4> rotationAwareKeyframes(const glm::dmat4& start, const glm::dmat4& end, double maxStepRadians);

// A box holding `bounds` transformed at every time: each point moves on
// straight segments between its keyframe images, so the keyframes' boxes
// bound it.
Bounds3 keyframeBounds(std::span<const Mat4> keys, const Bounds3& bounds);

}  // namespace strahl
