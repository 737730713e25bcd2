#include "strahl/integrator/light.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <memory>
#include <string_view>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/core/rng.h"
#include "strahl/core/spherical_triangle.h"
#include "test_random.h"
#include "test_support.h"

namespace strahl {
namespace {

using test::next2D;

// Monte Carlo irradiance at ctx through sampleLi: the mean of L cos / pdf.
// Also checks, for every sample of a non-delta light, that pdfLi reproduces
// the reported pdf and that the radiance matches what a ray would see.
double estimateIrradiance(const Light& light, const LightSampleContext& ctx, int n, uint64_t seed,
                          int channel = 0) {
    Pcg32 rng(seed, 3);
    const Vec3 normal = glm::normalize(ctx.n);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const auto s = sampleLi(light, ctx, next2D(rng));
        if (!s) continue;
        EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
        if (!light.isDelta()) {
            const float pdf = pdfLi(light, ctx, s->wi, s->pLight);
            EXPECT_EQ(pdf, s->pdf) << "sample " << i;
            const Color seen = s->atInfinity ? infiniteLe(light, s->wi) : triangleLe(light, -s->wi);
            EXPECT_EQ(seen[channel], s->L[channel]) << "sample " << i;
        }
        sum += s->L[channel] * std::max(0.0f, glm::dot(normal, s->wi)) / s->pdf;
    }
    return sum / n;
}

// Irradiance at p (unit normal n) from a polygon of uniform radiance L that lies
// wholly above p's tangent plane, by Lambert's formula (the vector irradiance):
//     E = L / 2 |sum_i theta_i n . g_i|
// with theta_i the angle edge i subtends at p and g_i the unit normal of the
// plane through p and edge i.
double lambertIrradiance(const Vec3& p, const Vec3& n, const std::vector<Vec3>& polygon, double L) {
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec3 a = glm::normalize(glm::dvec3(polygon[i]) - glm::dvec3(p));
        const glm::dvec3 b =
            glm::normalize(glm::dvec3(polygon[(i + 1) % polygon.size()]) - glm::dvec3(p));
        sum += std::acos(glm::dot(a, b)) * glm::normalize(glm::cross(a, b));
    }
    return 0.5 * L * std::abs(glm::dot(sum, glm::dvec3(n)));
}

PointLight pointLight(const Vec3& position, float I) {
    PointLight l;
    l.position = position;
    l.intensity = Color(I);
    return l;
}

SpotLight spotLight(const Vec3& position, float I, float cosFalloffStart, float cosTotalWidth) {
    SpotLight l;
    l.position = position;
    l.intensity = Color(I);
    l.cosFalloffStart = cosFalloffStart;
    l.cosTotalWidth = cosTotalWidth;
    return l;
}

TriangleLight triangleLight(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Color& L,
                            bool twoSided = false) {
    TriangleLight l;
    l.p0 = p0;
    l.p1 = p1;
    l.p2 = p2;
    l.radiance = L;
    l.twoSided = twoSided;
    return l;
}

DirectionalLight sunLight(const Vec3& direction, float E, float angularRadius) {
    DirectionalLight l;
    l.direction = glm::normalize(direction);
    l.irradiance = Color(E);
    l.angularRadius = angularRadius;
    return l;
}

SkyLight skyLight(const Color& L) {
    SkyLight l;
    l.radiance = L;
    return l;
}

EnvironmentLight environmentLight(std::shared_ptr<const EnvironmentMap> map,
                                  const Mat3& worldToMap, const Color& scale) {
    EnvironmentLight l;
    l.environment = std::move(map);
    l.worldToEnvironment = worldToMap;
    l.scale = scale;
    return l;
}

Bounds3 unitBox() {
    Bounds3 b;
    b.expand(Vec3(-1.0f));
    b.expand(Vec3(1.0f));
    return b;
}

