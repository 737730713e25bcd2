// The light BVH (integrator/light_bvh.h, light_bounds.h) and the light set's
// "bvh" selection: analytic probabilities, a distribution that sums to 1 and
// that choose() follows, lights that cannot reach a receiver never chosen,
// and cone unions that hold both cones.

#include "strahl/integrator/light_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "strahl/core/rng.h"
#include "strahl/integrator/light.h"

namespace strahl {
namespace {

Bounds3 box() {
    Bounds3 b;
    b.expand(Vec3(-10.0f));
    b.expand(Vec3(10.0f));
    return b;
}

Light point(const Vec3& position, float intensity) {
    PointLight l;
    l.position = position;
    l.intensity = Color(intensity);
    return l;
}

Light triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, bool twoSided = false) {
    TriangleLight l;
    l.p0 = p0;
    l.p1 = p1;
    l.p2 = p2;
    l.radiance = Color(1.0f);
    l.twoSided = twoSided;
    return l;
}

LightSampleContext at(const Vec3& p, const Vec3& n) {
    LightSampleContext c;
    c.p = p;
    c.n = n;
    return c;
}

Vec3 randomUnit(Pcg32& rng) {
    const float z = 1.0f - 2.0f * rng.nextFloat();
    const float phi = 2.0f * kPi * rng.nextFloat();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec3 randomPoint(Pcg32& rng, float extent) {
    return Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * (2.0f * extent) - extent;
}

TEST(LightBvh, TwoPointLightsOverAReceiverGoByTheInverseSquareLaw) {
    // Straight above the receiver at heights 1 and 3: importance 1/1 : 1/9.
    const LightSet set({point(Vec3(0, 1, 0), 1.0f), point(Vec3(0, 3, 0), 1.0f)}, box(),
                       LightSelection::Bvh, {0, 1});
    const LightSampleContext receiver = at(Vec3(0.0f), Vec3(0, 1, 0));
    EXPECT_NEAR(set.pmf(0, receiver), 0.9f, 1e-6f);
    EXPECT_NEAR(set.pmf(1, receiver), 0.1f, 1e-6f);
    EXPECT_EQ(set.choose(0.89f, receiver)->first, 0u);
    EXPECT_EQ(set.choose(0.91f, receiver)->first, 1u);
}

TEST(LightBvh, AutoSelectionTakesTheTreeAboveSixteenFiniteLights) {
    std::vector<Light> lights;
    SkyLight sky;
    lights.push_back(sky);  // infinite lights do not count
    for (size_t i = 0; i < kAutoBvhLights; ++i) lights.push_back(point(Vec3(float(i), 1, 0), 1.0f));
    std::vector<uint32_t> emitters(lights.size() + 1);
    for (size_t i = 0; i < emitters.size(); ++i) emitters[i] = uint32_t(i);
    emitters.pop_back();
    EXPECT_EQ(LightSet(lights, box(), LightSelection::Auto, emitters).selection(),
              LightSelection::Power);
    lights.push_back(point(Vec3(0, 2, 0), 1.0f));
    emitters.push_back(uint32_t(emitters.size()));
    EXPECT_EQ(LightSet(lights, box(), LightSelection::Auto, emitters).selection(),
              LightSelection::Bvh);
}

// Two infinite lights (a sun and a sky) take the tree, which chooses each as
// often (pbrt-v4's rule) however their powers compare; one does not.
TEST(LightBvh, AutoSelectionTakesTheTreeForTwoInfiniteLights) {
    DirectionalLight sun;
    sun.direction = Vec3(0, -1, 0);
    sun.irradiance = Color(100.0f);
    SkyLight sky;
    std::vector<Light> lights{sky, point(Vec3(0, 1, 0), 1.0f)};
    EXPECT_EQ(LightSet(lights, box(), LightSelection::Auto, {0, 1}).selection(), LightSelection::Power);
    lights.push_back(sun);
    const LightSet set(lights, box(), LightSelection::Auto, {0, 1, 2});
    ASSERT_EQ(set.selection(), LightSelection::Bvh);
    const LightSampleContext receiver = at(Vec3(0.0f), Vec3(0, 1, 0));
    EXPECT_NEAR(set.pmf(0, receiver), 1.0f / 3.0f, 1e-6f);  // the sky
    EXPECT_NEAR(set.pmf(2, receiver), 1.0f / 3.0f, 1e-6f);  // the sun, 100x brighter
    EXPECT_NEAR(set.pmf(1, receiver), 1.0f / 3.0f, 1e-6f);  // the tree, its only light
}

TEST(LightBvh, TheDistributionSumsToOneAndChooseFollowsIt) {
    Pcg32 rng(7, 1);
    std::vector<Light> lights;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c = randomPoint(rng, 8.0f);
        const Vec3 a = randomUnit(rng) * 0.3f, b = randomUnit(rng) * 0.3f;
        lights.push_back(triangle(c, c + a, c + b, i % 3 == 0));
    }
    for (int i = 0; i < 20; ++i) lights.push_back(point(randomPoint(rng, 8.0f), 1.0f + float(i)));
    SkyLight sky;
    sky.radiance = Color(0.2f);
    lights.push_back(sky);
    std::vector<uint32_t> emitters(lights.size());
    for (size_t i = 0; i < emitters.size(); ++i) emitters[i] = uint32_t(i);
    const LightSet set(lights, box(), LightSelection::Bvh, emitters);
    for (int trial = 0; trial < 20; ++trial) {
        const LightSampleContext receiver = at(randomPoint(rng, 9.0f), randomUnit(rng));
        double sum = 0.0;
        for (uint32_t i = 0; i < lights.size(); ++i) sum += set.pmf(i, receiver);
        // A walk may end at a node both of whose children are out of reach
        // (its own bounds were looser): no light, as for a light that gives
        // nothing. So the total is 1 less that small lost share.
        EXPECT_LE(sum, 1.0 + 1e-5) << "receiver " << trial;
        EXPECT_GT(sum, 0.99) << "receiver " << trial;
        // The sky and the tree are each chosen half the time.
        EXPECT_EQ(set.pmf(uint32_t(lights.size() - 1), receiver), 0.5f);
        for (int k = 0; k < 200; ++k) {
            const auto choice = set.choose(rng.nextFloat(), receiver);
            if (choice) {
                EXPECT_EQ(choice->second, set.pmf(choice->first, receiver));  // bit for bit
            }
        }
    }
    // Frequencies: one receiver, many draws.
    const LightSampleContext receiver = at(Vec3(1, 2, 3), Vec3(0, 0, 1));
    std::vector<int> counts(lights.size(), 0);
    const int n = 200000;
    for (int k = 0; k < n; ++k)
        if (const auto choice = set.choose(rng.nextFloat(), receiver)) ++counts[choice->first];
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const double p = set.pmf(i, receiver);
        EXPECT_NEAR(double(counts[i]) / n, p, 4.0 * std::sqrt(p * (1.0 - p) / n) + 1e-5) << i;
    }
}

