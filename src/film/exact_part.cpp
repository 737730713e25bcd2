#include "strahl/film/exact_part.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <unordered_map>

#include "strahl/core/error.h"
#include "strahl/film/image_output.h"

namespace strahl {

namespace {

constexpr int kPieceBits = 24;  // a float holds every integer below 2^24 exactly
constexpr uint32_t kPieceMask = (1u << kPieceBits) - 1;
constexpr int kSumPieces = 6;    // ceil(128 / 24)
constexpr int kCountPieces = 2;  // ceil(32 / 24)

constexpr const char* kSumPrefix = "strahl.sum.";
constexpr const char* kSamplesChannel = "strahl.count.samples";
constexpr const char* kHitsChannel = "strahl.count.hits";
constexpr const char* kEvenSamplesChannel = "strahl.count.even_samples";
constexpr const char* kEvenHitsChannel = "strahl.count.even_hits";
constexpr const char* kWelfordPrefix = "strahl.welford.";

// The film's state as named fields of a FilmPixel, by kind.
struct Fields {
    std::vector<std::pair<std::string, std::function<ExactSum&(FilmPixel&)>>> sums;
    std::vector<std::pair<std::string, std::function<uint32_t&(FilmPixel&)>>> counts;
    std::vector<std::pair<std::string, std::function<float&(FilmPixel&)>>> values;
};

bool has(const std::vector<AovKind>& aovs, AovKind kind) {
    return std::find(aovs.begin(), aovs.end(), kind) != aovs.end();
}

// halves: the film keeps the even samples' sums too (Film::keepHalves).
Fields fieldsOf(const std::vector<AovKind>& aovs, bool halves) {
    Fields f;
    const auto sum3 = [&](const std::string& prefix, const char* suffixes, ExactSum3 FilmPixel::*m) {
        for (int c = 0; c < 3; ++c)
            f.sums.emplace_back(kSumPrefix + prefix + suffixes[c],
                                [m, c](FilmPixel& p) -> ExactSum& { return (p.*m)[size_t(c)]; });
    };
    sum3("", "RGB", &FilmPixel::radiance);
    f.counts.emplace_back(kSamplesChannel, [](FilmPixel& p) -> uint32_t& { return p.samples; });
    for (AovKind kind : aovs) {
        const std::string name = std::string(aovName(kind)) + ".";
        const char* suffixes = exrChannelSuffixes(kind);
        switch (kind) {
            case AovKind::Normal:
                sum3(name, suffixes, &FilmPixel::normal);
                break;
            case AovKind::Albedo:
                sum3(name, suffixes, &FilmPixel::albedo);
                break;
            case AovKind::Position:
                sum3(name, suffixes, &FilmPixel::position);
                break;
            case AovKind::Depth:
                f.sums.emplace_back(kSumPrefix + name + suffixes[0],
                                    [](FilmPixel& p) -> ExactSum& { return p.depth; });
                break;
            case AovKind::ObjectId:
                // Its own channel is a float holding the film's value exactly.
                f.values.emplace_back(name + suffixes[0],
                                      [](FilmPixel& p) -> float& { return p.objectId; });
                break;
            case AovKind::Variance:
                for (int c = 0; c < 3; ++c) {
                    const std::string rgb(1, "RGB"[c]);
                    f.values.emplace_back(std::string(kWelfordPrefix) + "mean." + rgb,
                                          [c](FilmPixel& p) -> float& { return p.mean[c]; });
                    f.values.emplace_back(std::string(kWelfordPrefix) + "m2." + rgb,
                                          [c](FilmPixel& p) -> float& { return p.m2[c]; });
                }
                break;
            case AovKind::Samples:
                break;  // the counts are stored for every film (the samples channel)
        }
    }
    if (has(aovs, AovKind::Depth) || has(aovs, AovKind::Position))
        f.counts.emplace_back(kHitsChannel, [](FilmPixel& p) -> uint32_t& { return p.hits; });
    if (halves) {
        sum3("even.", "RGB", &FilmPixel::evenRadiance);
        sum3("even.normal.", "XYZ", &FilmPixel::evenNormal);
        sum3("even.albedo.", "RGB", &FilmPixel::evenAlbedo);
        f.sums.emplace_back(std::string(kSumPrefix) + "even.depth.Z",
                            [](FilmPixel& p) -> ExactSum& { return p.evenDepth; });
        f.counts.emplace_back(kEvenSamplesChannel,
                              [](FilmPixel& p) -> uint32_t& { return p.evenSamples; });
        f.counts.emplace_back(kEvenHitsChannel,
                              [](FilmPixel& p) -> uint32_t& { return p.evenHits; });
    }
    return f;
}

std::string pieceName(const std::string& base, int k) { return base + "." + std::to_string(k); }

float piece(UInt128 bits, int k) {
    return static_cast<float>(static_cast<uint32_t>(bits >> (kPieceBits * k)) & kPieceMask);
}

}  // namespace

uint64_t SamplePart::sampleCount() const {
    uint64_t n = 0;
    for (const SampleRange& r : ranges) n += r.size();
    return n;
}

std::vector<SampleRange> joinRanges(std::vector<SampleRange> ranges) {
    std::sort(ranges.begin(), ranges.end(),
              [](const SampleRange& a, const SampleRange& b) { return a.begin < b.begin; });
    std::vector<SampleRange> joined;
    for (const SampleRange& r : ranges) {
        if (!joined.empty() && joined.back().end == r.begin)
            joined.back().end = r.end;
        else
            joined.push_back(r);
    }
    return joined;
}

std::string formatRanges(const std::vector<SampleRange>& ranges) {
    std::string text;
    for (const SampleRange& r : ranges)
        text += concat(text.empty() ? "" : ",", r.begin, "-", r.end);
    return text;
}

std::optional<std::vector<SampleRange>> parseRanges(std::string_view text) {
    std::vector<SampleRange> ranges;
    const char* p = text.data();
    const char* end = text.data() + text.size();
    while (p < end) {
        SampleRange r;
        auto [afterBegin, e1] = std::from_chars(p, end, r.begin);
        if (e1 != std::errc() || afterBegin == end || *afterBegin != '-') return std::nullopt;
        auto [afterEnd, e2] = std::from_chars(afterBegin + 1, end, r.end);
        if (e2 != std::errc() || r.end <= r.begin) return std::nullopt;
        if (!ranges.empty() && r.begin < ranges.back().end) return std::nullopt;
        ranges.push_back(r);
        p = afterEnd;
        if (p < end && *p++ != ',') return std::nullopt;
        if (p == end && text.back() == ',') return std::nullopt;
    }
    if (ranges.empty()) return std::nullopt;
    return ranges;
}

void appendExactChannels(const Film& film, std::vector<std::string>& names,
                         std::vector<std::vector<float>>& planes) {
    Fields fields = fieldsOf(film.aovs(), film.keepsHalves());
    // objectid is written as an ordinary AOV channel already.
    std::erase_if(fields.values, [](const auto& f) { return f.first.rfind(kWelfordPrefix, 0) != 0; });
    const PixelRect& crop = film.crop();
    const size_t count = size_t(crop.width()) * size_t(crop.height());
    const size_t first = planes.size();
    for (const auto& field : fields.sums)
        for (int k = 0; k < kSumPieces; ++k) names.push_back(pieceName(field.first, k));
    for (const auto& field : fields.counts)
        for (int k = 0; k < kCountPieces; ++k) names.push_back(pieceName(field.first, k));
    for (const auto& field : fields.values) names.push_back(field.first);
    planes.resize(first + fields.sums.size() * kSumPieces + fields.counts.size() * kCountPieces +
                      fields.values.size(),
                  std::vector<float>(count));

    size_t i = 0;  // the pixel, row-major in the crop
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x, ++i) {
            FilmPixel p = film.pixel(x, y);
            size_t plane = first;
            for (auto& [name, at] : fields.sums) {
                const auto bits = static_cast<UInt128>(at(p).raw());  // two's complement
                for (int k = 0; k < kSumPieces; ++k) planes[plane++][i] = piece(bits, k);
            }
            for (auto& [name, at] : fields.counts)
                for (int k = 0; k < kCountPieces; ++k) planes[plane++][i] = piece(at(p), k);
            for (auto& [name, at] : fields.values) planes[plane++][i] = at(p);
        }
}