TEST(LightKinds, SceneFileNamesFollowTheVariantOrder) {
    const auto names = kindNames<LightKind>();
    const std::vector<std::string_view> expected = {"point", "spot",        "projector", "directional",
                                                    "sun",   "environment", "sky"};
    EXPECT_EQ(std::vector<std::string_view>(names.begin(), names.end()), expected);
    // "sun" is a directional light; triangles are made by the renderer, not named.
    const auto sunIsDirectional = withKindNamed<LightKind>(
        "sun", [](auto k) { return std::is_same_v<typename decltype(k)::type, DirectionalLight>; });
    ASSERT_TRUE(sunIsDirectional.has_value());
    EXPECT_TRUE(*sunIsDirectional);
    EXPECT_FALSE(withKindNamed<LightKind>("triangle", [](auto) { return 0; }));
    EXPECT_EQ(kindName(Light(triangleLight(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), Color(1))).kind),
              "triangle");
}

TEST(LightKinds, ALightIsAsSmallAsItsLargestKind) {
    // World::prepareLights makes one Light per emissive triangle: the variant
    // keeps that table smaller than the old struct with every kind's fields
    // (~190 bytes): the largest kind is the environment light.
    EXPECT_LE(sizeof(Light), 128u);
}

TEST(PointLight, InverseSquareIrradiance) {
    const PointLight light = pointLight(Vec3(1, 3, 0), 12.0f);
    EXPECT_TRUE(light.isDelta());
    EXPECT_FALSE(light.isInfinite());
    const LightSampleContext ctx{Vec3(1, 1, 0), Vec3(0, 1, 0)};
    const auto s = sampleLi(light, ctx, Vec2(0.5f));
    ASSERT_TRUE(s);
    EXPECT_FLOAT_EQ(s->L.r, 12.0f / 4.0f);
    EXPECT_EQ(s->wi, Vec3(0, 1, 0));
    EXPECT_EQ(s->pdf, 1.0f);
    EXPECT_EQ(s->pLight, light.position);
    EXPECT_FALSE(s->atInfinity);
    EXPECT_EQ(pdfLi(light, ctx, s->wi, s->pLight), 0.0f);
    // I cos / r^2 on a tilted receiver.
    const LightSampleContext tilted{Vec3(0, 0, 0), glm::normalize(Vec3(1, 1, 0))};
    const double cosTheta = glm::dot(tilted.n, glm::normalize(light.position));
    EXPECT_NEAR(estimateIrradiance(light, tilted, 1, 1), 12.0 * cosTheta / 10.0, 1e-5);
    EXPECT_FALSE(sampleLi(light, LightSampleContext{light.position, Vec3(0)}, Vec2(0.5f)));
}

