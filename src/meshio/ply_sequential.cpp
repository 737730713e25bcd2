// The generic PLY body reader: one value at a time through a per-encoding
// source, keeping vertex positions/normals/uvs, face index lists and the
// layout's attributes and skipping everything else. It reads ascii bodies, and
// binary elements the parallel decoder (ply_parallel.cpp) does not take: lists
// in vertices, faces with more than one list or with attributes, and every
// element whose data is cut short, where it finds the first bad value in file
// order and names its place.

#include "ply_sequential.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "ply_binary.h"
#include "strahl/core/error.h"
#include "text_scan.h"

namespace strahl::meshio::ply {

namespace {

// ---------------------------------------------------------------------------
// Body value sources: read one scalar at a time; errors name the place of the
// value read last.

template <bool kSwap>
class BinarySource {
public:
    BinarySource(const std::string& file, std::string_view data, size_t offset,
                 std::string_view truncationNote)
        : file_(file),
          note_(truncationNote),
          begin_(data.data()),
          p_(begin_ + offset),
          last_(p_),
          end_(begin_ + data.size()) {}

    size_t bytesLeft() const { return size_t(end_ - p_); }
    size_t offset() const { return size_t(p_ - begin_); }

    double real(Scalar t) {
        switch (t) {
            case Scalar::Float32:
                return load<float, uint32_t>();
            case Scalar::Float64:
                return load<double, uint64_t>();
            default:
                return static_cast<double>(integer(t));
        }
    }

    int64_t integer(Scalar t) {
        switch (t) {
            case Scalar::Int8:
                return load<int8_t, uint8_t>();
            case Scalar::UInt8:
                return load<uint8_t, uint8_t>();
            case Scalar::Int16:
                return load<int16_t, uint16_t>();
            case Scalar::UInt16:
                return load<uint16_t, uint16_t>();
            case Scalar::Int32:
                return load<int32_t, uint32_t>();
            case Scalar::UInt32:
                return load<uint32_t, uint32_t>();
            default:
                error("expected an integer type");  // ruled out by the header checks
        }
    }

    void skip(Scalar t) {
        need(sizeOf(t));
        p_ += sizeOf(t);
    }

    template <typename... Args>
    [[noreturn]] void error(const Args&... args) const {
        fail(file_, ": byte offset ", last_ - begin_, ": ", args...);
    }

private:
    void need(size_t n) {
        last_ = p_;
        if (size_t(end_ - p_) < n) error("unexpected end of file (truncated?)", note_);
    }

    template <typename T, typename Bits>
    T load() {
        need(sizeof(T));
        Bits bits;
        std::memcpy(&bits, p_, sizeof bits);
        p_ += sizeof bits;
        if constexpr (kSwap) bits = byteSwap(bits);
        return std::bit_cast<T>(bits);
    }

    const std::string& file_;
    std::string_view note_;  // appended to the end-of-file error
    const char* begin_;
    const char* p_;
    const char* last_;  // start of the value read last
    const char* end_;
};

class AsciiSource {
public:
    AsciiSource(const std::string& file, std::string_view data, size_t offset, size_t line)
        : file_(file),
          begin_(data.data()),
          p_(begin_ + offset),
          end_(begin_ + data.size()),
          line_(line),
          tokenLine_(line) {}

    size_t bytesLeft() const { return size_t(end_ - p_); }

    double real(Scalar t) {
        if (isInteger(t)) return static_cast<double>(integer(t));
        const std::string_view tok = token();
        double value = 0.0;
        const auto [next, ec] = parseNumber(tok.data(), tok.data() + tok.size(), value);
        if (ec != std::errc() || next != tok.data() + tok.size())
            error("cannot parse '", tok, "' as a number");
        return value;
    }

    int64_t integer(Scalar t) {
        const std::string_view tok = token();
        int64_t value = 0;
        const auto [next, ec] = parseNumber(tok.data(), tok.data() + tok.size(), value);
        if (ec != std::errc() || next != tok.data() + tok.size())
            error("cannot parse '", tok, "' as an integer");
        const int bits = int(8 * sizeOf(t));
        const bool isSigned = t == Scalar::Int8 || t == Scalar::Int16 || t == Scalar::Int32;
        const int64_t lo = isSigned ? -(int64_t(1) << (bits - 1)) : 0;
        const int64_t hi = isSigned ? (int64_t(1) << (bits - 1)) - 1 : (int64_t(1) << bits) - 1;
        if (value < lo || value > hi) error("value ", value, " does not fit its type");
        return value;
    }

    void skip(Scalar) { token(); }

    template <typename... Args>
    [[noreturn]] void error(const Args&... args) const {
        fail(file_, ":line ", tokenLine_, ": ", args...);
    }

private:
    std::string_view token() {
        while (p_ < end_ && (isBlank(*p_) || *p_ == '\n')) {
            if (*p_ == '\n') ++line_;
            ++p_;
        }
        tokenLine_ = line_;
        if (p_ == end_) {
            // Blame the last line there is, not the empty one after its newline.
            if (p_ != begin_ && p_[-1] == '\n') --tokenLine_;
            error("unexpected end of file (truncated?)");
        }
        const char* start = p_;
        while (p_ < end_ && !isBlank(*p_) && *p_ != '\n') ++p_;
        return {start, size_t(p_ - start)};
    }

