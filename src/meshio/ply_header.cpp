// PLY header parsing and the layout the loader reads the body with.

#include "ply_header.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

#include "strahl/core/srgb.h"
#include "strahl/core/error.h"
#include "text_scan.h"

namespace strahl::meshio::ply {

namespace {

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

// Mitsuba's grouping of an element's other scalar properties into attributes:
// r g b [a] (or red green blue [alpha]) are "<scope>_color"; then runs of
// consecutive properties <prefix>_<c> whose one-letter suffixes go x y z w,
// r g b a, 0 1 2 3 or 1 2 3 4 are "<scope>_<prefix>" (+ "_color" for r g b a),
// kept with 1 or 3 channels. Anything else (no suffix, a broken run, a prefix
// seen before) is not an attribute and is skipped, with a warning for the runs.
std::vector<AttributeColumns> groupAttributes(const std::string& file, const Element& e,
                                              const std::string& scope,
                                              const std::vector<const Property*>& reserved) {
    std::vector<AttributeColumns> groups;
    std::vector<bool> used(e.properties.size(), false);
    for (const Property* p : reserved) used[size_t(p - e.properties.data())] = true;
    const auto index = [&](std::string_view name) -> std::optional<size_t> {
        const Property* p = e.find(name);
        if (!p || p->isList || used[size_t(p - e.properties.data())]) return std::nullopt;
        return size_t(p - e.properties.data());
    };
    for (const auto& names : {std::array<std::string_view, 4>{"r", "g", "b", "a"},
                              std::array<std::string_view, 4>{"red", "green", "blue", "alpha"}}) {
        const auto r = index(names[0]), g = index(names[1]), b = index(names[2]);
        if (!r || !g || !b) continue;
        AttributeColumns color{scope + "_color", {*r, *g, *b}};
        if (const auto a = index(names[3])) color.properties.push_back(*a);
        for (size_t k : color.properties) used[k] = true;
        groups.push_back(std::move(color));
        break;
    }
    for (std::string_view name : {"r", "g", "b", "a"})
        if (const auto k = index(name)) used[*k] = true;

    static constexpr std::string_view kSuffixes[] = {"xyzw", "rgba", "0123", "1234"};
    std::vector<std::string> seen;
    AttributeColumns run;
    int category = -1;
    bool broken = false;
    const auto flush = [&] {
        if (category < 0) return;
        const size_t n = run.properties.size();
        if (broken || (n != 1 && n != 3)) {
            warn(concat(file, ": element ", e.name, ": properties ", run.name,
                        "_* are not an attribute (", broken ? "their suffixes break the sequence" : concat(n, " channels, not 1 or 3"),
                        "): skipped"));
        } else {
            groups.push_back({concat(scope, '_', run.name, category == 1 ? "_color" : ""), run.properties});
        }
        category = -1;
        broken = false;
        run = {};
    };
    for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (used[k] || p.isList) continue;
        const size_t underscore = p.name.rfind('_');
        if (underscore == std::string::npos || underscore + 2 != p.name.size()) {
            flush();
            continue;
        }
        const std::string prefix = p.name.substr(0, underscore);
        const char suffix = p.name.back();
        if (category >= 0 && prefix == run.name) {
            const size_t level = run.properties.size();
            if (level < 4 && kSuffixes[category][level] == suffix)
                run.properties.push_back(k);
            else
                broken = true;
            continue;
        }
        flush();
        if (std::find(seen.begin(), seen.end(), prefix) != seen.end()) continue;
        for (int c = 0; c < 4; ++c)
            if (kSuffixes[c][0] == suffix) category = c;
        if (category < 0) continue;
        seen.push_back(prefix);
        run = {prefix, {k}};
    }
    flush();
    return groups;
}


}  // namespace

float attributeValue(double raw, Scalar type) {
    if (!isInteger(type)) return static_cast<float>(raw);
    const bool isSigned = type == Scalar::Int8 || type == Scalar::Int16 || type == Scalar::Int32;
    const double largest = std::ldexp(1.0, int(8 * sizeOf(type)) - (isSigned ? 1 : 0)) - 1.0;
    return static_cast<float>(srgbToLinear(std::clamp(raw / largest, 0.0, 1.0)));
}

std::vector<MeshAttribute> makeAttributes(const Layout& layout) {
    std::vector<MeshAttribute> out;
    for (const AttributeColumns& a : layout.vertexAttributes)
        out.push_back({a.name, MeshAttribute::Scope::Vertex, int(a.properties.size()), {}});
    for (const AttributeColumns& a : layout.faceAttributes)
        out.push_back({a.name, MeshAttribute::Scope::Face, int(a.properties.size()), {}});
    return out;
}

const Property* Element::find(std::string_view propertyName) const {
    for (const Property& p : properties) {
        if (p.name == propertyName) return &p;
    }
    return nullptr;
}

size_t Element::fixedBinarySize() const {
    size_t size = 0;
    for (const Property& p : properties) {
        if (p.isList) return 0;
        size += sizeOf(p.type);
    }
    return size;
}

size_t Element::minBinarySize(const Property* atLeastThree) const {
    size_t size = 0;
    for (const Property& p : properties) {
        if (!p.isList)
            size += sizeOf(p.type);
        else
            size += sizeOf(p.countType) + (&p == atLeastThree ? 3 * sizeOf(p.type) : 0);
    }
    return size;
}

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
        LineScanner words{file, lineNo, line.data(), line.data() + line.size()};
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
    std::vector<const Property*> reserved;
    for (const Property* p : byRole)
        if (p) reserved.push_back(p);
    layout.vertexAttributes = groupAttributes(file, v, "vertex", reserved);
    layout.vertexRoles.assign(v.properties.size(), kSkip);
    for (size_t k = 0; k < v.properties.size(); ++k) {
        const auto it = std::find(byRole.begin(), byRole.end(), &v.properties[k]);
        if (it != byRole.end()) layout.vertexRoles[k] = int(it - byRole.begin());
    }
    int channel = kRoleCount;
    for (const AttributeColumns& a : layout.vertexAttributes)
        for (size_t k : a.properties) layout.vertexRoles[k] = channel++;

    if (layout.face) {
        const Element& f = *layout.face;
        layout.faceIndices = f.find("vertex_indices");
        if (!layout.faceIndices) layout.faceIndices = f.find("vertex_index");
        if (!layout.faceIndices)
            error(f.headerLine, "element face has no 'vertex_indices' property");
        const Property& p = *layout.faceIndices;
        if (!p.isList || !isInteger(p.type))
            error(p.headerLine, "face property '", p.name, "' is not a list of integers");
        layout.faceAttributes = groupAttributes(file, f, "face", {&p});
        layout.faceChannels.assign(f.properties.size(), -1);
        int faceChannel = 0;
        for (const AttributeColumns& a : layout.faceAttributes)
            for (size_t k : a.properties) layout.faceChannels[k] = faceChannel++;
    }
    return layout;
}

}  // namespace strahl::meshio::ply
