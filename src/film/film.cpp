#include "strahl/film/film.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <type_traits>
#include <istream>
#include <ostream>
#include <string>
#include <utility>

#include "strahl/core/error.h"

namespace strahl {


namespace {
constexpr std::string_view kAovNames[] = {"normal",   "depth",    "albedo",  "position",
                                          "objectid", "variance", "samples"};  // enum order

constexpr float kNoObject = -1.0f;  // the objectid of a miss: no id is negative

void addTo(ExactSum3& sum, const Vec3& v) {
    sum[0].add(v.x);
    sum[1].add(v.y);
    sum[2].add(v.z);
}

Vec3 meanOf(const ExactSum3& sum, uint32_t n) {
    return Vec3(sum[0].mean(n), sum[1].mean(n), sum[2].mean(n));
}

void addTo(ExactSum3& sum, const ExactSum3& other) {
    for (size_t c = 0; c < 3; ++c) sum[c] += other[c];
}

// The sum over one half of the samples: half 0 is the even sum itself, half 1
// the total minus it (exact: both are integers).
ExactSum halfOf(int half, const ExactSum& total, const ExactSum& even) {
    return half == 0 ? even : ExactSum::fromRaw(total.raw() - even.raw());
}
Vec3 halfMean(int half, const ExactSum3& total, const ExactSum3& even, uint32_t n) {
    return Vec3(halfOf(half, total[0], even[0]).mean(n), halfOf(half, total[1], even[1]).mean(n),
                halfOf(half, total[2], even[2]).mean(n));
}
}  // namespace

std::span<const std::string_view> aovNames() { return kAovNames; }

const char* aovName(AovKind kind) {
    const auto i = static_cast<size_t>(kind);
    if (i >= std::size(kAovNames)) fail("invalid AovKind value ", static_cast<int>(kind));
    return kAovNames[i].data();  // literals: NUL-terminated
}

std::optional<AovKind> aovFromName(std::string_view name) {
    for (size_t i = 0; i < std::size(kAovNames); ++i)
        if (kAovNames[i] == name) return static_cast<AovKind>(i);
    return std::nullopt;
}

int aovChannels(AovKind kind) {
    switch (kind) {
        case AovKind::Normal:
            return 3;
        case AovKind::Depth:
            return 1;
        case AovKind::Albedo:
            return 3;
        case AovKind::Position:
            return 3;
        case AovKind::ObjectId:
            return 1;
        case AovKind::Variance:
            return 3;
        case AovKind::Samples:
            return 1;
    }
    fail("invalid AovKind value ", static_cast<int>(kind));
}

Film::Film(int fullWidth, int fullHeight, PixelRect crop, std::vector<AovKind> aovs)
    : fullWidth_(fullWidth), fullHeight_(fullHeight), crop_(crop), aovs_(std::move(aovs)) {
    if (fullWidth_ <= 0 || fullHeight_ <= 0)
        fail("film: image size ", fullWidth_, "x", fullHeight_, " is not positive");
    if (crop_.empty() || crop_.x0 < 0 || crop_.y0 < 0 || crop_.x1 > fullWidth_ ||
        crop_.y1 > fullHeight_)
        fail("film: crop window [", crop_.x0, ", ", crop_.x1, ") x [", crop_.y0, ", ", crop_.y1,
             ") is not a non-empty part of the ", fullWidth_, "x", fullHeight_, " image");
    // Each AOV becomes a set of named EXR channels, so each may appear once.
    for (auto it = aovs_.begin(); it != aovs_.end(); ++it) {
        if (std::find(aovs_.begin(), it, *it) != it)
            fail("film: AOV '", aovName(*it), "' is requested twice");
    }

    const size_t pixels = static_cast<size_t>(crop_.width()) * static_cast<size_t>(crop_.height());
    radiance_.assign(pixels, ExactSum3{});
    samples_.assign(pixels, 0u);
    // AOV buffers exist only when requested; an empty buffer means "not stored".
    for (AovKind kind : aovs_) {
        switch (kind) {
            case AovKind::Normal:
                normal_.assign(pixels, ExactSum3{});
                break;
            case AovKind::Depth:
                depth_.assign(pixels, ExactSum{});
                hits_.assign(pixels, 0u);
                break;
            case AovKind::Albedo:
                albedo_.assign(pixels, ExactSum3{});
                break;
            case AovKind::Position:
                position_.assign(pixels, ExactSum3{});
                hits_.assign(pixels, 0u);
                break;
            case AovKind::ObjectId:
                objectId_.assign(pixels, kNoObject);
                break;
            case AovKind::Variance:
                mean_.assign(pixels, Color(0.0f));
                m2_.assign(pixels, Color(0.0f));
                break;
            case AovKind::Samples:
                break;  // the sample counts are always kept
        }
    }
}

void Film::keepHalves(uint32_t firstSample) {
    for (AovKind kind : {AovKind::Normal, AovKind::Depth, AovKind::Albedo})
        if (std::find(aovs_.begin(), aovs_.end(), kind) == aovs_.end())
            fail("film: the sample halves need the '", aovName(kind), "' AOV");
    if (std::any_of(samples_.begin(), samples_.end(), [](uint32_t n) { return n > 0; }))
        fail("film: keepHalves after samples were added");
    const size_t pixels = samples_.size();
    firstSample_ = firstSample;
    evenSamples_.assign(pixels, 0u);
    evenHits_.assign(pixels, 0u);
    evenRadiance_.assign(pixels, ExactSum3{});
    evenNormal_.assign(pixels, ExactSum3{});
    evenDepth_.assign(pixels, ExactSum{});
    evenAlbedo_.assign(pixels, ExactSum3{});
}

void Film::trackConvergence() {
    if (std::any_of(samples_.begin(), samples_.end(), [](uint32_t n) { return n > 0; }))
        fail("film: trackConvergence after samples were added");
    const size_t pixels = samples_.size();
    if (m2_.empty()) {
        mean_.assign(pixels, Color(0.0f));
        m2_.assign(pixels, Color(0.0f));
    }
    converged_.assign(pixels, uint8_t{0});
}

Film::Estimate Film::estimate(int x, int y) const {
    if (m2_.empty()) fail("film: no running variance (needs the variance AOV or trackConvergence)");
    const size_t i = index(x, y);
    Estimate e;
    e.samples = samples_[i];
    e.mean = mean_[i];
    const auto n = static_cast<float>(e.samples);
    // As the variance AOV: M2 / (n - 1) / n, clamped against rounding below 0.
    if (e.samples > 1) e.varianceOfMean = glm::max(m2_[i], Color(0.0f)) / ((n - 1.0f) * n);
    return e;
}

void Film::addSample(int x, int y, const Color& radiance, const AovSample& aov) {
    const size_t i = index(x, y);
    const bool first = samples_[i] == 0;
    // This sample's index is firstSample_ + samples_[i]: even ones also go to
    // the even sums.
    const bool even = !evenSamples_.empty() && ((firstSample_ + samples_[i]) & 1u) == 0;
    if (even) {
        addTo(evenRadiance_[i], radiance);
        ++evenSamples_[i];
        if (aov.hit) {
            addTo(evenNormal_[i], aov.normal);
            addTo(evenAlbedo_[i], aov.albedo);
            evenDepth_[i].add(aov.depth);
            ++evenHits_[i];
        }
    }
    addTo(radiance_[i], radiance);
    ++samples_[i];
    if (!m2_.empty()) {
        // Welford: the mean moves by delta / n, M2 grows by delta (x - mean_new).
        // Its own running mean, not the radiance sum over n: the sum's rounding
        // grows with n, the mean's stays at the size of the values.
        const Color delta = radiance - mean_[i];
        mean_[i] += delta / static_cast<float>(samples_[i]);
        m2_[i] += delta * (radiance - mean_[i]);
    }
    if (first && !objectId_.empty() && aov.hit)
        objectId_[i] = static_cast<float>(aov.objectId);
    if (!aov.hit) return;  // a miss adds 0 to the normal and albedo sums, no depth or position
    if (!normal_.empty()) addTo(normal_[i], aov.normal);
    if (!albedo_.empty()) addTo(albedo_[i], aov.albedo);
    if (!depth_.empty()) depth_[i].add(aov.depth);
    if (!position_.empty()) addTo(position_[i], aov.position);
    if (!hits_.empty()) ++hits_[i];
}

std::vector<float> Film::resolveBeauty() const {
    std::vector<float> out(radiance_.size() * 3);
    for (size_t i = 0; i < radiance_.size(); ++i) {
        // A pixel without samples resolves to black rather than 0/0 (ExactSum::mean).
        const Color mean = meanOf(radiance_[i], samples_[i]);
        out[3 * i + 0] = mean.r;
        out[3 * i + 1] = mean.g;
        out[3 * i + 2] = mean.b;
    }
    return out;
}

std::vector<float> Film::resolveAov(AovKind kind) const {
    if (std::find(aovs_.begin(), aovs_.end(), kind) == aovs_.end())
        fail("film: AOV '", aovName(kind), "' was not requested for this film");

    const size_t channels = static_cast<size_t>(aovChannels(kind));
    std::vector<float> out(samples_.size() * channels);
    for (size_t i = 0; i < samples_.size(); ++i) {
        float* px = out.data() + channels * i;
        const auto n = static_cast<float>(samples_[i]);
        Vec3 value(0.0f);
        switch (kind) {
            case AovKind::Depth:
                px[0] = hits_[i] > 0 ? depth_[i].mean(hits_[i]) : kInfinity;
                continue;
            case AovKind::ObjectId:
                px[0] = objectId_[i];
                continue;
            case AovKind::Samples:
                px[0] = n;  // exact: counts stay far below 2^24 (kMaxSpp)
                continue;
            case AovKind::Normal:
                value = meanOf(normal_[i], samples_[i]);
                break;
            case AovKind::Albedo:
                value = meanOf(albedo_[i], samples_[i]);
                break;
            case AovKind::Position:
                value = meanOf(position_[i], hits_[i]);
                break;
            case AovKind::Variance:
                // Sample variance M2 / (n - 1), divided by n for the variance of the
                // mean. Each M2 term is >= 0 up to rounding; clamp so it never reads < 0.
                if (samples_[i] > 1) value = glm::max(m2_[i], Color(0.0f)) / ((n - 1.0f) * n);
                break;
        }
        px[0] = value.x;
        px[1] = value.y;
        px[2] = value.z;
    }
    return out;
}

std::vector<float> Film::resolveHalfBeauty(int half) const {
    if (!keepsHalves()) fail("film: the sample halves were not kept");
    std::vector<float> out(radiance_.size() * 3);
    for (size_t i = 0; i < radiance_.size(); ++i) {
        const uint32_t n = half == 0 ? evenSamples_[i] : samples_[i] - evenSamples_[i];
        const Vec3 mean = halfMean(half, radiance_[i], evenRadiance_[i], n);
        for (int c = 0; c < 3; ++c) out[3 * i + size_t(c)] = mean[c];
    }
    return out;
}

std::vector<float> Film::resolveHalfAov(int half, AovKind kind) const {
    if (!keepsHalves()) fail("film: the sample halves were not kept");
    const size_t channels = static_cast<size_t>(aovChannels(kind));
    std::vector<float> out(samples_.size() * channels);
    for (size_t i = 0; i < samples_.size(); ++i) {
        const uint32_t n = half == 0 ? evenSamples_[i] : samples_[i] - evenSamples_[i];
        const uint32_t hits = half == 0 ? evenHits_[i] : hits_[i] - evenHits_[i];
        Vec3 value(0.0f);
        switch (kind) {
            case AovKind::Depth:
                out[i] = hits > 0 ? halfOf(half, depth_[i], evenDepth_[i]).mean(hits) : kInfinity;
                continue;
            case AovKind::Normal:
                value = halfMean(half, normal_[i], evenNormal_[i], n);
                break;
            case AovKind::Albedo:
                value = halfMean(half, albedo_[i], evenAlbedo_[i], n);
                break;
            default:
                fail("film: AOV '", aovName(kind), "' is not kept per half");
        }
        for (size_t c = 0; c < 3; ++c) out[channels * i + c] = value[int(c)];
    }
    return out;
}

FilmPixel Film::pixel(int x, int y) const {
    if (!crop_.contains(PixelRect{x, y, x + 1, y + 1})) fail("film: pixel outside the crop window");
    const size_t i = index(x, y);
    FilmPixel p;
    p.samples = samples_[i];
    p.radiance = radiance_[i];
    if (!hits_.empty()) p.hits = hits_[i];
    if (!normal_.empty()) p.normal = normal_[i];
    if (!depth_.empty()) p.depth = depth_[i];
    if (!albedo_.empty()) p.albedo = albedo_[i];
    if (!position_.empty()) p.position = position_[i];
    if (!objectId_.empty()) p.objectId = objectId_[i];
    if (!mean_.empty()) p.mean = mean_[i];
    if (!m2_.empty()) p.m2 = m2_[i];
    if (keepsHalves()) {
        p.evenSamples = evenSamples_[i];
        p.evenHits = evenHits_[i];
        p.evenRadiance = evenRadiance_[i];
        p.evenNormal = evenNormal_[i];
        p.evenDepth = evenDepth_[i];
        p.evenAlbedo = evenAlbedo_[i];
    }
    if (!converged_.empty()) p.converged = converged_[i];
    return p;
}

void Film::setPixel(int x, int y, const FilmPixel& p) {
    if (!crop_.contains(PixelRect{x, y, x + 1, y + 1})) fail("film: pixel outside the crop window");
    const size_t i = index(x, y);
    samples_[i] = p.samples;
    radiance_[i] = p.radiance;
    if (!hits_.empty()) hits_[i] = p.hits;
    if (!normal_.empty()) normal_[i] = p.normal;
    if (!depth_.empty()) depth_[i] = p.depth;
    if (!albedo_.empty()) albedo_[i] = p.albedo;
    if (!position_.empty()) position_[i] = p.position;
    if (!objectId_.empty()) objectId_[i] = p.objectId;
    if (!mean_.empty()) mean_[i] = p.mean;
    if (!m2_.empty()) m2_[i] = p.m2;
    if (keepsHalves()) {
        evenSamples_[i] = p.evenSamples;
        evenHits_[i] = p.evenHits;
        evenRadiance_[i] = p.evenRadiance;
        evenNormal_[i] = p.evenNormal;
        evenDepth_[i] = p.evenDepth;
        evenAlbedo_[i] = p.evenAlbedo;
    }
    if (!converged_.empty()) converged_[i] = p.converged;
}

void Film::merge(const Film& later, const std::string& source) {
    if (later.fullWidth_ != fullWidth_ || later.fullHeight_ != fullHeight_ ||
        later.crop_.x0 != crop_.x0 || later.crop_.y0 != crop_.y0 || later.crop_.x1 != crop_.x1 ||
        later.crop_.y1 != crop_.y1 || later.aovs_ != aovs_)
        fail(source, ": cannot merge films of different size, crop window or AOVs");
    if (later.keepsHalves() != keepsHalves())
        fail(source, ": cannot merge a film that keeps the sample halves (--denoise) with one "
                     "that does not");
    // Which pixels an adaptive render stops depends on all of its samples: the
    // parts of one would not add up to it.
    if (later.tracksConvergence() || tracksConvergence())
        fail(source, ": cannot merge films rendered with adaptive sampling");
    for (size_t i = 0; i < samples_.size(); ++i) {
        const uint32_t na = samples_[i], nb = later.samples_[i];
        if (nb > ExactSum::kMaxSamples - na)
            fail(source, ": merging gives a pixel more than ", ExactSum::kMaxSamples,
                 " samples, the most the exact sums can hold");
        addTo(radiance_[i], later.radiance_[i]);
        samples_[i] = na + nb;
        if (keepsHalves()) {
            evenSamples_[i] += later.evenSamples_[i];
            evenHits_[i] += later.evenHits_[i];
            addTo(evenRadiance_[i], later.evenRadiance_[i]);
            addTo(evenNormal_[i], later.evenNormal_[i]);
            evenDepth_[i] += later.evenDepth_[i];
            addTo(evenAlbedo_[i], later.evenAlbedo_[i]);
        }
        if (!hits_.empty()) hits_[i] += later.hits_[i];
        if (!normal_.empty()) addTo(normal_[i], later.normal_[i]);
        if (!depth_.empty()) depth_[i] += later.depth_[i];
        if (!albedo_.empty()) addTo(albedo_[i], later.albedo_[i]);
        if (!position_.empty()) addTo(position_[i], later.position_[i]);
        // The first sample is this film's, unless it has none.
        if (!objectId_.empty() && na == 0) objectId_[i] = later.objectId_[i];
        if (!m2_.empty() && nb > 0) {
            if (na == 0) {
                mean_[i] = later.mean_[i];
                m2_[i] = later.m2_[i];
                continue;
            }
            // Chan, Golub and LeVeque's pairwise update, in double: with
            // delta = mean_b - mean_a, mean = mean_a + delta nb / n and
            // M2 = M2_a + M2_b + delta^2 na nb / n. The same statistics as
            // Welford over all samples, rounded differently.
            const double a = na, b = nb, n = a + b;
            for (int c = 0; c < 3; ++c) {
                const double meanA = mean_[i][c], meanB = later.mean_[i][c];
                const double delta = meanB - meanA;
                mean_[i][c] = static_cast<float>(meanA + delta * b / n);
                m2_[i][c] = static_cast<float>(double(m2_[i][c]) + double(later.m2_[i][c]) +
                                               delta * delta * a * b / n);
            }
        }
    }
}

// --- checkpoint state --------------------------------------------------------

namespace {

template <typename T>
void writeVector(std::ostream& out, const std::vector<T>& v) {
    const uint64_t n = v.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
}

template <typename T>
void readVector(std::istream& in, std::vector<T>& v, const std::string& source, const char* what) {
    uint64_t n = 0;
    in.read(reinterpret_cast<char*>(&n), sizeof n);
    // The film was constructed for the same image: every buffer must already
    // have the stored size (so a corrupt count cannot make us allocate).
    if (!in || n != v.size())
        fail(source, ": checkpoint buffer '", what, "' does not match this image (",
             in ? std::to_string(n) : std::string("truncated"), " values, expected ", v.size(),
             ")");
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in) fail(source, ": checkpoint is truncated in buffer '", what, "'");
}

// Calls fn(buffer) for every per-pixel buffer of the film, stored or not (an
// AOV that is not stored has an empty buffer), in one fixed order.
template <typename FilmBuffers, typename Fn>
void forEachPixelBuffer(FilmBuffers&& buffers, Fn&& fn) {
    std::apply([&](auto&... b) { (fn(b), ...); }, buffers);
}

}  // namespace

