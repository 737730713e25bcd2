// Secondary rays against the surface they leave: for every kind of sphere the
// renderer can build and at scales from 1e-3 to 1e3 (far from the origin),
// rays spawned with spawnRay()/spawnRayTo() from the error bound pError of a
// hit must never hit that point's own surface again where the geometry says
// they cannot:
//  * reflected rays (the mirror direction, random and grazing directions in
//    Ng's hemisphere) leave a convex surface for good;
//  * a refracted ray (Snell, eta 1.5) hits the far side, about one chord
//    away — never the entry point again at t ≈ 0 — and rays leaving that
//    far-side point outwards escape;
//  * shadow rays to a point light in the visible hemisphere are unoccluded.
// The kinds: an icosphere mesh; the implicit sphere (closed form); the
// superellipsoid with e1 = e2 = 1, the same sphere found by the interval root
// finder; the parametric sphere intersected directly (Newton) and tessellated.
// The root finder and Newton also run at a coarse tolerance, where a pError
// without the solver's tolerance lets about 1 in 1000 (implicit) and 1 in 4
// (direct) of the spawned rays find their own surface again.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "strahl/core/rng.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "test_support.h"

namespace strahl {
namespace {

enum class Kind {
    Icosphere,
    Implicit,
    ImplicitSearched,
    ImplicitSearchedCoarse,
    DirectParametric,
    DirectParametricCoarse,
    TessellatedParametric
};

const char* kindName(Kind kind) {
    switch (kind) {
        case Kind::Icosphere:
            return "icosphere";
        case Kind::Implicit:
            return "implicit";
        case Kind::ImplicitSearched:
            return "implicit_searched";
        case Kind::ImplicitSearchedCoarse:
            return "implicit_searched_coarse";
        case Kind::DirectParametricCoarse:
            return "direct_parametric_coarse";
        case Kind::DirectParametric:
            return "direct_parametric";
        case Kind::TessellatedParametric:
            return "tessellated_parametric";
    }
    return "?";
}

// Triangles approximate the sphere: their hits lie up to the chord error inside
// it, so the far-side distance is only checked against half the chord.
bool isMesh(Kind kind) {
    return kind == Kind::Icosphere || kind == Kind::TessellatedParametric;
}

struct Placement {
    const char* name;
    double radius;
    DVec3 centre;
};

// Unit size at the origin; a millimetre sphere (coordinates far below 1); a
// 1000-unit sphere 2e4 units from the origin, where a float's ulp (~2e-3) is
// a visible fraction of the error budget.
const std::array<Placement, 3> kPlacements = {
    Placement{"r1_origin", 1.0, DVec3(0.0)},
    Placement{"r1e-3_origin", 1e-3, DVec3(0.0)},
    Placement{"r1e3_far", 1e3, DVec3(1e4, -3e3, 2e4)},
};

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

std::string vec(const DVec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g]", v.x, v.y, v.z);
    return text;
}

// The unit icosphere: an icosahedron with every triangle split in four
// `levels` times, new vertices pushed onto the sphere. Outward winding.
void icosphere(int levels, std::vector<DVec3>& positions, std::vector<uint32_t>& indices) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;  // golden ratio: the icosahedron's corners
    positions = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (DVec3& p : positions) p = glm::normalize(p);
    indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            positions.push_back(glm::normalize(positions[a] + positions[b]));
            const auto index = static_cast<uint32_t>(positions.size() - 1);
            midpoints.emplace(key, index);
            return index;
        };
        std::vector<uint32_t> finer;
        for (size_t t = 0; t < indices.size(); t += 3) {
            const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
            const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        indices = std::move(finer);
    }
}