TEST(SpotLight, SmoothstepFalloffBetweenTheCones) {
    SpotLight light = spotLight(Vec3(0, 0, 0), 8.0f, std::cos(0.3f), std::cos(0.5f));
    light.direction = Vec3(0, -1, 0);
    EXPECT_TRUE(light.isDelta());
    // Receivers on the unit sphere around the light at angle a from the axis.
    auto falloffAt = [&](float cosA) -> float {
        const float sinA = std::sqrt(1.0f - cosA * cosA);
        const auto s = sampleLi(light, LightSampleContext{Vec3(sinA, -cosA, 0), Vec3(0)}, Vec2(0));
        return s ? s->L.r / 8.0f : 0.0f;
    };
    EXPECT_NEAR(falloffAt(1.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(falloffAt(light.cosFalloffStart), 1.0f, 1e-6f);
    // Half-way in cos: smoothstep(1/2) = 1/2; a quarter: 3/16 - 2/64 = 5/32.
    const float mid = 0.5f * (light.cosFalloffStart + light.cosTotalWidth);
    EXPECT_NEAR(falloffAt(mid), 0.5f, 1e-4f);
    const float quarter =
        light.cosTotalWidth + 0.25f * (light.cosFalloffStart - light.cosTotalWidth);
    EXPECT_NEAR(falloffAt(quarter), 5.0f / 32.0f, 1e-4f);
    const LightSampleContext outside{Vec3(std::sin(0.55f), -std::cos(0.55f), 0), Vec3(0)};
    EXPECT_FALSE(sampleLi(light, outside, Vec2(0)));
    EXPECT_FALSE(sampleLi(light, LightSampleContext{Vec3(0, 1, 0), Vec3(0)}, Vec2(0)));
}

TEST(SpotLight, LinearFalloffIsLinearInTheAngle) {
    // Mitsuba's spot: full inside 0.3 rad, zero beyond 0.5 rad, linear in the
    // angle between.
    SpotLight light = spotLight(Vec3(0, 0, 0), 8.0f, std::cos(0.3f), std::cos(0.5f));
    light.shape = SpotLight::Falloff::LinearAngle;
    EXPECT_NEAR(light.falloff(std::cos(0.2f)), 1.0f, 1e-6f);
    EXPECT_NEAR(light.falloff(std::cos(0.4f)), 0.5f, 1e-5f);
    EXPECT_NEAR(light.falloff(std::cos(0.45f)), 0.25f, 1e-5f);
    EXPECT_EQ(light.falloff(std::cos(0.5f)), 0.0f);
    EXPECT_EQ(light.falloff(-1.0f), 0.0f);
}

TEST(SpotLight, PowerIsTheIntegralOfTheFalloff) {
    for (const auto shape : {SpotLight::Falloff::Smooth, SpotLight::Falloff::LinearAngle}) {
        SpotLight light = spotLight(Vec3(0, 0, 0), 3.0f, 0.9f, 0.6f);
        light.shape = shape;
        // Phi = I 2 pi integral of falloff(cos) dcos, by the midpoint rule.
        double integral = 0.0;
        const int steps = 20000;
        for (int i = 0; i < steps; ++i) {
            const double cosA = -1.0 + 2.0 * (i + 0.5) / steps;
            const auto s = sampleLi(
                light, LightSampleContext{Vec3(std::sqrt(1.0 - cosA * cosA), -cosA, 0), Vec3(0)},
                Vec2(0));
            if (s) integral += s->L.r / 3.0 * (2.0 / steps);
        }
        EXPECT_NEAR(lightPower(light, unitBox()), 3.0 * 2.0 * kPi * integral, 1e-3)
            << (shape == SpotLight::Falloff::Smooth ? "smooth" : "linear");
    }
}

// An untextured projector along -y from (0, 2, 0): a square frustum of
// half-angle 30 degrees (fov 60 along x of a square image).
ProjectorLight projector(float irradiance) {
    ProjectorLight l;
    l.position = Vec3(0, 2, 0);
    l.axis = Vec3(0, -1, 0);
    l.up = Vec3(0, 0, -1);
    l.right = glm::cross(l.axis, l.up);
    l.irradiance = Color(irradiance);
    l.fovDegrees = 60.0f;
    l.setFrustum(1.0f);
    return l;
}

TEST(ProjectorLight, APlaneFacingItReceivesTheIrradianceUpToTheFrustumsEdge) {
    const ProjectorLight light = projector(3.0f);
    EXPECT_TRUE(light.isDelta());
    // On the floor (2 units away), E = irradiance / 2² everywhere inside the
    // frustum: the 1 / cos³ of the intensity cancels cos / dist².
    const float half = 2.0f * std::tan(glm::radians(30.0f));
    for (const Vec2 xz : {Vec2(0.0f), Vec2(0.9f * half, 0.0f), Vec2(-0.5f * half, 0.95f * half)}) {
        const LightSampleContext ctx{Vec3(xz.x, 0, xz.y), Vec3(0, 1, 0)};
        EXPECT_NEAR(estimateIrradiance(light, ctx, 1, 1), 3.0 / 4.0, 1e-5) << xz.x << ", " << xz.y;
    }
    EXPECT_FALSE(sampleLi(light, LightSampleContext{Vec3(1.05f * half, 0, 0), Vec3(0, 1, 0)}, Vec2(0)));
    EXPECT_FALSE(sampleLi(light, LightSampleContext{Vec3(0, 3, 0), Vec3(0, -1, 0)}, Vec2(0)));
}

TEST(ProjectorLight, FovAxisAndAspectShapeTheFrustum) {
    ProjectorLight light = projector(1.0f);
    const float t = std::tan(glm::radians(30.0f));
    light.setFrustum(2.0f);  // a 2:1 image, fov along x
    EXPECT_FLOAT_EQ(light.tanX, t);
    EXPECT_FLOAT_EQ(light.tanY, t / 2.0f);
    light.fovAxis = ProjectorLight::FovAxis::Y;
    light.setFrustum(2.0f);
    EXPECT_FLOAT_EQ(light.tanY, t);
    EXPECT_FLOAT_EQ(light.tanX, 2.0f * t);
    light.fovAxis = ProjectorLight::FovAxis::Diagonal;
    light.setFrustum(2.0f);
    EXPECT_NEAR(std::hypot(light.tanX, light.tanY), t, 1e-6f);
    EXPECT_FLOAT_EQ(light.tanX, 2.0f * light.tanY);
    light.fovAxis = ProjectorLight::FovAxis::Smaller;
    light.setFrustum(2.0f);
    EXPECT_FLOAT_EQ(light.tanY, t);
}

TEST(ProjectorLight, PowerIsTheIntegralOfTheIntensity) {
    const ProjectorLight light = projector(3.0f);
    // Phi = integral of I over the sphere, by the midpoint rule in (theta, phi)
    // over the cap the frustum lies in.
    double integral = 0.0;
    const int n = 600;
    const double maxTheta = glm::radians(60.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double theta = (i + 0.5) / n * maxTheta, phi = (j + 0.5) / n * 2.0 * kPi;
            const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(-std::cos(theta)),
                         float(std::sin(theta) * std::sin(phi)));
            integral += light.intensityTowards(d, nullptr).r * std::sin(theta);
        }
    integral *= (maxTheta / n) * (2.0 * kPi / n);
    EXPECT_NEAR(lightPower(light, unitBox()) / integral, 1.0, 2e-3);
}

TEST(DirectionalLight, DeltaGivesTheIrradiance) {
    const DirectionalLight light = sunLight(Vec3(0, -1, 0), 3.0f, 0.0f);
    EXPECT_TRUE(light.isDelta());
    EXPECT_TRUE(light.isInfinite());
    const LightSampleContext ctx{Vec3(5, 2, 1), Vec3(0, 1, 0)};
    const auto s = sampleLi(light, ctx, Vec2(0.3f));
    ASSERT_TRUE(s);
    EXPECT_EQ(s->wi, Vec3(0, 1, 0));
    EXPECT_EQ(s->L, Color(3.0f));
    EXPECT_TRUE(s->atInfinity);
    EXPECT_EQ(pdfLi(light, ctx, Vec3(0, 1, 0), Vec3(0)), 0.0f);
    EXPECT_EQ(infiniteLe(light, Vec3(0, 1, 0)), Color(0.0f));
}

TEST(DirectionalLight, SunDiskRadianceAndIrradiance) {
    const float r = 0.3f;  // wide, so the estimate tests the cone geometry
    const DirectionalLight light = sunLight(Vec3(0, -1, 0), 2.0f, r);
    EXPECT_FALSE(light.isDelta());
    EXPECT_TRUE(light.isInfinite());
    const float L = 2.0f / (kPi * std::sin(r) * std::sin(r));
    EXPECT_NEAR(infiniteLe(light, Vec3(0, 1, 0)).r, L, 1e-4f * L);
    EXPECT_NEAR(infiniteLe(light, glm::normalize(Vec3(std::tan(0.29f), 1, 0))).r, L, 1e-4f * L);
    EXPECT_EQ(infiniteLe(light, glm::normalize(Vec3(std::tan(0.31f), 1, 0))).r, 0.0f);
    EXPECT_EQ(pdfLi(light, LightSampleContext{}, Vec3(0, -1, 0), Vec3(0)), 0.0f);
    // Facing: E. Tilted by t with the whole disk above the horizon: the mean
    // of the directions over the cone is the axis, so E cos t exactly.
    const LightSampleContext facing{Vec3(0), Vec3(0, 1, 0)};
    EXPECT_NEAR(estimateIrradiance(light, facing, 20000, 5), 2.0, 2e-3);
    const float tilt = 0.7f;
    const LightSampleContext tilted{Vec3(0), Vec3(std::sin(tilt), std::cos(tilt), 0)};
    EXPECT_NEAR(estimateIrradiance(light, tilted, 20000, 6), 2.0 * std::cos(tilt), 0.01);
}

TEST(DirectionalLight, RealSunSizeKeepsFullPrecision) {
    // The sun's 0.2666 degrees: 1 - cos r = 1.08e-5, near float's resolution at 1.
    const DirectionalLight light = sunLight(Vec3(1, -2, 0.5f), 1000.0f, 0.004653f);
    const LightSampleContext ctx{Vec3(0), -light.direction};
    EXPECT_NEAR(estimateIrradiance(light, ctx, 4000, 8), 1000.0, 0.05);
}

TEST(TriangleLight, SolidAngleSamplingMatchesLambertsFormula) {
    // Close and large: sampled by solid angle.
    const Vec3 p0(-1, 1, -1), p1(1, 1, -1), p2(0, 1, 1.5f);  // front faces -y
    const TriangleLight light = triangleLight(p0, p1, p2, Color(2.0f, 1.0f, 0.5f));
    EXPECT_FALSE(light.isDelta());
    EXPECT_FALSE(light.isInfinite());
    const LightSampleContext up{Vec3(0.1f, 0, 0.2f), Vec3(0, 1, 0)};
    const float omega = triangleSolidAngle(up.p, p0, p1, p2);
    ASSERT_GT(omega, 0.5f);
    const auto s = sampleLi(light, up, Vec2(0.3f, 0.6f));
    ASSERT_TRUE(s);
    EXPECT_FLOAT_EQ(s->pdf, 1.0f / omega);
    EXPECT_EQ(pdfLi(light, up, s->wi, s->pLight), s->pdf);
    EXPECT_NEAR(s->pLight.y, 1.0f, 1e-6f);
    for (const Vec3& n : {Vec3(0, 1, 0), glm::normalize(Vec3(0.3f, 1, -0.2f))}) {
        const LightSampleContext ctx{up.p, n};
        const double exact = lambertIrradiance(ctx.p, n, {p0, p1, p2}, 2.0);
        EXPECT_NEAR(estimateIrradiance(light, ctx, 20000, 7) / exact, 1.0, 0.01);
        const double exactBlue = lambertIrradiance(ctx.p, n, {p0, p1, p2}, 0.5);
        EXPECT_NEAR(estimateIrradiance(light, ctx, 5000, 9, 2) / exactBlue, 1.0, 0.02);
    }
}

TEST(TriangleLight, AreaSamplingOfATinyTriangleMatchesLambertsFormula) {
    // 3e-5 sr: below the solid-angle threshold, so sampled by area.
    const Vec3 p0(-0.005f, 1, -0.005f), p1(0.005f, 1, -0.005f), p2(0, 1.003f, 0.006f);
    const TriangleLight light = triangleLight(p0, p1, p2, Color(1000.0f), true);
    const LightSampleContext ctx{Vec3(0.2f, 0, 0.1f), glm::normalize(Vec3(0.2f, 1, 0))};
    const float omega = triangleSolidAngle(ctx.p, p0, p1, p2);
    ASSERT_LT(omega, 3e-4f);
    ASSERT_GT(omega, 1e-5f);
    Pcg32 rng(4, 4);
    bool varies = false;
    float firstPdf = 0.0f;
    for (int i = 0; i < 100; ++i) {
        const auto s = sampleLi(light, ctx, next2D(rng));
        ASSERT_TRUE(s);
        // Area density dist^2 / (|cos| A), not 1 / omega.
        const Vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
        const Vec3 d = s->pLight - ctx.p;
        const float area = 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
        EXPECT_NEAR(s->pdf, glm::dot(d, d) / (std::abs(glm::dot(n, s->wi)) * area), 1e-4f * s->pdf);
        EXPECT_EQ(pdfLi(light, ctx, s->wi, s->pLight), s->pdf);
        if (i == 0) firstPdf = s->pdf;
        varies |= s->pdf != firstPdf;
    }
    EXPECT_TRUE(varies);
    const double exact = lambertIrradiance(ctx.p, ctx.n, {p0, p1, p2}, 1000.0);
    EXPECT_NEAR(estimateIrradiance(light, ctx, 20000, 10) / exact, 1.0, 0.005);
}

TEST(TriangleLight, NearlyAHemisphereFallsBackToAreaSamplingConsistently) {
    const Vec3 p0(-100, 0, -100), p1(0, 0, 200), p2(100, 0, -100);  // front faces +y
    const TriangleLight light = triangleLight(p0, p1, p2, Color(1.0f));
    const LightSampleContext ctx{Vec3(0.5f, 0.01f, 0.3f), Vec3(0, -1, 0)};
    ASSERT_GT(triangleSolidAngle(ctx.p, p0, p1, p2), 6.22f);
    Pcg32 rng(2, 9);
    for (int i = 0; i < 200; ++i) {
        const auto s = sampleLi(light, ctx, next2D(rng));
        ASSERT_TRUE(s);
        EXPECT_EQ(pdfLi(light, ctx, s->wi, s->pLight), s->pdf);
        EXPECT_NEAR(s->pLight.y, 0.0f, 1e-5f);
    }
}

TEST(TriangleLight, OneSidedEmitsOnlyFromTheFront) {
    const Vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 0, -1);  // front faces +y
    TriangleLight light = triangleLight(p0, p1, p2, Color(1.0f));
    EXPECT_EQ(triangleLe(light, Vec3(0, 1, 0)), Color(1.0f));
    EXPECT_EQ(triangleLe(light, Vec3(0, -1, 0)), Color(0.0f));
    const LightSampleContext above{Vec3(0.2f, 1, -0.2f), Vec3(0, -1, 0)};
    const LightSampleContext below{Vec3(0.2f, -1, -0.2f), Vec3(0, 1, 0)};
    EXPECT_TRUE(sampleLi(light, above, Vec2(0.5f)));
    EXPECT_FALSE(sampleLi(light, below, Vec2(0.5f)));
    EXPECT_EQ(pdfLi(light, below, Vec3(0, 1, 0), Vec3(0.2f, 0, -0.2f)), 0.0f);
    light.twoSided = true;
    EXPECT_EQ(triangleLe(light, Vec3(0, -1, 0)), Color(1.0f));
    const double exact = lambertIrradiance(above.p, above.n, {p0, p1, p2}, 1.0);
    EXPECT_NEAR(estimateIrradiance(light, above, 10000, 3) / exact, 1.0, 0.01);
    EXPECT_NEAR(estimateIrradiance(light, below, 10000, 4) / exact, 1.0, 0.01);
}