TEST(LightBvh, ALightThatCannotReachTheReceiverIsNeverChosen) {
    // A one-sided triangle facing up over the receiver, one facing down at
    // it, and a spot pointing away from it.
    SpotLight away;
    away.position = Vec3(0, 2, 0);
    away.direction = Vec3(0, 1, 0);
    away.cosFalloffStart = 0.95f;
    away.cosTotalWidth = 0.9f;
    const std::vector<Light> lights = {
        triangle(Vec3(-1, 1, -1), Vec3(-1, 1, 1), Vec3(1, 1, 0)),  // normal +y: away
        triangle(Vec3(-1, 1, -1), Vec3(1, 1, 0), Vec3(-1, 1, 1)),  // normal -y: at it
        away};
    const LightSet set(lights, box(), LightSelection::Bvh, {0, 1, 2});
    // Far enough below that the bounds' angular extent (13.6 degrees from
    // here) cannot bring the others' cones round to it.
    const LightSampleContext below = at(Vec3(0.2f, -5.0f, 0.1f), Vec3(0, 1, 0));
    EXPECT_EQ(set.pmf(0, below), 0.0f);
    EXPECT_EQ(set.pmf(1, below), 1.0f);
    EXPECT_EQ(set.pmf(2, below), 0.0f);
    // Above, the downward triangle is the one that cannot reach.
    const LightSampleContext above = at(Vec3(0.1f, 6.0f, 0.0f), Vec3(0, -1, 0));
    EXPECT_EQ(set.pmf(1, above), 0.0f);
    EXPECT_NEAR(set.pmf(0, above) + set.pmf(2, above), 1.0f, 1e-6f);
}