std::string shapeJson(Kind kind, const Placement& at) {
    const std::string transform = R"(, "transform": [ { "translate": )" + vec(at.centre) + " } ]";
    const std::string sphere = R"({ "type": "sphere", "radius": )" + number(at.radius) + " }";
    switch (kind) {
        case Kind::Icosphere: {
            std::vector<DVec3> positions;
            std::vector<uint32_t> indices;
            icosphere(4, positions, indices);  // 5120 triangles: chord error ~1e-3 of the radius
            std::ostringstream s;
            s << R"({ "type": "mesh", "positions": [)";
            for (size_t i = 0; i < positions.size(); ++i)
                s << (i ? ", " : "") << vec(at.radius * positions[i]);
            s << R"(], "indices": [)";
            for (size_t i = 0; i < indices.size(); ++i) s << (i ? ", " : "") << indices[i];
            s << "]" << transform << " }";
            return s.str();
        }
        case Kind::Implicit:
            return R"({ "type": "implicit", "surface": )" + sphere + transform + " }";
        case Kind::ImplicitSearched:
        case Kind::ImplicitSearchedCoarse: {
            const std::string tolerance =
                kind == Kind::ImplicitSearchedCoarse ? R"(, "tolerance": 1e-2)" : "";
            return R"({ "type": "implicit", "surface": { "type": "superellipsoid", "radii": )" +
                   vec(DVec3(at.radius)) + R"(, "e1": 1, "e2": 1 })" + tolerance + transform + " }";
        }
        case Kind::DirectParametric:
            return R"({ "type": "parametric", "mode": "direct", "surface": )" + sphere + transform +
                   " }";
        case Kind::DirectParametricCoarse:
            return R"({ "type": "parametric", "mode": "direct", "direct": { "tolerance": 1e-3 },)"
                   R"( "surface": )" +
                   sphere + transform + " }";
        case Kind::TessellatedParametric:
            return R"({ "type": "parametric", "mode": "tessellated", "surface": )" + sphere +
                   transform + " }";
    }
    return {};
}

World buildSphereWorld(Kind kind, const Placement& at) {
    const std::string text = R"({
      "camera": { "eye": )" + vec(at.centre + DVec3(0.0, 0.0, 4.0 * at.radius)) +
                             R"(, "look_at": )" + vec(at.centre) + R"(, "fov": 40 },
      "film": { "width": 64, "height": 64 },
      "shapes": [ )" + shapeJson(kind, at) +
                             R"( ]
    })";
    const SceneDesc desc = parseSceneText(
        text, test::scratchDir("secondary") / (std::string(kindName(kind)) + ".json"));
    BuildOptions build;
    build.threads = 1;
    return buildWorld(desc, build);
}

// ---- sampling and optics, in double -------------------------------------------

double uniform(Pcg32& rng) {
    return static_cast<double>(rng.nextFloat());
}

DVec3 uniformSphere(Pcg32& rng) {
    const double z = 1.0 - 2.0 * uniform(rng);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * num::kPiD * uniform(rng);
    return DVec3(r * std::cos(phi), r * std::sin(phi), z);
}

// Uniform over the hemisphere around n (unit).
DVec3 uniformHemisphere(Pcg32& rng, const DVec3& n) {
    const DVec3 w = uniformSphere(rng);
    return glm::dot(w, n) < 0.0 ? -w : w;
}

// Nearly tangent to the surface with normal n: cosine to n in (0, 0.02]. Rays
// like these stay within a solver's tolerance of the surface longest, so they
// find an error box that is too small (uniform directions rarely graze).
DVec3 grazingDirection(Pcg32& rng, const DVec3& n) {
    const DVec3 axis = std::abs(n.x) < 0.5 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
    const DVec3 t1 = glm::normalize(glm::cross(n, axis)), t2 = glm::cross(n, t1);
    const double phi = 2.0 * num::kPiD * uniform(rng);
    const double cosine = 0.02 * (1.0 - uniform(rng));  // (0, 0.02]: never exactly tangent
    const double sine = std::sqrt(1.0 - cosine * cosine);
    return sine * (std::cos(phi) * t1 + std::sin(phi) * t2) + cosine * n;
}

// The k-th of the directions leaving a surface with normal n: 0 is `first`,
// the last is grazing, the others are uniform over the hemisphere.
DVec3 leavingDirection(int k, int count, const DVec3& first, Pcg32& rng, const DVec3& n) {
    if (k == 0) return first;
    return k + 1 == count ? grazingDirection(rng, n) : uniformHemisphere(rng, n);
}

// Snell refraction of unit d through a surface with unit normal n facing d
// (dot(d, n) < 0), eta = n_incident / n_transmitted. False on total internal
// reflection.
bool refract(const DVec3& d, const DVec3& n, double eta, DVec3& out) {
    const double cosI = -glm::dot(d, n);
    const double k = 1.0 - eta * eta * (1.0 - cosI * cosI);
    if (k < 0.0) return false;
    out = glm::normalize(eta * d + (eta * cosI - std::sqrt(k)) * n);
    return true;
}