TEST(SkyLight, CosineSamplingGivesPiLExactly) {
    const SkyLight light = skyLight(Color(0.7f));
    EXPECT_TRUE(light.isInfinite());
    EXPECT_FALSE(light.isDelta());
    // Cosine-weighted around n: every sample contributes L cos / (cos / pi) = pi L.
    const LightSampleContext ctx{Vec3(1, 2, 3), glm::normalize(Vec3(1, 1, 1))};
    EXPECT_NEAR(estimateIrradiance(light, ctx, 2000, 1), kPi * 0.7, 1e-4);
    EXPECT_EQ(pdfLi(light, ctx, -ctx.n, Vec3(0)), 0.0f);  // never samples below n
    EXPECT_EQ(infiniteLe(light, Vec3(0, -1, 0)), Color(0.7f));
}

TEST(SkyLight, UniformSphereOffSurfaces) {
    const SkyLight light = skyLight(Color(0.7f));
    const LightSampleContext ctx{Vec3(0), Vec3(0)};  // no normal: a medium point
    EXPECT_NEAR(pdfLi(light, ctx, Vec3(0, 0, 1), Vec3(0)), 0.25f * kInvPi, 1e-7f);
    Pcg32 rng(1, 1);
    double sum = 0.0;
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        const auto s = sampleLi(light, ctx, next2D(rng));
        ASSERT_TRUE(s);
        EXPECT_EQ(pdfLi(light, ctx, s->wi, s->pLight), s->pdf);
        sum += s->L.r * std::max(0.0f, s->wi.y) / s->pdf;  // an upward plane
    }
    EXPECT_NEAR(sum / n, kPi * 0.7, 0.02);
}