bool hasExactChannels(const std::vector<std::string>& channels) {
    return std::any_of(channels.begin(), channels.end(), [](const std::string& name) {
        return name.rfind(kSumPrefix, 0) == 0 || name.rfind("strahl.count.", 0) == 0 ||
               name.rfind(kWelfordPrefix, 0) == 0;
    });
}

void readExactChannels(Film& film, const std::vector<std::string>& channels,
                       const std::vector<float>& pixels, const std::string& source) {
    Fields fields = fieldsOf(film.aovs(), film.keepsHalves());
    std::unordered_map<std::string, size_t> column;
    for (size_t c = 0; c < channels.size(); ++c) column[channels[c]] = c;
    const auto find = [&](const std::string& name) {
        const auto it = column.find(name);
        if (it == column.end())
            fail(source, ": channel '", name, "' of the exact sums is missing");
        return it->second;
    };
    const auto columns = [&](const std::string& base, int pieces) {
        std::vector<size_t> cs;
        for (int k = 0; k < pieces; ++k) cs.push_back(find(pieceName(base, k)));
        return cs;
    };
    std::vector<std::vector<size_t>> sumColumns, countColumns;
    for (const auto& field : fields.sums) sumColumns.push_back(columns(field.first, kSumPieces));
    for (const auto& field : fields.counts) countColumns.push_back(columns(field.first, kCountPieces));
    std::vector<size_t> valueColumns;
    for (const auto& field : fields.values) valueColumns.push_back(find(field.first));

    const size_t stride = channels.size();
    // The integer a column's pieces hold; anything but whole numbers below
    // 2^24 (2^8 for the top piece of a sum, which holds bits 120..127) is not
    // ours.
    const auto integer = [&](const float* px, const std::vector<size_t>& cs, int topBits) {
        UInt128 bits = 0;
        for (size_t k = 0; k < cs.size(); ++k) {
            const float v = px[cs[k]];
            const int width = k + 1 == cs.size() ? topBits : kPieceBits;
            if (!(v >= 0.0f && v < static_cast<float>(1u << width) && v == std::floor(v)))
                fail(source, ": channel '", channels[cs[k]], "' does not hold an exact sum (",
                     v, ")");
            bits |= static_cast<UInt128>(static_cast<uint32_t>(v)) << (kPieceBits * int(k));
        }
        return bits;
    };
    constexpr int kSumTopBits = 128 - kPieceBits * (kSumPieces - 1);      // 8
    constexpr int kCountTopBits = 32 - kPieceBits * (kCountPieces - 1);  // 8

    const PixelRect& crop = film.crop();
    size_t i = 0;
    for (int y = crop.y0; y < crop.y1; ++y)
        for (int x = crop.x0; x < crop.x1; ++x, ++i) {
            const float* px = pixels.data() + i * stride;
            FilmPixel p;
            for (size_t f = 0; f < fields.sums.size(); ++f)
                fields.sums[f].second(p) =
                    ExactSum::fromRaw(static_cast<Int128>(integer(px, sumColumns[f], kSumTopBits)));
            for (size_t f = 0; f < fields.counts.size(); ++f)
                fields.counts[f].second(p) =
                    static_cast<uint32_t>(integer(px, countColumns[f], kCountTopBits));
            for (size_t f = 0; f < fields.values.size(); ++f)
                fields.values[f].second(p) = px[valueColumns[f]];
            if (p.samples > ExactSum::kMaxSamples || p.hits > p.samples)
                fail(source, ": pixel (", x, ", ", y, ") has ", p.samples, " samples and ", p.hits,
                     " hits, which no render gives");
            film.setPixel(x, y, p);
        }
}

}  // namespace strahl