// Distance from o (inside the sphere) along unit w to the sphere.
double exitDistance(const DVec3& o, const DVec3& w, const DVec3& centre, double radius) {
    const DVec3 oc = o - centre;
    const double b = glm::dot(oc, w), c = glm::dot(oc, oc) - radius * radius;
    return -b + std::sqrt(std::max(0.0, b * b - c));
}

Ray rayOf(const DVec3& origin, const DVec3& dir) {
    Ray ray;
    ray.origin = Vec3(origin);
    ray.dir = Vec3(glm::normalize(dir));
    return ray;
}

// ---- the experiment -----------------------------------------------------------

struct Counts {
    int primaryHits = 0;
    // Hits whose outward normal faces along the ray: a ray passing a
    // silhouette within the solver's tolerance (direct mode, coarse
    // tolerance) counts as hitting it. No mirror or refraction then.
    int grazingHits = 0;
    int inwardNormals = 0;  // Ng pointing into the sphere: a failure
    int reflected = 0, reflectedSelfHits = 0;
    int refracted = 0, refractedMisses = 0, refractedNearHits = 0, refractedWrongDistance = 0;
    int exiting = 0, exitingSelfHits = 0;
    int shadow = 0, shadowOccluded = 0;

    int failures() const {
        return inwardNormals + reflectedSelfHits + refractedMisses + refractedNearHits +
               refractedWrongDistance + exitingSelfHits + shadowOccluded;
    }
    std::string describe() const {
        std::ostringstream s;
        s << primaryHits << " hits (" << grazingHits << " grazing, " << inwardNormals
          << " inward Ng); reflected " << reflectedSelfHits << "/" << reflected
          << " self-hits; refracted " << refractedMisses << " misses, " << refractedNearHits
          << " at t < chord/2, " << refractedWrongDistance << " off the chord (of " << refracted
          << "); exiting " << exitingSelfHits << "/" << exiting << " self-hits; shadow "
          << shadowOccluded << "/" << shadow << " occluded";
        return s.str();
    }
};

// Primary rays per placement: ~2/3 hit, and each hit spawns 13 secondary rays.
// The direct parametric mode gets fewer: its grazing rays split sub-patches
// down to 2^-8 (parametric_shape.cpp) and cost ~0.3 ms each.
int primaryRays(Kind kind) {
    return kind == Kind::DirectParametric || kind == Kind::DirectParametricCoarse ? 600 : 3000;
}
constexpr int kReflections = 5;  // mirror, 3 uniform, 1 grazing per hit
constexpr int kExits = 4;        // refracted out, 2 uniform, 1 grazing per far-side hit
constexpr int kShadowRays = 3;
constexpr double kEta = 1.5;
// The analytic kinds hit the true sphere: their far-side distance must match
// the chord to 1e-3 relative (the hit point is good to ~1e-6).
constexpr double kChordTolerance = 1e-3;

// The sphere's Ng, which all kinds orient outwards (implicit: +grad f; parametric:
// d_u f x d_v f; meshes: the winding), unit, in double.
DVec3 outwardNormal(const SurfaceInteraction& si, const DVec3& centre, int& inwardNormals) {
    const DVec3 n = glm::normalize(DVec3(si.Ng));
    if (glm::dot(n, DVec3(si.p) - centre) > 0.0) return n;
    ++inwardNormals;
    return -n;
}