TEST(EnvironmentLight, ConstantMapEqualsTheSky) {
    auto map = std::make_shared<const EnvironmentMap>(16, 8, std::vector<Color>(128, Color(0.5f)));
    const Mat3 rotation = Mat3(glm::rotate(Mat4(1.0f), 0.8f, glm::normalize(Vec3(1, 2, 3))));
    const EnvironmentLight light = environmentLight(map, rotation, Color(1.4f));
    EXPECT_TRUE(light.isInfinite());
    EXPECT_FALSE(light.isDelta());
    const LightSampleContext ctx{Vec3(0), Vec3(0, 1, 0)};
    EXPECT_NEAR(estimateIrradiance(light, ctx, 100000, 2), kPi * 0.7, 0.03);
    const Light sky = skyLight(Color(0.7f));
    EXPECT_NEAR(lightPower(light, unitBox()), lightPower(sky, unitBox()), 1e-3);
}

TEST(EnvironmentLight, RotationAndScaleApplyToLookupAndSampling) {
    Pcg32 texelRng(5, 5);
    std::vector<Color> texels;
    for (int i = 0; i < 32 * 16; ++i)
        texels.emplace_back(texelRng.nextFloat(), texelRng.nextFloat(), texelRng.nextFloat());
    auto map = std::make_shared<const EnvironmentMap>(32, 16, texels);
    const Mat3 rotation = Mat3(glm::rotate(Mat4(1.0f), 1.1f, glm::normalize(Vec3(-1, 3, 1))));
    const EnvironmentLight light = environmentLight(map, rotation, Color(2.0f, 1.0f, 0.5f));
    const Vec3 dir = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
    const Color expected = Color(2.0f, 1.0f, 0.5f) * map->lookup(rotation * dir);
    const Color seen = infiniteLe(light, dir);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(seen[c], expected[c]);
    // Samples: radiance and pdf as a ray in that direction would see them.
    const LightSampleContext ctx{Vec3(0), Vec3(0, 0, 1)};
    for (int c = 0; c < 3; ++c) estimateIrradiance(light, ctx, 2000, 11, c);
}

