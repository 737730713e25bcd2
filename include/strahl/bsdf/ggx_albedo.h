#pragma once
// Directional albedo of the isotropic GGX reflection lobe with Schlick Fresnel,
//   E(mu) = integral F(wo.m) D(m) G2(wo, wi) / (4 cos_o cos_i) cos_i dwi,
// mu = cos(theta_o), and its cosine-weighted hemispherical average. Schlick's F
// is linear in F0, so E = F0 e1(mu, alpha) + (1 - F0) e5(mu, alpha), where e1
// is the albedo with F = 1 and e5 with F = (1 - wo.m)^5; both are tabulated
// once per process (a bilinear table over mu and sqrt(alpha)). The coupled
// diffuse lobe of the metallic-roughness BSDF needs E (docs/materials.md).

namespace strahl {

// E(mu) for alpha in [0, 1] (larger values clamp to 1); exact Schlick below
// MicrofacetDistribution::kSmoothAlpha.
float ggxSchlickAlbedo(float cosThetaO, float alpha, float f0);

// 2 * integral_0^1 E(mu) mu dmu, integrated exactly from the same bilinear
// interpolant ggxSchlickAlbedo evaluates, so that a lobe weighted by
// (1 - E(wi)) / (1 - average) integrates to exactly 1 - E(wo) over wi.
float ggxSchlickAverageAlbedo(float alpha, float f0);

}  // namespace strahl
