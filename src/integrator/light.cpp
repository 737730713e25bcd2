#include "strahl/integrator/light.h"

#include <algorithm>
#include <cmath>

#include "strahl/core/error.h"
#include "strahl/core/sampling.h"
#include "strahl/core/spherical_triangle.h"

namespace strahl {

namespace {

// Spherical-triangle sampling is used between these solid angles. Below 3e-4 sr
// (a triangle ~1 degree across) area sampling is as good: its density
// dist^2 / (cos A) varies by only ~ the angular size over the triangle. Above
// 6.22 sr (2 pi - 0.06) the point is almost in the plane of a large triangle and
// Arvo's inversion loses accuracy. Both bounds as in pbrt-v4.
constexpr float kMinSphericalSolidAngle = 3e-4f;
constexpr float kMaxSphericalSolidAngle = 6.22f;

bool sampleBySolidAngle(float solidAngle) {
    return solidAngle >= kMinSphericalSolidAngle && solidAngle <= kMaxSphericalSolidAngle;
}

float mean(const Color& c) {
    return (c.r + c.g + c.b) / 3.0f;
}
bool isBlack(const Color& c) {
    return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f;
}

// A local direction (z along the unit axis) in world space.
Vec3 aroundAxis(const Vec3& local, const Vec3& axis) {
    Vec3 b1, b2;
    orthonormalBasis(axis, b1, b2);
    return local.x * b1 + local.y * b2 + local.z * axis;
}

// Cone of the sun disk: 1 - cos r as 2 sin^2(r / 2), exact for tiny r.
float sunOneMinusCos(const Light& light) {
    const float s = std::sin(0.5f * light.angularRadius);
    return 2.0f * s * s;
}

// Radiance of the sun disk. A facing surface receives
//     E = integral over the cone of L cos(theta) d omega
//       = L 2 pi integral_0^r cos(theta) sin(theta) d theta = L pi sin^2 r,
// (= solid angle 2 pi (1 - cos r) times mean cosine (1 + cos r) / 2), so
// L = E / (pi sin^2 r).
Color sunRadiance(const Light& light) {
    const float s = std::sin(light.angularRadius);
    return light.irradiance / (kPi * s * s);
}

// Inside the sun's cone around axis = -direction: 1 - cos(angle to the axis) is
// half the squared chord |dir - axis|^2, which stays accurate for tiny angles.
bool inSunDisk(const Light& light, const Vec3& dir) {
    const Vec3 chord = glm::normalize(dir) + light.direction;
    return 0.5f * glm::dot(chord, chord) <= sunOneMinusCos(light);
}

// pbrt-v4's spot falloff: smoothstep in cos(theta) between the two cones;
// a hard edge at cosTotalWidth if the cones coincide.
float spotFalloff(const Light& light, float cosTheta) {
    if (cosTheta >= light.cosFalloffStart) return 1.0f;
    if (cosTheta <= light.cosTotalWidth) return 0.0f;
    const float t =
        (cosTheta - light.cosTotalWidth) / (light.cosFalloffStart - light.cosTotalWidth);
    return t * t * (3.0f - 2.0f * t);
}

// The triangle's geometric normal, length = twice its area (front: p0 p1 p2
// counter-clockwise).
Vec3 triangleCross(const Light& light) {
    return glm::cross(light.p1 - light.p0, light.p2 - light.p0);
}

// A one-sided triangle light is seen only from its front half-space.
bool seesFront(const Light& light, const Vec3& normal, const Vec3& p) {
    return light.twoSided || glm::dot(normal, p - light.p0) > 0.0f;
}

std::optional<LightLiSample> samplePointLike(const Light& light, const Vec3& p, const Color& I) {
    const Vec3 toLight = light.position - p;
    const float dist2 = glm::dot(toLight, toLight);
    if (!(dist2 > 0.0f)) return std::nullopt;  // at the light itself: no direction
    LightLiSample s;
    s.wi = toLight / std::sqrt(dist2);
    float falloff = 1.0f;
    if (light.type == Light::Type::Spot)
        falloff = spotFalloff(light, glm::dot(-s.wi, light.direction));
    if (falloff == 0.0f || isBlack(I)) return std::nullopt;
    s.L = falloff * I / dist2;  // inverse-square law: E = I / r^2
    s.pdf = 1.0f;
    s.pLight = light.position;
    return s;
}

std::optional<LightLiSample> sampleTriangle(const Light& light, const LightSampleContext& ctx,
                                            const Vec2& u) {
    const Vec3 n = triangleCross(light);
    const float twiceArea = glm::length(n);
    if (!(twiceArea > 0.0f) || !seesFront(light, n, ctx.p) || isBlack(light.radiance))
        return std::nullopt;
    LightLiSample s;
    const float solidAngle = triangleSolidAngle(ctx.p, light.p0, light.p1, light.p2);
    if (sampleBySolidAngle(solidAngle)) {
        const auto st =
            sampleSphericalTriangle(ctx.p, light.p0, light.p1, light.p2, u, solidAngle);
        if (!st) return std::nullopt;
        const Vec3 b = st->barycentrics;
        s.pLight = b.x * light.p0 + b.y * light.p1 + b.z * light.p2;
        const Vec3 d = s.pLight - ctx.p;
        if (!(glm::dot(d, d) > 0.0f)) return std::nullopt;
        s.wi = unitVector(d);
        s.pdf = st->pdf;
    } else {
        // Uniform in area (density 1 / A), as solid angle density: d omega =
        // |cos theta_light| dA / dist^2, so pdf = dist^2 / (|cos theta_light| A).
        const Vec3 b = sampleUniformTriangle(u);
        s.pLight = b.x * light.p0 + b.y * light.p1 + b.z * light.p2;
        const Vec3 d = s.pLight - ctx.p;
        const float dist2 = glm::dot(d, d);
        if (!(dist2 > 0.0f)) return std::nullopt;
        s.wi = d / std::sqrt(dist2);
        const float cosLight = std::abs(glm::dot(n, s.wi)) / twiceArea;
        s.pdf = dist2 / (cosLight * 0.5f * twiceArea);
        if (!std::isfinite(s.pdf)) return std::nullopt;  // grazing: cos = 0
    }
    s.L = triangleLe(light, -s.wi);
    if (isBlack(s.L)) return std::nullopt;
    return s;
}

std::optional<LightLiSample> sampleDirectional(const Light& light, const Vec2& u) {
    LightLiSample s;
    s.atInfinity = true;
    if (light.angularRadius == 0.0f) {
        s.wi = -light.direction;
        s.L = light.irradiance;
        s.pdf = 1.0f;
    } else {
        const float h = sunOneMinusCos(light);
        s.wi = glm::normalize(aroundAxis(sampleUniformConeHeight(u, h), -light.direction));
        // Rounding can put a sample on the cone's edge a hair outside it; drop
        // those (a ~1e-5 fraction at the sun's size) so that every sample is a
        // direction where infiniteLe and pdfLi see the disk.
        if (!inSunDisk(light, s.wi)) return std::nullopt;
        s.L = sunRadiance(light);
        s.pdf = uniformConeHeightPdf(h);
    }
    if (isBlack(s.L)) return std::nullopt;
    return s;
}

std::optional<LightLiSample> sampleEnvironment(const Light& light, const Vec2& u) {
    if (!light.environment) return std::nullopt;
    LightLiSample s;
    s.atInfinity = true;
    float mapPdf;
    const Vec3 dMap = light.environment->sample(u, mapPdf);
    if (!(mapPdf > 0.0f)) return std::nullopt;
    // The inverse of a rotation is its transpose.
    s.wi = glm::normalize(glm::transpose(light.worldToEnvironment) * dMap);
    // Radiance and density as infiniteLe and pdfLi compute them for s.wi, so
    // that MIS weights agree bit for bit. They differ from the map's own values
    // only where rotating back lands across a texel edge (a ~1e-6 fraction).
    s.pdf = light.environment->pdf(light.worldToEnvironment * s.wi);
    s.L = infiniteLe(light, s.wi);
    if (!(s.pdf > 0.0f) || isBlack(s.L)) return std::nullopt;
    return s;
}

float skyPdf(const LightSampleContext& ctx, const Vec3& wi) {
    if (glm::dot(ctx.n, ctx.n) > 0.0f)
        return cosineHemispherePdf(glm::dot(glm::normalize(ctx.n), wi));
    return kUniformSpherePdf;
}

std::optional<LightLiSample> sampleSky(const Light& light, const LightSampleContext& ctx,
                                       const Vec2& u) {
    if (isBlack(light.radiance)) return std::nullopt;
    LightLiSample s;
    s.atInfinity = true;
    s.L = light.radiance;
    if (glm::dot(ctx.n, ctx.n) > 0.0f)
        s.wi = glm::normalize(aroundAxis(sampleCosineHemisphere(u), glm::normalize(ctx.n)));
    else
        s.wi = sampleUniformSphere(u);
    s.pdf = skyPdf(ctx, s.wi);                 // the formula pdfLi uses, so both agree exactly
    if (!(s.pdf > 0.0f)) return std::nullopt;  // on the horizon
    return s;
}

bool isUnit(const Vec3& v) {
    return isFinite(v) && std::abs(glm::length(v) - 1.0f) < 1e-3f;
}

void checkColor(size_t index, const char* what, const Color& c) {
    if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
        fail("light ", index, ": ", what, " (", c.r, ", ", c.g, ", ", c.b,
             ") must be finite and >= 0");
}

void validate(size_t index, const Light& light) {
    switch (light.type) {
        case Light::Type::Point:
            checkColor(index, "intensity", light.intensity);
            break;
        case Light::Type::Spot:
            checkColor(index, "intensity", light.intensity);
            if (!isUnit(light.direction))
                fail("light ", index, ": spot direction must be a unit vector");
            if (!(-1.0f <= light.cosTotalWidth && light.cosTotalWidth <= light.cosFalloffStart &&
                  light.cosFalloffStart <= 1.0f))
                fail("light ", index, ": spot needs -1 <= cosTotalWidth (", light.cosTotalWidth,
                     ") <= cosFalloffStart (", light.cosFalloffStart, ") <= 1");
            break;
        case Light::Type::Directional:
            checkColor(index, "irradiance", light.irradiance);
            if (!isUnit(light.direction))
                fail("light ", index, ": directional direction must be a unit vector");
            // Beyond pi/2 the disk would cover more than a facing hemisphere and
            // E = L pi sin^2 r would no longer hold.
            if (!(light.angularRadius >= 0.0f && light.angularRadius <= 0.5f * kPi))
                fail("light ", index, ": angular radius ", light.angularRadius,
                     " must lie in [0, pi/2]");
            break;
        case Light::Type::Triangle:
            checkColor(index, "radiance", light.radiance);
            if (!isFinite(light.p0) || !isFinite(light.p1) || !isFinite(light.p2))
                fail("light ", index, ": triangle vertices must be finite");
            break;
        case Light::Type::Environment: {
            checkColor(index, "scale", light.scale);
            if (!light.environment) fail("light ", index, ": environment light without a map");
            const Mat3& m = light.worldToEnvironment;
            const Mat3 shouldBeIdentity = glm::transpose(m) * m;
            float error = 0.0f;
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r)
                    error =
                        std::max(error, std::abs(shouldBeIdentity[c][r] - (c == r ? 1.0f : 0.0f)));
            // 1e-3: a rotation typed with 4-5 significant digits passes.
            if (!(error < 1e-3f) || !(glm::determinant(m) > 0.0f))
                fail("light ", index, ": worldToEnvironment must be a rotation");
            break;
        }
        case Light::Type::Sky:
            checkColor(index, "radiance", light.radiance);
            break;
    }
}

}  // namespace

