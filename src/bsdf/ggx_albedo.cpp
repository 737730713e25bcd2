// Tabulated albedo of the GGX + Schlick reflection lobe (see ggx_albedo.h).
// Each node integrates the lobe by stratified visible-normal sampling: with m
// drawn from D_wo, the estimator of E is F(wo.m) G2(wo, wi) / G1(wo) for wi
// above the horizon (docs/materials.md, "Metallic-roughness").

#include "strahl/bsdf/ggx_albedo.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/bsdf/microfacet.h"

namespace strahl {

namespace {

// 48 cosine nodes keep the linear-interpolation error of the smooth row's
// (1 - mu)^5 below 1.1e-3; 16 roughness nodes in r = sqrt(alpha), where E
// varies about evenly; 32 x 32 strata per node bound the quadrature error near
// 1e-3 (the integrand jumps where wi crosses the horizon).
constexpr int kMuNodes = 48;
constexpr int kRoughnessNodes = 16;
constexpr int kStrata = 32;

struct AlbedoPair {
    float e1 = 0.0f, e5 = 0.0f;
};

class AlbedoTable {
public:
    AlbedoTable() {
        for (int j = 0; j < kRoughnessNodes; ++j) {
            const float r = static_cast<float>(j) / (kRoughnessNodes - 1);
            for (int i = 0; i < kMuNodes; ++i) node(i, j) = integrate(muNode(i), r * r);
            for (int i = 0; i + 1 < kMuNodes; ++i) {
                // 2 * integral of the linear interpolant times mu over [mu0, mu1]:
                // h (a (2 mu0 + mu1) + b (mu0 + 2 mu1)) / 3.
                const float mu0 = muNode(i), mu1 = muNode(i + 1), h = mu1 - mu0;
                const AlbedoPair& a = node(i, j);
                const AlbedoPair& b = node(i + 1, j);
                average_[j].e1 += h * (a.e1 * (2 * mu0 + mu1) + b.e1 * (mu0 + 2 * mu1)) / 3.0f;
                average_[j].e5 += h * (a.e5 * (2 * mu0 + mu1) + b.e5 * (mu0 + 2 * mu1)) / 3.0f;
            }
        }
    }

    float albedo(float mu, float alpha, float f0) const {
        const Lookup r = roughnessLookup(alpha);
        const float x = std::clamp(mu, 0.0f, 1.0f) * (kMuNodes - 1);
        const int i = std::min(static_cast<int>(x), kMuNodes - 2);
        const float t = x - static_cast<float>(i);
        auto row = [&](int j) {
            const AlbedoPair& a = node(i, j);
            const AlbedoPair& b = node(i + 1, j);
            return combine(a, f0) * (1.0f - t) + combine(b, f0) * t;
        };
        return row(r.index) * (1.0f - r.t) + row(r.index + 1) * r.t;
    }

    float average(float alpha, float f0) const {
        const Lookup r = roughnessLookup(alpha);
        return combine(average_[r.index], f0) * (1.0f - r.t) +
               combine(average_[r.index + 1], f0) * r.t;
    }

private:
    struct Lookup {
        int index;
        float t;
    };

    static float muNode(int i) { return static_cast<float>(i) / (kMuNodes - 1); }
    static float combine(const AlbedoPair& p, float f0) { return f0 * p.e1 + (1.0f - f0) * p.e5; }

    static Lookup roughnessLookup(float alpha) {
        const float x = std::sqrt(std::clamp(alpha, 0.0f, 1.0f)) * (kRoughnessNodes - 1);
        const int j = std::min(static_cast<int>(x), kRoughnessNodes - 2);
        return {j, x - static_cast<float>(j)};
    }

    static AlbedoPair integrate(float mu, float alpha) {
        if (alpha < MicrofacetDistribution::kSmoothAlpha) return {1.0f, schlickWeight(mu)};
        // The horizon itself is degenerate; its limit is approached from 1e-4.
        const float cosO = std::max(mu, 1e-4f);
        const Vec3 wo(std::sqrt(1.0f - cosO * cosO), 0.0f, cosO);
        const MicrofacetDistribution ggx(alpha, alpha);
        const float g1 = ggx.g1(wo);
        double e1 = 0.0, e5 = 0.0;
        for (int sy = 0; sy < kStrata; ++sy) {
            for (int sx = 0; sx < kStrata; ++sx) {
                const Vec2 u((static_cast<float>(sx) + 0.5f) / kStrata,
                             (static_cast<float>(sy) + 0.5f) / kStrata);
                const Vec3 m = ggx.sampleNormal(wo, u);
                const float cosOm = glm::dot(wo, m);
                const Vec3 wi = reflectDir(wo, m);
                if (cosOm <= 0.0f || wi.z <= 0.0f) continue;
                const float weight = ggx.g(wo, wi) / g1;
                e1 += weight;
                e5 += weight * schlickWeight(cosOm);
            }
        }
        constexpr double kInvCount = 1.0 / (kStrata * kStrata);
        return {static_cast<float>(e1 * kInvCount), static_cast<float>(e5 * kInvCount)};
    }

    AlbedoPair& node(int i, int j) { return nodes_[static_cast<size_t>(j * kMuNodes + i)]; }
    const AlbedoPair& node(int i, int j) const {
        return nodes_[static_cast<size_t>(j * kMuNodes + i)];
    }

    std::array<AlbedoPair, kMuNodes * kRoughnessNodes> nodes_{};
    std::array<AlbedoPair, kRoughnessNodes> average_{};
};

const AlbedoTable& albedoTable() {
    static const AlbedoTable table;  // built once, thread-safe (C++11 magic static)
    return table;
}

}  // namespace

float ggxSchlickAlbedo(float cosThetaO, float alpha, float f0) {
    if (alpha < MicrofacetDistribution::kSmoothAlpha) return fresnelSchlick(f0, cosThetaO);
    return albedoTable().albedo(cosThetaO, alpha, f0);
}

float ggxSchlickAverageAlbedo(float alpha, float f0) {
    // Smooth: 2 integral (1 - mu)^5 mu dmu = 2 B(2, 6) = 1 / 21.
    if (alpha < MicrofacetDistribution::kSmoothAlpha) return f0 + (1.0f - f0) / 21.0f;
    return albedoTable().average(alpha, f0);
}

}  // namespace strahl