TEST(LightPower, MatchesTheEmittedFlux) {
    const Bounds3 box = unitBox();  // radius sqrt(3)
    const float R2 = 3.0f;
    EXPECT_FLOAT_EQ(lightPower(pointLight(Vec3(0), 2.0f), box), 8.0f * kPi);
    const TriangleLight tri = triangleLight(Vec3(0), Vec3(2, 0, 0), Vec3(0, 0, 3), Color(1, 2, 3));
    EXPECT_FLOAT_EQ(lightPower(tri, box), kPi * 3.0f * 2.0f);
    TriangleLight twoSided = tri;
    twoSided.twoSided = true;
    EXPECT_FLOAT_EQ(lightPower(twoSided, box), 2.0f * kPi * 3.0f * 2.0f);
    EXPECT_FLOAT_EQ(lightPower(sunLight(Vec3(0, -1, 0), 2.0f, 0.0f), box), kPi * R2 * 2.0f);
    EXPECT_FLOAT_EQ(lightPower(skyLight(Color(0.5f)), box), 4.0f * kPi * kPi * R2 * 0.5f);
    EXPECT_EQ(lightPower(skyLight(Color(0.5f)), Bounds3{}), 0.0f);  // empty scene
}

TEST(LightSet, ChoosesInProportionToPower) {
    std::vector<Light> lights = {pointLight(Vec3(0), 1.0f), skyLight(Color(0.0f)),
                                 pointLight(Vec3(1), 3.0f), sunLight(Vec3(0, -1, 0), 1.0f, 0.0f)};
    const LightSet set(lights, unitBox());
    ASSERT_EQ(set.lights().size(), 4u);
    EXPECT_FALSE(set.empty());
    EXPECT_EQ(set.infiniteLights(), (std::vector<uint32_t>{1, 3}));
    const double p0 = 4 * kPi, p2 = 12 * kPi, p3 = kPi * 3.0;
    const double total = p0 + p2 + p3;
    EXPECT_NEAR(set.pmf(0), p0 / total, 1e-6);
    EXPECT_EQ(set.pmf(1), 0.0f);
    EXPECT_NEAR(set.pmf(2), p2 / total, 1e-6);
    EXPECT_NEAR(set.pmf(3), p3 / total, 1e-6);
    Pcg32 rng(9, 9);
    std::vector<int> counts(4, 0);
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        const auto choice = set.choose(rng.nextFloat());
        ASSERT_TRUE(choice);
        EXPECT_EQ(choice->second, set.pmf(choice->first));
        ++counts[choice->first];
    }
    EXPECT_EQ(counts[1], 0);
    for (uint32_t i : {0u, 2u, 3u})
        EXPECT_NEAR(static_cast<double>(counts[i]) / n, set.pmf(i), 0.01) << i;
    const auto last = set.choose(0x1.fffffep-1f);
    ASSERT_TRUE(last);
    EXPECT_EQ(last->first, 3u);
}