    const std::string& file_;
    const char* begin_;
    const char* p_;
    const char* end_;
    size_t line_;
    size_t tokenLine_;  // line of the token read last
};

// At most this many items can fit in what is left of the file: a bound for
// reserve() that a lying element count cannot blow up.
template <typename Source>
size_t plausibleCount(const Source& src, const Element& e, bool binary) {
    size_t minBytes = 0;
    for (const Property& p : e.properties)
        minBytes += binary ? sizeOf(p.isList ? p.countType : p.type) : 2;
    return size_t(std::min<uint64_t>(e.count, src.bytesLeft() / std::max<size_t>(minBytes, 1)));
}

template <typename Source>
void skipList(Source& src, const Property& p) {
    const int64_t n = src.integer(p.countType);
    if (n < 0) src.error("negative list length ", n);
    for (int64_t i = 0; i < n; ++i) src.skip(p.type);
}

template <typename Source>
void readVertices(Source& src, const Layout& layout, bool binary, TriangleMesh& mesh) {
    const Element& e = *layout.vertex;
    const size_t expected = plausibleCount(src, e, binary);
    mesh.positions.reserve(expected + 1);  // the spare element Embree's 16-byte loads need
    if (layout.hasNormals) mesh.normals.reserve(expected);
    if (layout.hasUvs) mesh.uvs.reserve(expected);
    std::vector<float> values(kRoleCount + layout.vertexChannels(), 0.0f);
    for (uint64_t i = 0; i < e.count; ++i) {
        for (size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            const int role = layout.vertexRoles[k];
            if (p.isList) {
                skipList(src, p);
            } else if (role == kSkip) {
                src.skip(p.type);
            } else {
                const double raw = src.real(p.type);
                float& value = values[size_t(role)];
                value = role < kRoleCount ? static_cast<float>(raw) : attributeValue(raw, p.type);
                if (!std::isfinite(value)) src.error("vertex ", i, " has a non-finite ", p.name);
            }
        }
        mesh.positions.emplace_back(values[kX], values[kY], values[kZ]);
        if (layout.hasNormals) mesh.normals.emplace_back(values[kNX], values[kNY], values[kNZ]);
        if (layout.hasUvs) mesh.uvs.emplace_back(values[kU], values[kV]);
        size_t channel = kRoleCount;
        for (size_t a = 0; a < layout.vertexAttributes.size(); ++a)
            for (size_t c = 0; c < layout.vertexAttributes[a].properties.size(); ++c)
                mesh.attributes[a].values.push_back(values[channel++]);
    }
}

template <typename Source>
void readFaces(Source& src, const Layout& layout, bool binary, TriangleMesh& mesh) {
    const Element& e = *layout.face;
    const uint64_t vertexCount = layout.vertex->count;
    mesh.indices.reserve(3 * plausibleCount(src, e, binary));
    std::vector<uint32_t> polygon;
    std::vector<float> channels(layout.faceChannelCount(), 0.0f);
    const size_t firstFaceAttribute = layout.vertexAttributes.size();
    for (uint64_t i = 0; i < e.count; ++i) {
        const size_t trianglesBefore = mesh.indices.size() / 3;
        for (size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            if (layout.faceChannels[k] >= 0) {
                const float value = attributeValue(src.real(p.type), p.type);
                if (!std::isfinite(value)) src.error("face ", i, " has a non-finite ", p.name);
                channels[size_t(layout.faceChannels[k])] = value;
                continue;
            }
            if (&p != layout.faceIndices) {
                p.isList ? skipList(src, p) : src.skip(p.type);
                continue;
            }
            const int64_t n = src.integer(p.countType);
            if (n < 3) src.error("face ", i, " has ", n, " vertices (needs at least 3)");
            polygon.clear();
            for (int64_t corner = 0; corner < n; ++corner) {
                const int64_t index = src.integer(p.type);
                if (index < 0 || uint64_t(index) >= vertexCount)
                    src.error("face ", i, " refers to vertex ", index, " but there are only ",
                              vertexCount, " vertices");
                polygon.push_back(static_cast<uint32_t>(index));
            }
            // Fan triangulation keeps the polygon's winding (convex polygons only).
            for (size_t c = 1; c + 1 < polygon.size(); ++c)
                mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[c], polygon[c + 1]});
        }
        // The face's attribute values, once for each triangle of its fan.
        for (size_t t = trianglesBefore; t < mesh.indices.size() / 3; ++t) {
            size_t channel = 0;
            for (size_t a = 0; a < layout.faceAttributes.size(); ++a)
                for (size_t c = 0; c < layout.faceAttributes[a].properties.size(); ++c)
                    mesh.attributes[firstFaceAttribute + a].values.push_back(channels[channel++]);
        }
    }
}

template <typename Source>
void readElement(Source& src, const Layout& layout, bool binary, const Element& e,
                 TriangleMesh& mesh) {
    if (e.properties.empty()) return;  // items without properties occupy no bytes
    if (&e == layout.vertex) {
        readVertices(src, layout, binary, mesh);
    } else if (&e == layout.face) {
        readFaces(src, layout, binary, mesh);
    } else {
        for (uint64_t i = 0; i < e.count; ++i) {
            for (const Property& p : e.properties) p.isList ? skipList(src, p) : src.skip(p.type);
        }
    }
}

}  // namespace

size_t readBinaryElement(const std::string& file, std::string_view data, size_t offset,
                         bool swapBytes, const Layout& layout, const Element& e,
                         TriangleMesh& mesh, std::string_view truncationNote) {
    if (swapBytes) {
        BinarySource<true> src(file, data, offset, truncationNote);
        readElement(src, layout, true, e, mesh);
        return src.offset();
    }
    BinarySource<false> src(file, data, offset, truncationNote);
    readElement(src, layout, true, e, mesh);
    return src.offset();
}

void readAsciiBody(const std::string& file, std::string_view data, const Header& h,
                   const Layout& layout, TriangleMesh& mesh) {
    AsciiSource src(file, data, h.bodyOffset, h.endHeaderLine + 1);
    for (const Element& e : h.elements) readElement(src, layout, false, e, mesh);
}

}  // namespace strahl::meshio::ply