std::vector<std::byte> Film::packPixels(const PixelRect& rect) const {
    if (!crop_.contains(rect)) fail("film: packPixels outside the crop window");
    std::vector<std::byte> bytes;
    forEachPixelBuffer(buffers(), [&](const auto& buffer) {
        if (buffer.empty()) return;
        using T = typename std::decay_t<decltype(buffer)>::value_type;
        for (int y = rect.y0; y < rect.y1; ++y) {
            const auto* row = reinterpret_cast<const std::byte*>(&buffer[index(rect.x0, y)]);
            bytes.insert(bytes.end(), row, row + sizeof(T) * size_t(rect.width()));
        }
    });
    return bytes;
}

void Film::unpackPixels(const PixelRect& rect, std::span<const std::byte> bytes,
                        const std::string& source) {
    if (!crop_.contains(rect)) fail(source, ": pixels outside the crop window");
    size_t expected = 0;
    forEachPixelBuffer(buffers(), [&](const auto& buffer) {
        if (buffer.empty()) return;
        using T = typename std::decay_t<decltype(buffer)>::value_type;
        expected += sizeof(T) * size_t(rect.width()) * size_t(rect.height());
    });
    if (bytes.size() != expected)
        fail(source, ": ", bytes.size(), " bytes of pixel state for a ", rect.width(), "x",
             rect.height(), " rectangle that needs ", expected);
    size_t at = 0;
    forEachPixelBuffer(buffers(), [&](auto& buffer) {
        if (buffer.empty()) return;
        using T = typename std::decay_t<decltype(buffer)>::value_type;
        for (int y = rect.y0; y < rect.y1; ++y) {
            const size_t n = sizeof(T) * size_t(rect.width());
            std::memcpy(&buffer[index(rect.x0, y)], bytes.data() + at, n);
            at += n;
        }
    });
}