TEST(LightSet, AllZeroPowersFallBackToUniformAndEmptyChoosesNothing) {
    const LightSet dark({skyLight(Color(0.0f)), pointLight(Vec3(0), 0.0f)}, unitBox());
    EXPECT_EQ(dark.pmf(0), 0.5f);
    EXPECT_EQ(dark.pmf(1), 0.5f);
    EXPECT_EQ(dark.choose(0.7f)->first, 1u);
    const LightSet none;
    EXPECT_TRUE(none.empty());
    EXPECT_FALSE(none.choose(0.5f));
    EXPECT_FALSE(LightSet({}, unitBox()).choose(0.5f));
}

TEST(LightSet, UniformEmitterSelectionSharesEachEmitterByPower) {
    // Three lights, the last two one emitter (two triangles of a lamp): the
    // first gets 1/2, the lamp 1/2 split 1 : 3 by power.
    const std::vector<Light> lights = {pointLight(Vec3(0), 1.0f), pointLight(Vec3(0), 10.0f),
                                       pointLight(Vec3(0), 30.0f)};
    const LightSet uniform(lights, unitBox(), LightSelection::UniformEmitters, {0, 1, 1});
    EXPECT_FLOAT_EQ(uniform.pmf(0), 0.5f);
    EXPECT_FLOAT_EQ(uniform.pmf(1), 0.125f);
    EXPECT_FLOAT_EQ(uniform.pmf(2), 0.375f);
    const LightSet power(lights, unitBox(), LightSelection::Power, {0, 1, 1});
    EXPECT_FLOAT_EQ(power.pmf(0), 1.0f / 41.0f);  // the emitters do not matter
    EXPECT_THROW(LightSet(lights, unitBox(), LightSelection::UniformEmitters, {0, 1}), Error);
}