TEST(LightBounds, TheUnionOfTwoConesHoldsBoth) {
    Pcg32 rng(3, 5);
    for (int i = 0; i < 2000; ++i) {
        LightBounds a, b;
        a.box.expand(Vec3(0.0f));
        b.box.expand(Vec3(1.0f));
        a.power = b.power = 1.0f;
        a.axis = randomUnit(rng);
        b.axis = randomUnit(rng);
        a.thetaO = kPi * rng.nextFloat() * rng.nextFloat();
        b.thetaO = kPi * rng.nextFloat() * rng.nextFloat();
        const LightBounds u = unite(a, b);
        for (const LightBounds* c : {&a, &b}) {
            const float between =
                std::atan2(glm::length(glm::cross(u.axis, c->axis)), glm::dot(u.axis, c->axis));
            if (u.thetaO < kPi) {  // pi: every direction
                EXPECT_LE(between + c->thetaO, u.thetaO + 1e-5f) << i;
            }
        }
        EXPECT_EQ(u.power, 2.0f);
    }
}

TEST(LightBounds, TheWalksImportanceIsTheReferenceImportanceWithoutTrigonometry) {
    // ImportanceBounds (the tree's nodes) against LightBounds::importance, the
    // angles written out: every cone, receiver and distance, both sides of
    // every threshold.
    Pcg32 rng(11, 2);
    int nonZero = 0;
    for (int i = 0; i < 20000; ++i) {
        LightBounds b;
        const Vec3 c = randomPoint(rng, 2.0f);
        b.box.expand(c);
        b.box.expand(c + Vec3(rng.nextFloat(), rng.nextFloat(), rng.nextFloat()) * (2.0f * rng.nextFloat()));
        b.axis = randomUnit(rng);
        b.thetaO = kPi * rng.nextFloat() * rng.nextFloat();
        b.thetaE = kPi * rng.nextFloat();
        b.power = 0.1f + 10.0f * rng.nextFloat();
        b.twoSided = rng.nextFloat() < 0.3f;
        const Vec3 p = randomPoint(rng, 6.0f);
        const Vec3 n = rng.nextFloat() < 0.2f ? Vec3(0.0f) : randomUnit(rng);
        const float reference = b.importance(p, n);
        const float fast = ImportanceBounds(b).importance(p, n);
        // The largest value the importance can take at this distance.
        const float radius = 0.5f * glm::length(b.box.diagonal());
        const float d2 = glm::dot(p - b.box.center(), p - b.box.center());
        const float scale = b.power / std::max({d2, 0.01f * radius * radius, 1e-12f});
        EXPECT_NEAR(fast, reference, 1e-3f * scale) << i;
        if (reference > 0.0f) ++nonZero;
    }
    EXPECT_GT(nonZero, 5000);
}

TEST(LightBounds, TheOrientationMeasureOfAHemisphereEmitterIsPi) {
    // One direction of normals emitting over the hemisphere: the cosine-
    // weighted solid angle, pi.
    LightBounds b;
    b.thetaO = 0.0f;
    b.thetaE = 0.5f * kPi;
    EXPECT_NEAR(orientationMeasure(b), kPi, 1e-5f);
    // Normals in every direction: 2 pi (1 - cos pi) = 4 pi; the emission
    // beyond the normals adds nothing.
    b.thetaO = kPi;
    EXPECT_NEAR(orientationMeasure(b), 4.0f * kPi, 1e-4f);
}

}  // namespace
}  // namespace strahl