bool Light::isDelta() const {
    return type == Type::Point || type == Type::Spot ||
           (type == Type::Directional && angularRadius == 0.0f);
}

bool Light::isInfinite() const {
    return type == Type::Directional || type == Type::Environment || type == Type::Sky;
}

std::optional<LightLiSample> sampleLi(const Light& light, const LightSampleContext& ctx,
                                      const Vec2& u) {
    switch (light.type) {
        case Light::Type::Point:
        case Light::Type::Spot:
            return samplePointLike(light, ctx.p, light.intensity);
        case Light::Type::Directional:
            return sampleDirectional(light, u);
        case Light::Type::Triangle:
            return sampleTriangle(light, ctx, u);
        case Light::Type::Environment:
            return sampleEnvironment(light, u);
        case Light::Type::Sky:
            return sampleSky(light, ctx, u);
    }
    return std::nullopt;
}

float pdfLi(const Light& light, const LightSampleContext& ctx, const Vec3& wi, const Vec3& pLight) {
    switch (light.type) {
        case Light::Type::Point:
        case Light::Type::Spot:
            return 0.0f;
        case Light::Type::Directional:
            if (light.angularRadius == 0.0f || !inSunDisk(light, wi)) return 0.0f;
            return uniformConeHeightPdf(sunOneMinusCos(light));
        case Light::Type::Triangle: {
            // The decision rule of sampleTriangle, on the same inputs.
            const Vec3 n = triangleCross(light);
            const float twiceArea = glm::length(n);
            if (!(twiceArea > 0.0f) || !seesFront(light, n, ctx.p) || isBlack(light.radiance))
                return 0.0f;
            const float solidAngle = triangleSolidAngle(ctx.p, light.p0, light.p1, light.p2);
            if (sampleBySolidAngle(solidAngle)) return 1.0f / solidAngle;
            const Vec3 d = pLight - ctx.p;
            const float cosLight = std::abs(glm::dot(n, wi)) / twiceArea;
            const float pdf = glm::dot(d, d) / (cosLight * 0.5f * twiceArea);
            return std::isfinite(pdf) ? pdf : 0.0f;
        }
        case Light::Type::Environment:
            if (!light.environment) return 0.0f;
            return light.environment->pdf(light.worldToEnvironment * wi);
        case Light::Type::Sky:
            return isBlack(light.radiance) ? 0.0f : skyPdf(ctx, wi);
    }
    return 0.0f;
}

