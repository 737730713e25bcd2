#pragma once
// Internal to the bsdf module: Gauss-Legendre quadrature on [0, 1], for the
// tables that integrate a microfacet lobe over its sampled normals
// (rough_coat.cpp, coated_base.cpp), and the loop over those normals.

#include <cmath>
#include <vector>

#include "strahl/bsdf/microfacet.h"

namespace strahl {

struct QuadratureNode {
    double x, w;
};

// Gauss-Legendre nodes and weights on [0, 1]: the roots of P_n by Newton's
// method from the Chebyshev estimates cos(pi (i + 3/4) / (n + 1/2)).
inline std::vector<QuadratureNode> gaussLegendre01(int n) {
    std::vector<QuadratureNode> nodes(n);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(3.14159265358979323846 * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x;  // P_0, P_1, then the recurrence up to P_n
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / dp;
            x -= step;
            if (std::abs(step) < 1e-15) break;
        }
        nodes[i] = {0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp)};  // weight 2/.. halved
    }
    return nodes;
}

// An integral over the microfacet normals m that `dist` shows to wo (wo.z =
// cos theta_o > 0): calls visit(m, cos(wo, m), weight) at the nodes x nodes
// points of the distribution's normal sampling, with weight = w_a w_b D(m)
// (wo.m) / (cos theta_o pdf(m)): the sampling's Jacobian, so that the sum
// of weight g(m) is the integral of D(m) (wo.m) / cos theta_o g(m) dm (a
// lobe's albedo, given g = G F). Normals facing away from wo are skipped.
template <typename Visit>
void forVisibleNormals(const MicrofacetDistribution& dist, const Vec3& wo,
                       const std::vector<QuadratureNode>& nodes, Visit&& visit) {
    for (const QuadratureNode& a : nodes) {
        for (const QuadratureNode& b : nodes) {
            const Vec3 m = dist.sampleNormal(wo, Vec2(float(a.x), float(b.x)));
            const float cosOm = glm::dot(wo, m);
            const float pdf = dist.normalPdf(wo, m);
            if (cosOm <= 0.0f || !(pdf > 0.0f)) continue;
            visit(m, cosOm, a.w * b.w * dist.d(m) * cosOm / (wo.z * pdf));
        }
    }
}

}  // namespace strahl
