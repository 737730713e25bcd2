// Stanford PLY loader: ascii, binary_little_endian and binary_big_endian 1.0.
// The header is parsed into a list of elements; the body is then read by one
// generic routine over a per-encoding value source, which keeps the vertex
// positions/normals/uvs and the face index lists and skips everything else.

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <optional>
#include <utility>

#include "strahl/meshio/mesh_file.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace {

// ---------------------------------------------------------------------------
// Header

enum class Scalar : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

size_t sizeOf(Scalar t) {
    switch (t) {
        case Scalar::Int8:
        case Scalar::UInt8:
            return 1;
        case Scalar::Int16:
        case Scalar::UInt16:
            return 2;
        case Scalar::Int32:
        case Scalar::UInt32:
        case Scalar::Float32:
            return 4;
        case Scalar::Float64:
            return 8;
    }
    return 0;
}

bool isInteger(Scalar t) {
    return t != Scalar::Float32 && t != Scalar::Float64;
}

std::optional<Scalar> scalarNamed(std::string_view name) {
    static constexpr std::pair<std::string_view, Scalar> kNames[] = {
        {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
        {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
        {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
        {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
        {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
        {"float64", Scalar::Float64}};
    for (const auto& [n, t] : kNames) {
        if (n == name) return t;
    }
    return std::nullopt;
}

struct Property {
    std::string name;
    Scalar type = Scalar::Float32;  // the item type for a list
    bool isList = false;
    Scalar countType = Scalar::UInt8;
    size_t headerLine = 0;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
    size_t headerLine = 0;

    const Property* find(std::string_view propertyName) const {
        for (const Property& p : properties) {
            if (p.name == propertyName) return &p;
        }
        return nullptr;
    }
};

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    size_t bodyOffset = 0;     // first byte after the end_header line
    size_t endHeaderLine = 0;  // for errors about the header as a whole
};

Header parseHeader(const std::string& file, std::string_view data) {
    Header h;
    bool haveFormat = false;
    size_t pos = 0;
    for (size_t lineNo = 1;; ++lineNo) {
        const auto error = [&](const auto&... args) {
            fail(file, ": header line ", lineNo, ": ", args...);
        };
        if (pos >= data.size()) error("end of file before end_header");
        size_t eol = data.find('\n', pos);
        if (eol == std::string_view::npos) eol = data.size();
        const std::string_view line(data.data() + pos, eol - pos);
        pos = eol + 1;

        std::vector<std::string_view> tokens;
        meshio::LineScanner words{file, lineNo, line.data(), line.data() + line.size()};
        for (std::string_view w = words.token(); !w.empty(); w = words.token()) tokens.push_back(w);

        if (lineNo == 1) {
            if (tokens.size() != 1 || tokens[0] != "ply") error("not a PLY file (expected 'ply')");
            continue;
        }
        if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
        const std::string_view keyword = tokens[0];
        if (keyword == "format") {
            if (haveFormat) error("second format line");
            if (tokens.size() != 3) error("expected 'format <encoding> 1.0'");
            if (tokens[1] == "ascii") {
                h.encoding = Encoding::Ascii;
            } else if (tokens[1] == "binary_little_endian") {
                h.encoding = Encoding::BinaryLittleEndian;
            } else if (tokens[1] == "binary_big_endian") {
                h.encoding = Encoding::BinaryBigEndian;
            } else {
                error("unknown format '", tokens[1], "'");
            }
            if (tokens[2] != "1.0") error("unsupported PLY version '", tokens[2], "'");
            haveFormat = true;
        } else if (keyword == "element") {
            if (tokens.size() != 3) error("expected 'element <name> <count>'");
            Element e;
            e.name = tokens[1];
            e.headerLine = lineNo;
            const auto [next, ec] =
                std::from_chars(tokens[2].data(), tokens[2].data() + tokens[2].size(), e.count);
            if (ec != std::errc() || next != tokens[2].data() + tokens[2].size())
                error("element count '", tokens[2], "' is not a non-negative integer");
            if (e.name == "tristrips")
                error("element 'tristrips' (triangle strips) is not supported");
            h.elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (h.elements.empty()) error("property before the first element");
            Property p;
            p.headerLine = lineNo;
            std::optional<Scalar> type;
            if (tokens.size() >= 2 && tokens[1] == "list") {
                if (tokens.size() != 5)
                    error("expected 'property list <count type> <type> <name>'");
                const std::optional<Scalar> countType = scalarNamed(tokens[2]);
                if (!countType) error("unknown type '", tokens[2], "'");
                if (!isInteger(*countType))
                    error("list count type '", tokens[2], "' is not an integer");
                p.isList = true;
                p.countType = *countType;
                type = scalarNamed(tokens[3]);
                if (!type) error("unknown type '", tokens[3], "'");
            } else {
                if (tokens.size() != 3) error("expected 'property <type> <name>'");
                type = scalarNamed(tokens[1]);
                if (!type) error("unknown type '", tokens[1], "'");
            }
            p.type = *type;
            p.name = tokens.back();
            h.elements.back().properties.push_back(std::move(p));
        } else if (keyword == "end_header") {
            if (!haveFormat) error("end_header before any format line");
            h.bodyOffset = std::min(pos, data.size());
            h.endHeaderLine = lineNo;
            return h;
        } else {
            error("unknown header keyword '", keyword, "'");
        }
    }
}

// ---------------------------------------------------------------------------
// Body value sources: read one scalar at a time; errors name the place of the
// value read last.

template <typename U>
U byteSwap(U v) {
    U out = 0;
    for (size_t i = 0; i < sizeof(U); ++i) {
        out = static_cast<U>((out << 8) | (v & 0xff));
        v = static_cast<U>(v >> 8);
    }
    return out;
}

template <bool kSwap>
class BinarySource {
public:
    BinarySource(const std::string& file, std::string_view data, size_t offset)
        : file_(file),
          begin_(data.data()),
          p_(begin_ + offset),
          last_(p_),
          end_(begin_ + data.size()) {}

    size_t bytesLeft() const { return size_t(end_ - p_); }

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
        if (size_t(end_ - p_) < n) error("unexpected end of file (truncated?)");
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
        const auto [next, ec] = meshio::parseNumber(tok.data(), tok.data() + tok.size(), value);
        if (ec != std::errc() || next != tok.data() + tok.size())
            error("cannot parse '", tok, "' as a number");
        return value;
    }

    int64_t integer(Scalar t) {
        const std::string_view tok = token();
        int64_t value = 0;
        const auto [next, ec] = meshio::parseNumber(tok.data(), tok.data() + tok.size(), value);
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
        while (p_ < end_ && (meshio::isBlank(*p_) || *p_ == '\n')) {
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
        while (p_ < end_ && !meshio::isBlank(*p_) && *p_ != '\n') ++p_;
        return {start, size_t(p_ - start)};
    }

    const std::string& file_;
    const char* begin_;
    const char* p_;
    const char* end_;
    size_t line_;
    size_t tokenLine_;  // line of the token read last
};

// ---------------------------------------------------------------------------
// Reading the body

// What each vertex property is used for.
enum Role : int { kSkip = -1, kX, kY, kZ, kNX, kNY, kNZ, kU, kV, kRoleCount };

struct Layout {
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    const Property* faceIndices = nullptr;
    std::vector<int> vertexRoles;  // one Role per vertex property
    bool hasNormals = false;
    bool hasUvs = false;
};

Layout makeLayout(const std::string& file, const Header& h) {
    Layout layout;
    const auto error = [&](size_t line, const auto&... args) {
        fail(file, ": header line ", line, ": ", args...);
    };
    for (const Element& e : h.elements) {
        if (e.name == "vertex" && !layout.vertex) layout.vertex = &e;
        if (e.name == "face" && !layout.face) layout.face = &e;
    }
    if (!layout.vertex) error(h.endHeaderLine, "no 'vertex' element");
    const Element& v = *layout.vertex;
    if (v.count > UINT32_MAX)
        error(v.headerLine, "element vertex has ", v.count, " vertices, more than 2^32-1");

    // The first property of each name plays its role; a pair or triple is only
    // used when complete.
    const auto scalar = [&](std::string_view name) -> const Property* {
        const Property* p = v.find(name);
        if (p && p->isList) error(p->headerLine, "vertex property '", name, "' is a list");
        return p;
    };
    for (const char* axis : {"x", "y", "z"}) {
        if (!scalar(axis)) error(v.headerLine, "element vertex has no property '", axis, "'");
    }
    std::array<const Property*, kRoleCount> byRole{scalar("x"), scalar("y"), scalar("z")};
    if (scalar("nx") && scalar("ny") && scalar("nz")) {
        byRole[kNX] = scalar("nx");
        byRole[kNY] = scalar("ny");
        byRole[kNZ] = scalar("nz");
        layout.hasNormals = true;
    }
    static constexpr std::pair<const char*, const char*> kUvNames[] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const auto& [u, vName] : kUvNames) {
        if (scalar(u) && scalar(vName)) {
            byRole[kU] = scalar(u);
            byRole[kV] = scalar(vName);
            layout.hasUvs = true;
            break;
        }
    }
    for (const Property& p : v.properties) {
        const auto it = std::find(byRole.begin(), byRole.end(), &p);
        layout.vertexRoles.push_back(it == byRole.end() ? kSkip : int(it - byRole.begin()));
    }

    if (layout.face) {
        const Element& f = *layout.face;
        layout.faceIndices = f.find("vertex_indices");
        if (!layout.faceIndices) layout.faceIndices = f.find("vertex_index");
        if (!layout.faceIndices)
            error(f.headerLine, "element face has no 'vertex_indices' property");
        const Property& p = *layout.faceIndices;
        if (!p.isList || !isInteger(p.type))
            error(p.headerLine, "face property '", p.name, "' is not a list of integers");
    }
    return layout;
}

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
    std::array<float, kRoleCount> values{};
    for (uint64_t i = 0; i < e.count; ++i) {
        for (size_t k = 0; k < e.properties.size(); ++k) {
            const Property& p = e.properties[k];
            const int role = layout.vertexRoles[k];
            if (p.isList) {
                skipList(src, p);
            } else if (role == kSkip) {
                src.skip(p.type);
            } else {
                values[size_t(role)] = static_cast<float>(src.real(p.type));
                if (!std::isfinite(values[size_t(role)]))
                    src.error("vertex ", i, " has a non-finite ", p.name);
            }
        }
        mesh.positions.emplace_back(values[kX], values[kY], values[kZ]);
        if (layout.hasNormals) mesh.normals.emplace_back(values[kNX], values[kNY], values[kNZ]);
        if (layout.hasUvs) mesh.uvs.emplace_back(values[kU], values[kV]);
    }
}

template <typename Source>
void readFaces(Source& src, const Layout& layout, bool binary, TriangleMesh& mesh) {
    const Element& e = *layout.face;
    const uint64_t vertexCount = layout.vertex->count;
    mesh.indices.reserve(3 * plausibleCount(src, e, binary));
    std::vector<uint32_t> polygon;
    for (uint64_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.properties) {
            if (&p != layout.faceIndices) {
                p.isList ? skipList(src, p) : src.skip(p.type);
                continue;
            }
            const int64_t n = src.integer(p.countType);
            if (n < 3) src.error("face ", i, " has ", n, " vertices (needs at least 3)");
            polygon.clear();
            for (int64_t k = 0; k < n; ++k) {
                const int64_t index = src.integer(p.type);
                if (index < 0 || uint64_t(index) >= vertexCount)
                    src.error("face ", i, " refers to vertex ", index, " but there are only ",
                              vertexCount, " vertices");
                polygon.push_back(static_cast<uint32_t>(index));
            }
            // Fan triangulation keeps the polygon's winding (convex polygons only).
            for (size_t k = 1; k + 1 < polygon.size(); ++k)
                mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
        }
    }
}

template <typename Source>
TriangleMesh readBody(Source& src, const Header& h, const Layout& layout) {
    const bool binary = h.encoding != Encoding::Ascii;
    TriangleMesh mesh;
    for (const Element& e : h.elements) {
        if (e.properties.empty()) continue;  // items without properties occupy no bytes
        if (&e == layout.vertex) {
            readVertices(src, layout, binary, mesh);
        } else if (&e == layout.face) {
            readFaces(src, layout, binary, mesh);
        } else {
            for (uint64_t i = 0; i < e.count; ++i) {
                for (const Property& p : e.properties)
                    p.isList ? skipList(src, p) : src.skip(p.type);
            }
        }
    }
    return mesh;
}

}  // namespace

LoadedMesh loadPly(const fs::path& file) {
    return loadPlyFromMemory(meshio::readWholeFile(file), file);
}

LoadedMesh loadPlyFromMemory(std::string_view data, const fs::path& file) {
    const std::string name = file.string();
    const Header header = parseHeader(name, data);
    const Layout layout = makeLayout(name, header);

    LoadedMesh result;
    constexpr bool kLittleHost = std::endian::native == std::endian::little;
    switch (header.encoding) {
        case Encoding::Ascii: {
            AsciiSource src(name, data, header.bodyOffset, header.endHeaderLine + 1);
            result.mesh = readBody(src, header, layout);
            break;
        }
        case Encoding::BinaryLittleEndian: {
            BinarySource<!kLittleHost> src(name, data, header.bodyOffset);
            result.mesh = readBody(src, header, layout);
            break;
        }
        case Encoding::BinaryBigEndian: {
            BinarySource<kLittleHost> src(name, data, header.bodyOffset);
            result.mesh = readBody(src, header, layout);
            break;
        }
    }
    result.mesh.validate(name);
    return result;
}

}  // namespace strahl