TEST(LightSet, RejectsLightsTheSamplersCannotHandle) {
    const SpotLight spot = spotLight(Vec3(0), 1.0f, 0.5f, 0.9f);  // cosines out of order
    EXPECT_THROW(LightSet({spot}, unitBox()), Error);
    EXPECT_THROW(LightSet({sunLight(Vec3(0, -1, 0), 1.0f, 2.0f)}, unitBox()), Error);
    DirectionalLight sun = sunLight(Vec3(0, -1, 0), 1.0f, 0.0f);
    sun.direction = Vec3(0, -2, 0);
    EXPECT_THROW(LightSet({sun}, unitBox()), Error);
    EXPECT_THROW(LightSet({skyLight(Color(-1.0f))}, unitBox()), Error);
    EXPECT_THROW(LightSet({environmentLight(nullptr, Mat3(1.0f), Color(1.0f))}, unitBox()), Error);
    auto map = std::make_shared<const EnvironmentMap>(2, 1, std::vector<Color>(2, Color(1.0f)));
    EXPECT_THROW(LightSet({environmentLight(map, Mat3(2.0f), Color(1.0f))}, unitBox()), Error);
    const std::string message = test::errorMessage([&] {
        LightSet({pointLight(Vec3(0), 1.0f), skyLight(Color(NAN))}, unitBox());
    });
    EXPECT_NE(message.find("light 1"), std::string::npos) << message;
}

}  // namespace
}  // namespace strahl
