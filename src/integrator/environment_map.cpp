#include "strahl/integrator/environment_map.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "strahl/core/error.h"

namespace strahl {

namespace {

// Rec. 709 luminance of linear RGB (the primaries strahl renders in).
float luminance(const Color& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

int wrap(int i, int n) {
    return ((i % n) + n) % n;
}

}  // namespace

Vec3 EnvironmentMap::direction(const Vec2& uv) {
    const float theta = kPi * uv.y, phi = 2.0f * kPi * uv.x;
    const float sinTheta = std::sin(theta);
    return Vec3(-sinTheta * std::cos(phi), std::cos(theta), -sinTheta * std::sin(phi));
}

Vec2 EnvironmentMap::uv(const Vec3& dir) {
    // atan2 in both angles: exact for any length and accurate near the poles,
    // where acos(y) would lose precision.
    float u = 0.5f + std::atan2(dir.z, dir.x) * (0.5f * kInvPi);
    u = std::clamp(u, 0.0f, 1.0f);
    const float v = std::atan2(std::sqrt(dir.x * dir.x + dir.z * dir.z), dir.y) * kInvPi;
    return Vec2(u, std::clamp(v, 0.0f, 1.0f));
}

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<Color> texels,
                               RowLayout rows)
    : width_(width), height_(height), texels_(std::move(texels)), rows_(rows) {
    if (width <= 0 || height <= 0)
        fail("environment map: empty image (", width, " x ", height, ")");
    if (rows == RowLayout::PoleToPole && height < 2)
        fail("environment map: ", height, " row; rows from pole to pole need at least two");
    const auto w = static_cast<size_t>(width), h = static_cast<size_t>(height);
    if (texels_.size() != w * h)
        fail("environment map: ", texels_.size(), " texels for ", width, " x ", height);
    for (size_t i = 0; i < texels_.size(); ++i) {
        const Color& c = texels_[i];
        if (!isFinite(c) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
            fail("environment map: texel (", i % w, ", ", i / w, ") is (", c.r, ", ", c.g, ", ",
                 c.b, "); radiance must be finite and >= 0");
    }

    // Sampling weights. lookup() interpolates bilinearly between texel centres, so
    // over texel x it blends x with its neighbours; the mean of a linear
    // interpolant over [x - 1/2, x + 1/2] (centres at integers) is
    // (c[x-1] + 6 c[x] + c[x+1]) / 8, and in 2D the tensor product of that. A
    // weight is thus > 0 wherever lookup() is > 0 (no radiance is unreachable by
    // light sampling) and tracks the bilinear image's mean over the texel.
    // With rows from pole to pole a cell of the distribution still only blends
    // the rows next to its own (row y's band of v reaches rows y - 1 to y + 1),
    // so the same weights stay > 0 wherever lookup() is; they track the mean a
    // little less closely, which costs variance, not correctness.
    std::vector<float> lum(w * h);
    for (size_t i = 0; i < lum.size(); ++i) lum[i] = luminance(texels_[i]);
    std::vector<float> horizontal(w * h);  // columns wrap, as in lookup()
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t row = static_cast<size_t>(y) * w;
            horizontal[row + static_cast<size_t>(x)] =
                (lum[row + static_cast<size_t>(wrap(x - 1, width))] +
                 6.0f * lum[row + static_cast<size_t>(x)] +
                 lum[row + static_cast<size_t>(wrap(x + 1, width))]) /
                8.0f;
        }
    std::vector<float> weights(w * h);
    for (int y = 0; y < height; ++y) {
        // Rows clamp at the poles, as in lookup().
        const size_t above = static_cast<size_t>(std::max(y - 1, 0)) * w;
        const size_t row = static_cast<size_t>(y) * w;
        const size_t below = static_cast<size_t>(std::min(y + 1, height - 1)) * w;
        // sin(theta) at the row centre: the solid angle of a texel is
        // (2 pi / w)(pi / h) sin(theta), so weighting by it makes the density
        // proportional to radiance per solid angle. Row centres avoid sin = 0.
        const float sinTheta =
            std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height));
        for (size_t x = 0; x < w; ++x)
            weights[row + x] =
                sinTheta *
                (horizontal[above + x] + 6.0f * horizontal[row + x] + horizontal[below + x]) / 8.0f;
    }
    distribution_ = Distribution2D(weights, width, height);
}

Color EnvironmentMap::lookup(const Vec3& dir) const {
    const Vec2 st = uv(dir);
    // Continuous texel coordinates with texel values at integers.
    const float s = st.x * static_cast<float>(width_) - 0.5f;
    const float t = rows_ == RowLayout::PoleToPole ? st.y * static_cast<float>(height_ - 1)
                                                   : st.y * static_cast<float>(height_) - 0.5f;
    const float sFloor = std::floor(s), tFloor = std::floor(t);
    const float fs = s - sFloor, ft = t - tFloor;
    const int x0 = wrap(static_cast<int>(sFloor), width_), x1 = wrap(x0 + 1, width_);
    const int yFloor = static_cast<int>(tFloor);
    const int y0 = std::clamp(yFloor, 0, height_ - 1), y1 = std::clamp(yFloor + 1, 0, height_ - 1);
    const Color top = (1.0f - fs) * texel(x0, y0) + fs * texel(x1, y0);
    const Color bottom = (1.0f - fs) * texel(x0, y1) + fs * texel(x1, y1);
    return (1.0f - ft) * top + ft * bottom;
}

// The map pdf is per unit (u, v) area; d omega = sin(theta) dtheta dphi =
// 2 pi^2 sin(theta) du dv, so the solid-angle density divides by 2 pi^2 sin(theta).
Vec3 EnvironmentMap::sample(const Vec2& u, float& pdf) const {
    float mapPdf;
    const Vec2 st = distribution_.sample(u, mapPdf);
    const Vec3 dir = direction(st);
    const float sinTheta = std::sqrt(dir.x * dir.x + dir.z * dir.z);
    pdf = sinTheta > 0.0f ? mapPdf / (2.0f * kPi * kPi * sinTheta) : 0.0f;
    return dir;
}

float EnvironmentMap::pdf(const Vec3& dir) const {
    const float len = glm::length(dir);
    const float sinTheta = std::sqrt(dir.x * dir.x + dir.z * dir.z) / len;
    if (!(sinTheta > 0.0f)) return 0.0f;
    return distribution_.pdf(uv(dir)) / (2.0f * kPi * kPi * sinTheta);
}

Color EnvironmentMap::average() const {
    // Row y spans cos(theta) from cos(pi y / h) to cos(pi (y + 1) / h) (rows
    // from pole to pole: the band nearest its v = y / (h - 1), half a row each
    // way, clamped at the poles); its solid angle over 4 pi is the difference
    // / 2, shared by its w texels.
    constexpr double pi = 3.14159265358979323846;
    const bool poles = rows_ == RowLayout::PoleToPole;
    glm::dvec3 sum(0.0);
    for (int y = 0; y < height_; ++y) {
        const double theta0 = poles ? pi * std::max(0.0, (y - 0.5) / (height_ - 1)) : pi * y / height_;
        const double theta1 =
            poles ? pi * std::min(1.0, (y + 0.5) / (height_ - 1)) : pi * (y + 1) / height_;
        const double fraction = (std::cos(theta0) - std::cos(theta1)) / (2.0 * width_);
        glm::dvec3 rowSum(0.0);
        for (int x = 0; x < width_; ++x) rowSum += glm::dvec3(texel(x, y));
        sum += fraction * rowSum;
    }
    return Color(sum);
}

}  // namespace strahl
