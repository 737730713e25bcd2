// OBJ chunks: cutting the text, counting statements, parsing one chunk. The
// statement rules are those of docs/mesh-formats.md ("OBJ"); the errors are
// the ones a line-by-line reader of the whole file would raise first within
// the chunk, since every check that depends on earlier lines only needs the
// v/vt/vn counts before the chunk.

#include "obj_chunks.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "text_scan.h"

namespace strahl::meshio::obj {

namespace {

// The first blank-separated token of the line [p, end).
std::string_view keywordOf(const char* p, const char* end) {
    while (p < end && isBlank(*p)) ++p;
    const char* start = p;
    while (p < end && !isBlank(*p)) ++p;
    return {start, size_t(p - start)};
}

class ChunkParser {
public:
    ChunkParser(Chunk& chunk, Attributes& attributes) : c_(chunk), a_(attributes) {}

    void statement(LineScanner& s) {
        const std::string_view keyword = s.token();
        if (keyword == "v") {
            Vec3 p(0.0f);
            p.x = s.finiteFloat("coordinate");
            p.y = s.finiteFloat("coordinate");
            p.z = s.finiteFloat("coordinate");
            while (!s.atEnd()) s.number("vertex value");  // w or a vertex colour: unused
            a_.positions[c_.before.v + c_.parsed.v++] = p;
        } else if (keyword == "vt") {
            Vec2 uv(0.0f);  // a missing v is 0
            uv.x = s.finiteFloat("texture coordinate");
            if (!s.atEnd()) uv.y = s.finiteFloat("texture coordinate");
            if (!s.atEnd()) s.number("texture coordinate");  // w: unused
            s.expectEnd("vt");
            a_.texcoords[c_.before.vt + c_.parsed.vt++] = uv;
        } else if (keyword == "vn") {
            Vec3 n(0.0f);
            n.x = s.finiteFloat("normal coordinate");
            n.y = s.finiteFloat("normal coordinate");
            n.z = s.finiteFloat("normal coordinate");
            s.expectEnd("vn");
            a_.normals[c_.before.vn + c_.parsed.vn++] = n;
        } else if (keyword == "f") {
            face(s);
        } else if (keyword == "usemtl") {
            const std::string_view material = s.rest();
            if (material.empty()) s.error("usemtl without a material name");
            c_.usemtl.push_back({material, s.line});
        } else if (keyword == "mtllib") {
            c_.deferred.push_back({Deferred::Kind::MaterialLibrary, s.line, s.rest()});
        } else if (keyword.empty() || keyword[0] == '#' || keyword == "o" || keyword == "g" ||
                   keyword == "s" || keyword == "l" || keyword == "p" || keyword == "vp") {
            return;  // comments, grouping, smoothing, lines, points: nothing to render
        } else if (std::find(unsupported_.begin(), unsupported_.end(), keyword) ==
                   unsupported_.end()) {
            unsupported_.push_back(keyword);
            c_.deferred.push_back({Deferred::Kind::Unsupported, s.line, keyword});
        }
    }

private:
    // Parses one index of the corner starting at `corner`: 1-based, or negative =
    // relative to the end of the `count` elements defined so far.
    static uint32_t index(LineScanner& s, const char* corner, size_t count, const char* what) {
        int64_t i = 0;
        const auto [next, ec] = parseNumber(s.p, s.end, i);
        if (ec != std::errc()) {
            s.p = corner;
            s.error("cannot parse ", what, " index in face corner '", s.token(), "'");
        }
        s.p = next;
        if (i == 0) s.error(what, " index 0 is invalid (OBJ indices start at 1)");
        const int64_t resolved = i > 0 ? i - 1 : int64_t(count) + i;
        if (resolved < 0 || resolved >= int64_t(count))
            s.error(what, " index ", i, " is out of range (", count, " defined so far)");
        return static_cast<uint32_t>(resolved);
    }

    void face(LineScanner& s) {
        const size_t first = c_.corners.size();
        while (!s.atEnd()) {
            const char* start = s.p;
            Corner c;
            c.v = index(s, start, c_.before.v + c_.parsed.v, "vertex");
            if (s.p < s.end && *s.p == '/') {
                ++s.p;
                if (s.p == s.end || *s.p != '/')
                    c.vt = index(s, start, c_.before.vt + c_.parsed.vt, "texture");
                if (s.p < s.end && *s.p == '/') {
                    ++s.p;
                    c.vn = index(s, start, c_.before.vn + c_.parsed.vn, "normal");
                }
            }
            if (s.p < s.end && !isBlank(*s.p)) {
                s.p = start;
                s.error("malformed face corner '", s.token(), "'");
            }
            (c.vt == kNone ? c_.cornerWithoutUv : c_.cornerWithUv) = true;
            (c.vn == kNone ? c_.cornerWithoutNormal : c_.cornerWithNormal) = true;
            c_.corners.push_back(c);
        }
        const size_t corners = c_.corners.size() - first;
        if (corners < 3) s.error("face with ", corners, " vertices (needs at least 3)");
        if (corners > UINT32_MAX) s.error("face with more than 2^32-1 vertices");
        c_.faceSizes.push_back(static_cast<uint32_t>(corners));
        c_.faceUse.push_back(static_cast<uint32_t>(c_.usemtl.size()));
    }

    Chunk& c_;
    Attributes& a_;
    std::vector<std::string_view> unsupported_;  // keywords already deferred
};

}  // namespace

std::vector<Chunk> splitIntoChunks(std::string_view text, size_t chunkBytes) {
    std::vector<Chunk> chunks;
    const size_t step = std::max<size_t>(chunkBytes, 1);
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.size();
        if (text.size() - start > step) {
            const size_t eol = text.find('\n', start + step - 1);
            if (eol != std::string_view::npos) end = eol + 1;
        }
        chunks.emplace_back().text = text.substr(start, end - start);
        start = end;
    }
    return chunks;
}

void countStatements(Chunk& chunk) {
    const char* p = chunk.text.data();
    const char* const end = p + chunk.text.size();
    while (p < end) {
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        if (eol == nullptr) eol = end;
        const std::string_view keyword = keywordOf(p, eol);
        if (keyword == "v")
            ++chunk.own.v;
        else if (keyword == "vt")
            ++chunk.own.vt;
        else if (keyword == "vn")
            ++chunk.own.vn;
        else if (keyword == "f")
            ++chunk.ownFaces;
        if (eol < end) ++chunk.lines;
        p = eol + 1;
    }
}

void parseChunk(const std::string& file, Chunk& chunk, Attributes& attributes) {
    try {
        chunk.faceSizes.reserve(chunk.ownFaces);
        chunk.faceUse.reserve(chunk.ownFaces);
        chunk.corners.reserve(3 * chunk.ownFaces);  // triangles, the common case
        ChunkParser parser(chunk, attributes);
        forEachLine(file, chunk.text, [&](LineScanner& s) { parser.statement(s); },
                    chunk.firstLine);
    } catch (...) {
        chunk.error = std::current_exception();
    }
}

size_t lineOfFace(const std::string& file, const Chunk& chunk, size_t face) {
    size_t seen = 0, found = chunk.firstLine;
    forEachLine(
        file, chunk.text,
        [&](LineScanner& s) {
            if (keywordOf(s.p, s.end) == "f" && seen++ == face) found = s.line;
        },
        chunk.firstLine);
    return found;
}

}  // namespace strahl::meshio::obj
