#pragma once
// Film: float accumulation of radiance and AOVs over a pixel rectangle of the
// full image (the crop window), with a box pixel filter (the mean of the
// samples that landed in the pixel). Each pixel is written by exactly one tile,
// so no locking is needed and the summation order is fixed (deterministic).

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/core/pixel_rect.h"

namespace strahl {

// Arbitrary output variables written next to the beauty pass.
enum class AovKind {  // values 0, 1, 2 in the order of aovNames()
    Normal,  // world-space shading normal of the first hit, mean over samples (0 for misses)
    Depth,   // ray distance to the first hit, mean over the samples that hit; +inf if none did
    Albedo,  // diffuse reflectance of the first hit, mean over samples (0 for misses)
};

const char* aovName(AovKind kind);  // "normal", "depth", "albedo"
std::span<const std::string_view> aovNames();  // every AOV's name, in enum order
std::optional<AovKind> aovFromName(std::string_view name);
int aovChannels(AovKind kind);      // 3, 1, 3

// First-hit values of one camera sample, for the AOVs.
struct AovSample {
    bool hit = false;
    Vec3 normal{0.0f};
    float depth = 0.0f;
    Color albedo{0.0f};
};

class Film {
public:
    // fullWidth x fullHeight is the image; crop selects the rendered rectangle.
    Film(int fullWidth, int fullHeight, PixelRect crop, std::vector<AovKind> aovs);

    int fullWidth() const { return fullWidth_; }
    int fullHeight() const { return fullHeight_; }
    const PixelRect& crop() const { return crop_; }
    const std::vector<AovKind>& aovs() const { return aovs_; }

    // (x, y) in full-image pixel coordinates, inside the crop.
    void addSample(int x, int y, const Color& radiance, const AovSample& aov);

    // Resolved crop-sized images, row-major from the top row, interleaved channels.
    std::vector<float> resolveBeauty() const;  // RGB
    std::vector<float> resolveAov(AovKind kind) const;

private:
    size_t index(int x, int y) const;

    int fullWidth_, fullHeight_;
    PixelRect crop_;
    std::vector<AovKind> aovs_;
    std::vector<Color> radiance_;
    std::vector<uint32_t> samples_;
    std::vector<uint32_t> hits_;
    std::vector<Vec3> normal_;
    std::vector<float> depth_;
    std::vector<Color> albedo_;
};

}  // namespace strahl