void Film::writeState(std::ostream& out) const {
    writeVector(out, radiance_);
    writeVector(out, samples_);
    writeVector(out, hits_);
    writeVector(out, normal_);
    writeVector(out, depth_);
    writeVector(out, albedo_);
    writeVector(out, position_);
    writeVector(out, objectId_);
    writeVector(out, mean_);
    writeVector(out, m2_);
    writeVector(out, evenSamples_);
    writeVector(out, evenHits_);
    writeVector(out, evenRadiance_);
    writeVector(out, evenNormal_);
    writeVector(out, evenDepth_);
    writeVector(out, evenAlbedo_);
    writeVector(out, converged_);
}

void Film::readState(std::istream& in, const std::string& source) {
    readVector(in, radiance_, source, "radiance");
    readVector(in, samples_, source, "samples");
    readVector(in, hits_, source, "hits");
    readVector(in, normal_, source, "normal");
    readVector(in, depth_, source, "depth");
    readVector(in, albedo_, source, "albedo");
    readVector(in, position_, source, "position");
    readVector(in, objectId_, source, "objectid");
    readVector(in, mean_, source, "variance mean");
    readVector(in, m2_, source, "variance m2");
    readVector(in, evenSamples_, source, "even samples");
    readVector(in, evenHits_, source, "even hits");
    readVector(in, evenRadiance_, source, "even radiance");
    readVector(in, evenNormal_, source, "even normal");
    readVector(in, evenDepth_, source, "even depth");
    readVector(in, evenAlbedo_, source, "even albedo");
    readVector(in, converged_, source, "converged");
}

}  // namespace strahl