Counts shootAt(const World& world, Kind kind, const Placement& at, uint64_t seed) {
    Counts n;
    const Accel& accel = *world.accel;
    const double R = at.radius;
    const DVec3 c = at.centre;
    for (int i = 0; i < primaryRays(kind); ++i) {
        // One stream per primary ray: the rays are the same for every kind.
        Pcg32 rng(seed, static_cast<uint64_t>(i));
        // From 4 radii away towards a random point of the sphere's box.
        const DVec3 from = c + 4.0 * R * uniformSphere(rng);
        const DVec3 target = c + 1.1 * R *
                                     DVec3(2.0 * uniform(rng) - 1.0, 2.0 * uniform(rng) - 1.0,
                                           2.0 * uniform(rng) - 1.0);
        const Ray primary = rayOf(from, target - from);
        const Hit hit = accel.intersect(primary);
        if (!hit.valid()) continue;
        ++n.primaryHits;
        const SurfaceInteraction si = world.interaction(primary, hit);
        const DVec3 ng = outwardNormal(si, c, n.inwardNormals);
        const DVec3 d = DVec3(primary.dir);
        const DVec3 p(si.p);
        const bool entering = glm::dot(d, ng) < 0.0;
        if (!entering) ++n.grazingHits;

        // Reflection: the mirror direction, then random and grazing ones.
        const DVec3 mirror = d - 2.0 * glm::dot(d, ng) * ng;
        for (int k = entering ? 0 : 1; k < kReflections; ++k) {
            const DVec3 w = leavingDirection(k, kReflections, mirror, rng, ng);
            ++n.reflected;
            if (accel.occluded(spawnRay(si.p, si.pError, si.Ng, Vec3(w)))) ++n.reflectedSelfHits;
        }

        // Refraction into the sphere, to the far side.
        DVec3 inside;
        if (entering && refract(d, ng, 1.0 / kEta, inside)) {
            ++n.refracted;
            const Ray in = spawnRay(si.p, si.pError, si.Ng, Vec3(inside));
            const Hit far = accel.intersect(in);
            const double chord = exitDistance(DVec3(in.origin), DVec3(in.dir), c, R);
            if (!far.valid()) {
                ++n.refractedMisses;
            } else if (far.t < 0.5 * chord) {
                ++n.refractedNearHits;
            } else {
                if (!isMesh(kind) && std::abs(far.t - chord) > kChordTolerance * chord)
                    ++n.refractedWrongDistance;
                const SurfaceInteraction out = world.interaction(in, far);
                const DVec3 nOut = outwardNormal(out, c, n.inwardNormals);
                const DVec3 w = DVec3(in.dir);
                // Leaving: refracted out (the normal facing w is -nOut), the
                // normal itself on total internal reflection (possible on a
                // mesh's facets), then random and grazing outward directions.
                DVec3 leave;
                if (!refract(w, -nOut, kEta, leave)) leave = nOut;
                for (int k = 0; k < kExits; ++k) {
                    const DVec3 dir = leavingDirection(k, kExits, leave, rng, nOut);
                    ++n.exiting;
                    if (accel.occluded(spawnRay(out.p, out.pError, out.Ng, Vec3(dir))))
                        ++n.exitingSelfHits;
                }
            }
        }

        // Shadow rays to point lights in front of the tangent plane: between
        // 0.01 and 3 radii along the normal, up to 2 radii sideways.
        const DVec3 axis = std::abs(ng.x) < 0.5 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
        const DVec3 t1 = glm::normalize(glm::cross(ng, axis)), t2 = glm::cross(ng, t1);
        for (int k = 0; k < kShadowRays; ++k) {
            const double up = R * (0.01 + 2.99 * uniform(rng));
            const double a = R * (4.0 * uniform(rng) - 2.0), b = R * (4.0 * uniform(rng) - 2.0);
            const DVec3 light = p + up * ng + a * t1 + b * t2;
            ++n.shadow;
            if (accel.occluded(spawnRayTo(si.p, si.pError, si.Ng, Vec3(light)))) ++n.shadowOccluded;
        }
    }
    return n;
}

class SecondaryRays : public ::testing::TestWithParam<Kind> {};

TEST_P(SecondaryRays, NeverRehitTheirOwnSphere) {
    const Kind kind = GetParam();
    uint64_t seed = 17;
    for (const Placement& at : kPlacements) {
        const World world = buildSphereWorld(kind, at);
        const Counts n = shootAt(world, kind, at, seed++);
        std::printf("[ secondary ] %-22s %-13s %s\n", kindName(kind), at.name,
                    n.describe().c_str());
        // About 0.6 of the rays aimed at the sphere's box hit it.
        EXPECT_GT(n.primaryHits, primaryRays(kind) / 3) << at.name;
        EXPECT_EQ(n.refracted, n.primaryHits - n.grazingHits)
            << at.name << ": eta > 1 always refracts in";
        EXPECT_EQ(n.failures(), 0) << kindName(kind) << " " << at.name << ": " << n.describe();
    }
}

INSTANTIATE_TEST_SUITE_P(Spheres, SecondaryRays,
                         ::testing::Values(Kind::Icosphere, Kind::Implicit, Kind::ImplicitSearched,
                                           Kind::ImplicitSearchedCoarse, Kind::DirectParametric,
                                           Kind::DirectParametricCoarse,
                                           Kind::TessellatedParametric),
                         [](const ::testing::TestParamInfo<Kind>& p) {
                             return std::string(kindName(p.param));
                         });

}  // namespace
}  // namespace strahl
