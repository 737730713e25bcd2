// The coated conductor's per-material quantities and the table of the light a
// rough metal keeps inside its coat. Derivation in docs/materials.md,
// "Coated conductor".

#include "strahl/bsdf/coated_base.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "quadrature.h"
#include "strahl/bsdf/fresnel.h"
#include "strahl/bsdf/local_frame.h"
#include "strahl/core/error.h"

namespace strahl {

// trapped(alpha_j, cos theta_i outside) for a coat index and microfacet
// model, and per roughness the cosine-weighted mean over the inside
// hemisphere of what does not leave after a bounce. Rows are integrated when
// first asked for (a material of one roughness needs two, about 30 ms), once,
// whichever thread asks.
struct CoatedBase::EscapeTable {
    struct Row {
        std::once_flag once;
        std::array<float, kCosines> trapped{};
        float meanTrapped = 0.0f;
    };
    float coatEta;
    MicrofacetModel model;
    mutable std::array<Row, kRoughnesses> rows;

    const Row& row(int j) const;
};

namespace {

// Nodes per dimension of the quadrature over the metal's sampled normals. The
// integrand has a kink where the reflected direction crosses the critical
// angle: with 32 x 32 a white coated metal reflected up to 1.012, with
// 48 x 48 0.991 to 1.007 (64 x 64: 0.997 to 1.009, twice the time).
constexpr int kNormalNodes = 48;
// Nodes of the one-dimensional integrals over cos theta (smooth integrands).
constexpr int kCosineNodes = 32;

// The i-th cosine of CoatedBase's tables, i / (kCosines - 1), kept off the horizon.
float coatedBaseCosine(int i) {
    return std::max(1e-4f, float(i) / float(CoatedBase::kCosines - 1));
}

float roughnessAlpha(int j) {
    const float r = float(j) / float(CoatedBase::kRoughnesses - 1);
    return r * r;
}

// The fraction of light leaving through the coat from inside at cos mu: the
// coat's transmittance from below (0 beyond the critical angle).
float transmittanceFromInside(float mu, float coatEta) {
    return 1.0f - fresnelDielectric(mu, 1.0f / coatEta);
}

// What a white metal of this roughness lit from inside at cos mu sends out
// through the coat in one bounce: the integral of T(wi') f cos over the
// reflection lobe, with m drawn from the visible normals (the weight
// D (wo.m) / (mu pdf) G2 = G2 / G1).
float escapeAfterOneBounce(const MicrofacetDistribution& metal, float mu, float coatEta,
                           const std::vector<QuadratureNode>& nodes) {
    const Vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
    double sum = 0.0;
    forVisibleNormals(metal, wo, nodes, [&](const Vec3& m, float, double weight) {
        const Vec3 wi = reflectDir(wo, m);
        if (wi.z > 0.0f) sum += weight * metal.g(wo, wi) * transmittanceFromInside(wi.z, coatEta);
    });
    return float(sum);
}

// cos theta' inside the coat of the direction at cos theta outside (Snell).
float insideCosine(float cosOutside, float coatEta) {
    return std::sqrt(std::max(0.0f, 1.0f - (1.0f - cosOutside * cosOutside) / (coatEta * coatEta)));
}

// Tables are shared between materials of the same coat index and model.
std::shared_ptr<const CoatedBase::EscapeTable> sharedTable(float coatEta, MicrofacetModel model) {
    static std::mutex mutex;
    static std::vector<std::shared_ptr<const CoatedBase::EscapeTable>> tables;
    const std::lock_guard lock(mutex);
    for (const auto& t : tables)
        if (t->coatEta == coatEta && t->model.type == model.type && t->model.masking == model.masking) return t;
    auto table = std::make_shared<CoatedBase::EscapeTable>();
    table->coatEta = coatEta;
    table->model = model;
    tables.push_back(std::move(table));
    return tables.back();
}

// 2 integral_0^1 g(mu) mu dmu by Gauss-Legendre.
template <typename Fn>
double cosineWeighted(Fn&& g) {
    static const std::vector<QuadratureNode> nodes = gaussLegendre01(kCosineNodes);
    double sum = 0.0;
    for (const QuadratureNode& n : nodes) sum += n.w * g(float(n.x)) * n.x;
    return 2.0 * sum;
}

void requireColor(const char* what, const Color& c) {
    if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
        fail("coated conductor: ", what, " must be finite and non-negative, got (", c.r, ", ", c.g, ", ", c.b, ")");
}

}  // namespace

const CoatedBase::EscapeTable::Row& CoatedBase::EscapeTable::row(int j) const {
    Row& r = rows[size_t(j)];
    std::call_once(r.once, [&] {
        static const std::vector<QuadratureNode> nodes = gaussLegendre01(kNormalNodes);
        static const std::vector<QuadratureNode> cosineNodes = gaussLegendre01(kCosineNodes);
        const MicrofacetDistribution metal(roughnessAlpha(j), roughnessAlpha(j), model);
        // What does not leave after one bounce, lit from inside at cos mu.
        const auto trapped = [&](float mu) {
            // A smooth metal reflects everything to the mirror direction, at mu.
            const float escape = metal.smooth() ? transmittanceFromInside(mu, coatEta)
                                                : escapeAfterOneBounce(metal, mu, coatEta, nodes);
            return std::clamp(1.0f - escape, 0.0f, 1.0f);
        };
        // The row is indexed by the cosine outside: light from outside only
        // reaches the metal within the critical cone, where the Fresnel terms
        // change fastest in the inside cosine but smoothly in the outside one.
        for (int i = 0; i < kCosines; ++i)
            r.trapped[size_t(i)] = trapped(insideCosine(coatedBaseCosine(i), coatEta));
        // The trapped light meets the metal from every inside direction:
        // 2 integral_0^1 trapped(mu) mu dmu over the whole inside hemisphere.
        double sum = 0.0;
        for (const QuadratureNode& n : cosineNodes) sum += n.w * trapped(float(n.x)) * n.x;
        r.meanTrapped = float(2.0 * sum);
    });
    return r;
}

CoatedBase::CoatedBase(const CoatedLayers& layers)
    : coatEta_(layers.coatEta), thickness_(layers.thickness), microfacets_(layers.microfacets) {
    requireColor("eta", layers.eta);
    requireColor("k", layers.k);
    if (!(std::isfinite(coatEta_) && coatEta_ >= 1.0f))
        fail("coated conductor: the coat's index of refraction must be at least 1, got ", coatEta_);
    if (!(std::isfinite(thickness_) && thickness_ >= 0.0f))
        fail("coated conductor: the thickness must be finite and non-negative, got ", thickness_);
    // Under the coat the metal's index is relative to the coat's (pbrt-v4 divides it too).
    eta_ = layers.eta / coatEta_;
    k_ = layers.k / coatEta_;
    table_ = sharedTable(coatEta_, microfacets_);

    // The metal's cosine-weighted mean reflectance and the layer's mean
    // round-trip transmittance over the inside hemisphere, where the trapped
    // light travels.
    for (int c = 0; c < 3; ++c)
        metalMean_[c] = float(cosineWeighted([&](float mu) { return fresnelConductor(mu, eta_[c], k_[c]); }));
    layerMean_ = float(cosineWeighted([&](float mu) { return attenuation(mu) * attenuation(mu); }));
}

const CoatedBase::MaterialRow& CoatedBase::materialRow(int j) const {
    MaterialRow& r = rows_[size_t(j)];
    std::call_once(r.once, [&] {
        // After the first bounce (about the mean reflectance), each round
        // crosses the layer twice, meets the metal again and leaves with
        // probability q: the sum over the rounds is q R a / (1 - (1 - q) R a).
        const float q = std::max(1e-6f, 1.0f - table_->row(j).meanTrapped);
        const Color round = metalMean_ * layerMean_;
        r.escape = metalMean_ * q * round / (Color(1.0f) - (1.0f - q) * round);
        // integral over outside w of T(w) trapped(w) a(w') cos = 2 pi x the
        // integral over cos theta.
        r.norm = float(kPi * cosineWeighted([&](float c) {
                           return (1.0f - fresnelDielectric(c, coatEta_)) * trappedInRow(j, c) *
                                  attenuation(insideCosine(c, coatEta_));
                       }));
    });
    return r;
}

float CoatedBase::attenuation(float cosInside) const {
    return thickness_ > 0.0f ? std::exp(-thickness_ / std::max(cosInside, 1e-6f)) : 1.0f;
}

CoatedBase::Bracket CoatedBase::bracket(float alpha) {
    // Linear in perceptual roughness sqrt(alpha) between the table's rows.
    const float x = std::clamp(std::sqrt(std::max(alpha, 0.0f)), 0.0f, 1.0f) * float(kRoughnesses - 1);
    const int lo = std::min(int(x), kRoughnesses - 2);
    return {lo, lo + 1, x - float(lo)};
}

float CoatedBase::trappedInRow(int j, float cosOutside) const {
    // Linear in cos(theta) between the row's evenly spaced entries.
    const float x = std::clamp(cosOutside, 0.0f, 1.0f) * float(kCosines - 1);
    const int i = std::min(int(x), kCosines - 2);
    const float f = x - float(i);
    const auto& t = table_->row(j).trapped;
    return t[size_t(i)] + f * (t[size_t(i) + 1] - t[size_t(i)]);
}

float CoatedBase::trapped(float alpha, float cosOutside) const {
    const Bracket b = bracket(alpha);
    const float lo = trappedInRow(b.lo, cosOutside);
    return b.t > 0.0f ? lo + b.t * (trappedInRow(b.hi, cosOutside) - lo) : lo;
}

Color CoatedBase::trappedEscape(float alpha) const {
    const Bracket b = bracket(alpha);
    const Color lo = materialRow(b.lo).escape;
    return b.t > 0.0f ? lo + b.t * (materialRow(b.hi).escape - lo) : lo;
}

float CoatedBase::trappedNorm(float alpha) const {
    const Bracket b = bracket(alpha);
    const float lo = materialRow(b.lo).norm;
    return b.t > 0.0f ? lo + b.t * (materialRow(b.hi).norm - lo) : lo;
}

}  // namespace strahl