Color infiniteLe(const Light& light, const Vec3& dir) {
    switch (light.type) {
        case Light::Type::Directional:
            if (light.angularRadius > 0.0f && inSunDisk(light, dir)) return sunRadiance(light);
            return Color(0.0f);
        case Light::Type::Environment:
            if (!light.environment) return Color(0.0f);
            return light.scale * light.environment->lookup(light.worldToEnvironment * dir);
        case Light::Type::Sky:
            return light.radiance;
        default:
            return Color(0.0f);
    }
}

Color triangleLe(const Light& light, const Vec3& w) {
    if (light.type != Light::Type::Triangle) return Color(0.0f);
    const float cosTheta = glm::dot(triangleCross(light), w);
    const bool emits = light.twoSided ? cosTheta != 0.0f : cosTheta > 0.0f;
    return emits ? light.radiance : Color(0.0f);
}

float lightPower(const Light& light, const Bounds3& sceneBounds) {
    const float radius = 0.5f * glm::length(sceneBounds.diagonal());
    const float disk = kPi * radius * radius;  // the bounding sphere's cross-section
    switch (light.type) {
        case Light::Type::Point:
            return 4.0f * kPi * mean(light.intensity);
        case Light::Type::Spot:
            // 2 pi times the integral of the falloff over cos(theta): 1 on
            // [cosStart, 1], and smoothstep, whose mean on its interval is 1/2.
            return 2.0f * kPi * mean(light.intensity) *
                   ((1.0f - light.cosFalloffStart) +
                    0.5f * (light.cosFalloffStart - light.cosTotalWidth));
        case Light::Type::Directional:
            return disk * mean(light.irradiance);
        case Light::Type::Triangle: {
            // A Lambertian emitter sends pi L per unit area from each emitting face.
            const float area = 0.5f * glm::length(triangleCross(light));
            return kPi * area * mean(light.radiance) * (light.twoSided ? 2.0f : 1.0f);
        }
        case Light::Type::Environment:
            if (!light.environment) return 0.0f;
            return 4.0f * kPi * disk * mean(light.scale * light.environment->average());
        case Light::Type::Sky:
            return 4.0f * kPi * disk * mean(light.radiance);
    }
    return 0.0f;
}

LightSet::LightSet(std::vector<Light> lights, const Bounds3& sceneBounds)
    : lights_(std::move(lights)) {
    if (lights_.empty()) return;
    if (lights_.size() > UINT32_MAX) fail("too many lights: ", lights_.size());
    std::vector<float> powers(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
        validate(i, lights_[i]);
        powers[i] = lightPower(lights_[i], sceneBounds);
        if (!std::isfinite(powers[i]) || powers[i] < 0.0f)
            fail("light ", i, ": power ", powers[i], " is not finite and >= 0");
        if (lights_[i].isInfinite()) infinite_.push_back(static_cast<uint32_t>(i));
    }
    distribution_ = Distribution1D(std::move(powers));  // all zero: uniform
}

std::optional<std::pair<uint32_t, float>> LightSet::choose(float u) const {
    if (lights_.empty()) return std::nullopt;
    float pmf;
    const size_t index = distribution_.sampleDiscrete(u, pmf);
    return std::make_pair(static_cast<uint32_t>(index), pmf);
}

float LightSet::pmf(uint32_t index) const {
    return distribution_.pmf(index);
}

}  // namespace strahl
