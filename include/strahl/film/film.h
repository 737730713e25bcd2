#pragma once
// Film: accumulation of radiance and AOVs over a pixel rectangle of the full
// image (the crop window). A pixel's value is the plain mean of the samples
// credited to it: with filter importance sampling (core/filter.h) every sample
// has weight 1, even one whose raster position lies outside its pixel. Each
// pixel is written by exactly one tile, in sample order, so no locking is needed
// and the summation order is fixed (deterministic).
//
// The beauty and the mean AOVs (normal, depth, albedo, position) are summed
// exactly, in fixed point (film/exact_sum.h): sums over disjoint sample ranges
// add up to the sum over their union bit for bit, so a render split by sample
// ranges merges into exactly the single-machine image (merge()). The variance
// AOV keeps Welford's float running mean and M2, which merge() combines by
// Chan et al.'s parallel formula: exact in arithmetic, not in rounding. The
// objectid AOV is the first sample's, which a merge takes from the earlier part.

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <span>
#include <string_view>
#include <string>
#include <tuple>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/film/exact_sum.h"

namespace strahl {

// Arbitrary output variables written next to the beauty pass.
// Unless stated, "samples" are those credited to the pixel.
enum class AovKind {  // values 0 .. 6 in the order of aovNames()
    Normal,    // world-space shading normal of the first hit, mean over samples (0 for misses)
    Depth,     // ray distance to the first hit, mean over the samples that hit; +inf if none did
    Albedo,    // diffuse reflectance of the first hit, mean over samples (0 for misses)
    Position,  // world-space first-hit point, mean over the samples that hit; 0 if none did
    ObjectId,  // AovSample::objectId of the pixel's first sample (not averaged); -1 if that
               // sample missed or the pixel has no samples
    Variance,  // per channel, the variance of the beauty mean: s^2 / n with s^2 the
               // sample variance of the n radiance values (Welford); 0 for n < 2
    Samples,   // the number of samples credited to the pixel (adaptive sampling varies it)
};

// "normal", "depth", "albedo", "position", "objectid", "variance", "samples"
const char* aovName(AovKind kind);
std::span<const std::string_view> aovNames();  // every AOV's name, in enum order
std::optional<AovKind> aovFromName(std::string_view name);
int aovChannels(AovKind kind);      // 3, 1, 3, 3, 1, 3, 1

// First-hit values of one camera sample, for the AOVs. Only `hit` is read for a
// miss; the radiance for the variance AOV comes from addSample.
struct AovSample {
    bool hit = false;
    Vec3 normal{0.0f};
    float depth = 0.0f;
    Color albedo{0.0f};
    Vec3 position{0.0f};    // world space
    uint32_t objectId = 0;  // written as a float: exact below 2^24
};

// One pixel's whole accumulation state (Film::pixel, setPixel): what a part
// of a split render hands to `strahl merge` (film/exact_part.h). Members of
// AOVs the film does not store are left at their defaults and ignored.
struct FilmPixel {
    uint32_t samples = 0;
    uint32_t hits = 0;  // samples that hit, for depth and position
    ExactSum3 radiance{};
    ExactSum3 normal{};
    ExactSum depth{};
    ExactSum3 albedo{};
    ExactSum3 position{};
    float objectId = -1.0f;  // the first sample's, -1 if it missed
    Color mean{0.0f};        // Welford's running mean of the radiance (variance AOV)
    Color m2{0.0f};          // and its sum of squared deviations
    // The same sums over the samples of even index alone (Film::keepHalves).
    uint32_t evenSamples = 0;
    uint32_t evenHits = 0;
    ExactSum3 evenRadiance{};
    ExactSum3 evenNormal{};
    ExactSum evenDepth{};
    ExactSum3 evenAlbedo{};
    uint8_t converged = 0;  // adaptive sampling has stopped the pixel (Film::trackConvergence)
};

class Film {
public:
    // fullWidth x fullHeight is the image; crop selects the rendered rectangle.
    Film(int fullWidth, int fullHeight, PixelRect crop, std::vector<AovKind> aovs);

    int fullWidth() const { return fullWidth_; }
    int fullHeight() const { return fullHeight_; }
    const PixelRect& crop() const { return crop_; }
    const std::vector<AovKind>& aovs() const { return aovs_; }

    // (x, y) in full-image pixel coordinates, inside the crop: the pixel the
    // sample belongs to, not necessarily the one its raster position lies in.
    // The first call for a pixel is its first sample (the objectid AOV).
    void addSample(int x, int y, const Color& radiance, const AovSample& aov);

    // A hint that addSample(x, y, ...) is coming: starts loading the pixel's
    // radiance sum and sample count into the cache. A camera packet asks for
    // its pixels before it is traced, so the film's cache misses (a 1024²
    // film is 48 MB of sums) overlap Embree's traversal instead of following
    // it. Changes nothing but timing.
    void prefetch(int x, int y) const {
        const size_t i = index(x, y);
        const char* sum = reinterpret_cast<const char*>(&radiance_[i]);
        __builtin_prefetch(sum, 1);
        __builtin_prefetch(sum + sizeof(ExactSum3) - 1, 1);  // a 48-byte sum may span two lines
        __builtin_prefetch(&samples_[i], 1);
    }

    // Also keeps the beauty, normal, depth and albedo sums of the samples of
    // even index alone, so that the image splits into two independent halves,
    // even and odd samples, as the denoiser needs (denoise/denoiser.h): the
    // odd half is the total minus the even one, exactly. A sample's index is
    // firstSample plus the samples the pixel already has (a part of a split
    // render starts at its --sample-offset), so the halves of merged parts
    // are those of one render. Needs the normal, depth and albedo AOVs; call
    // before the first sample.
    void keepHalves(uint32_t firstSample);
    bool keepsHalves() const { return !evenSamples_.empty(); }
    uint32_t halvesFirstSample() const { return firstSample_; }

