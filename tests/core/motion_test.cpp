// Keyframed motion (core/motion.h): the interpolation Embree does for a
// multi-segment moving instance, and bounds that hold the whole motion.

#include "strahl/core/motion.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "strahl/core/transform.h"

namespace strahl {
namespace {

const Mat4 I(1.0f);

TEST(Motion, KeyframesAreHitExactlyAndSegmentsInterpolateLinearly) {
    const std::vector<Mat4> keys = {glm::translate(I, Vec3(0, 0, 0)), glm::translate(I, Vec3(2, 0, 0)),
                                    glm::translate(I, Vec3(2, 4, 0))};
    EXPECT_EQ(keyframeAt(keys, 0.0f), keys[0]);
    EXPECT_EQ(keyframeAt(keys, 0.5f), keys[1]);
    EXPECT_EQ(keyframeAt(keys, 1.0f), keys[2]);
    // Segment k covers [k, k + 1) of time * (n - 1).
    const Vec3 quarter = transformPoint(keyframeAt(keys, 0.25f), Vec3(0.0f));
    EXPECT_FLOAT_EQ(quarter.x, 1.0f);
    EXPECT_FLOAT_EQ(quarter.y, 0.0f);
    const Vec3 threeQuarters = transformPoint(keyframeAt(keys, 0.75f), Vec3(0.0f));
    EXPECT_FLOAT_EQ(threeQuarters.x, 2.0f);
    EXPECT_FLOAT_EQ(threeQuarters.y, 2.0f);
    // Outside the frame: clamped to its ends.
    EXPECT_EQ(keyframeAt(keys, -1.0f), keys[0]);
    EXPECT_EQ(keyframeAt(keys, 7.0f), keys[2]);
}

TEST(Motion, RotationsFollowTheirChords) {
    // A quarter turn in one segment: the point at radius 1 passes the chord's
    // midpoint, at distance cos(45°) from the axis, not the arc's.
    const std::vector<Mat4> keys = {I, glm::rotate(I, glm::radians(90.0f), Vec3(0, 0, 1))};
    const Vec3 mid = transformPoint(keyframeAt(keys, 0.5f), Vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(mid), std::sqrt(0.5f), 1e-6f);
}

TEST(Motion, KeyframeBoundsHoldEveryTime) {
    const std::vector<Mat4> keys = {glm::translate(I, Vec3(-1, 0, 0)),
                                    glm::rotate(I, 1.3f, Vec3(0.2f, 1, 0)) * glm::scale(I, Vec3(2, 1, 1)),
                                    glm::translate(I, Vec3(3, 1, -2)) * glm::rotate(I, 2.8f, Vec3(1, 0, 0))};
    const Bounds3 object{Vec3(-0.5f, -1, -0.25f), Vec3(0.5f, 1, 0.25f)};
    const Bounds3 swept = keyframeBounds(keys, object);
    for (int k = 0; k <= 100; ++k) {
        const Mat4 m = keyframeAt(keys, float(k) / 100.0f);
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p((corner & 1) ? object.max.x : object.min.x, (corner & 2) ? object.max.y : object.min.y,
                         (corner & 4) ? object.max.z : object.min.z);
            const Vec3 q = transformPoint(m, p);
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(q[a], swept.min[a] - 1e-5f);
                EXPECT_LE(q[a], swept.max[a] + 1e-5f);
            }
        }
    }
}

TEST(Motion, RotationAwareKeyframesTurnOnTheArc) {
    const glm::dmat4 start = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 1));
    const glm::dmat4 end = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(4, 0, 1)), glm::radians(120.0),
                                       glm::dvec3(0, 0, 1)) *
                           glm::scale(glm::dmat4(1.0), glm::dvec3(2.0));
    const std::vector<Mat4> keys = rotationAwareKeyframes(start, end, glm::radians(15.0));
    ASSERT_EQ(keys.size(), 9u) << "120 degrees in steps of at most 15";
    EXPECT_EQ(keys.front(), Mat4(start));
    EXPECT_EQ(keys.back(), Mat4(end));
    for (size_t k = 0; k < keys.size(); ++k) {
        const float f = float(k) / 8.0f;
        const Vec3 x = transformVector(keys[k], Vec3(1, 0, 0));
        EXPECT_NEAR(glm::length(x), 1.0f + f, 1e-5f) << "the scale grows linearly";
        EXPECT_NEAR(std::atan2(x.y, x.x), glm::radians(120.0f * f), 1e-5f) << "the angle too";
        EXPECT_NEAR(transformPoint(keys[k], Vec3(0.0f)).x, 4.0f * f, 1e-5f);
    }
    // Without rotation the two ends suffice; a mirror has no rotation to
    // turn, and keeps its two ends too.
    EXPECT_EQ(rotationAwareKeyframes(start, glm::translate(start, glm::dvec3(1, 2, 3)), 0.1).size(), 2u);
    const glm::dmat4 mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1));
    EXPECT_EQ(rotationAwareKeyframes(mirror, glm::rotate(mirror, 2.0, glm::dvec3(0, 0, 1)), 0.1).size(), 2u);
}

}  // namespace
}  // namespace strahl