    // Samples accumulated so far in pixel (x, y) (full-image coordinates).
    uint32_t sampleCount(int x, int y) const { return samples_[index(x, y)]; }

    // Adaptive sampling (render/adaptive_sampling.h): also keeps the
    // radiance's running mean and variance (as the variance AOV does, whether
    // or not that AOV is written) and a per-pixel flag "converged", which
    // stops a pixel for the rest of the render. The flag is part of the
    // accumulation state: checkpoints and packed tiles carry it, so a resumed
    // or distributed render stops the same pixels. Call before the first sample.
    void trackConvergence();
    bool tracksConvergence() const { return !converged_.empty(); }
    bool converged(int x, int y) const {
        return !converged_.empty() && converged_[index(x, y)] != 0;
    }
    void setConverged(int x, int y) { converged_.at(index(x, y)) = 1; }
    // The running mean of the pixel's radiance and the variance of that mean
    // (0 for fewer than 2 samples); needs the variance AOV or trackConvergence.
    struct Estimate {
        uint32_t samples = 0;
        Color mean{0.0f};
        Color varianceOfMean{0.0f};
    };
    Estimate estimate(int x, int y) const;

    // The complete accumulation state, for checkpoints (film/checkpoint.h):
    // written raw and read back bit for bit, so a resumed render continues
    // every sum exactly where it stopped. readState throws strahl::Error
    // naming `source` if the data does not match this film's size, crop and
    // AOVs or is truncated.
    void writeState(std::ostream& out) const;
    void readState(std::istream& in, const std::string& source);

    // The accumulation state of the pixels of `rect` (full-image coordinates,
    // inside the crop) as bytes, and its inverse: unpackPixels overwrites those
    // pixels with state packed by a film of the same size, crop and AOVs (in
    // another process: distributed rendering moves finished tiles this way).
    // unpackPixels throws strahl::Error naming `source` if the byte count does
    // not match.
    std::vector<std::byte> packPixels(const PixelRect& rect) const;
    void unpackPixels(const PixelRect& rect, std::span<const std::byte> bytes,
                      const std::string& source);

    // One pixel's state (full-image coordinates, inside the crop), and its
    // inverse. setPixel ignores the members of AOVs this film does not store.
    FilmPixel pixel(int x, int y) const;
    void setPixel(int x, int y, const FilmPixel& state);

    // Adds the samples of `later`, a film of the same size, crop and AOVs whose
    // samples come after this film's (the objectid AOV keeps the first
    // sample's): the exact sums simply add, so the result is bit for bit the
    // film of both sample sets, except the variance AOV (Chan's formula, see
    // above). Throws strahl::Error naming `source` if the films do not match
    // or a pixel would exceed ExactSum::kMaxSamples samples.
    void merge(const Film& later, const std::string& source);

    // Resolved crop-sized images, row-major from the top row, interleaved channels.
    std::vector<float> resolveBeauty() const;  // RGB
    std::vector<float> resolveAov(AovKind kind) const;
    // The beauty (RGB) or the normal, depth or albedo AOV over one half of the
    // samples: half 0 the even sample indices, half 1 the odd ones
    // (keepHalves). A pixel without samples in the half reads as one without
    // samples at all.
    std::vector<float> resolveHalfBeauty(int half) const;
    std::vector<float> resolveHalfAov(int half, AovKind kind) const;

private:
    size_t index(int x, int y) const {
        return static_cast<size_t>(y - crop_.y0) * static_cast<size_t>(crop_.width()) +
               static_cast<size_t>(x - crop_.x0);
    }
    // Every per-pixel buffer, in one fixed order (packPixels, unpackPixels).
    auto buffers() const {
        return std::tie(radiance_, samples_, hits_, normal_, depth_, albedo_, position_,
                        objectId_, mean_, m2_, evenSamples_, evenHits_, evenRadiance_,
                        evenNormal_, evenDepth_, evenAlbedo_, converged_);
    }
    auto buffers() {
        return std::tie(radiance_, samples_, hits_, normal_, depth_, albedo_, position_,
                        objectId_, mean_, m2_, evenSamples_, evenHits_, evenRadiance_,
                        evenNormal_, evenDepth_, evenAlbedo_, converged_);
    }


    int fullWidth_, fullHeight_;
    PixelRect crop_;
    std::vector<AovKind> aovs_;
    std::vector<ExactSum3> radiance_;
    std::vector<uint32_t> samples_;
    std::vector<uint32_t> hits_;  // samples that hit: for depth and position
    std::vector<ExactSum3> normal_;
    std::vector<ExactSum> depth_;
    std::vector<ExactSum3> albedo_;
    std::vector<ExactSum3> position_;
    std::vector<float> objectId_;
    std::vector<Color> mean_;  // Welford's running mean of the radiance
    std::vector<Color> m2_;    // Welford's sum of squared deviations from it
    // keepHalves: the sums of the samples of even index alone.
    uint32_t firstSample_ = 0;
    std::vector<uint32_t> evenSamples_;
    std::vector<uint32_t> evenHits_;
    std::vector<ExactSum3> evenRadiance_;
    std::vector<ExactSum3> evenNormal_;
    std::vector<ExactSum> evenDepth_;
    std::vector<ExactSum3> evenAlbedo_;
    std::vector<uint8_t> converged_;  // trackConvergence: 1 once adaptive sampling stopped the pixel
};

}  // namespace strahl
