// OBJ polygons (polygon_file.h): a line-by-line reader; cages are small
// (thousands of faces), so clarity wins over the chunked parallel OBJ loader.

#include "strahl/meshio/polygon_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "strahl/core/error.h"

namespace strahl {

namespace {

struct LineReader {
    const std::filesystem::path& file;
    size_t line = 0;

    template <class... Args>
    [[noreturn]] void fail(const Args&... args) const {
        strahl::fail(file.string(), ":", line, ": ", args...);
    }
};

std::string_view nextToken(std::string_view& rest) {
    const size_t start = rest.find_first_not_of(" \t\r");
    if (start == std::string_view::npos) {
        rest = {};
        return {};
    }
    const size_t end = rest.find_first_of(" \t\r", start);
    const std::string_view token = rest.substr(start, end == std::string_view::npos ? rest.npos : end - start);
    rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end);
    return token;
}

double parseNumber(std::string_view token, const LineReader& reader) {
    double x = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), x);
    if (token.empty() || error != std::errc() || end != token.data() + token.size() || !std::isfinite(x))
        reader.fail("expected a finite number, got '", token, "'");
    return x;
}

// A 1-based (or negative, relative) OBJ index to a 0-based one.
uint32_t parseIndex(std::string_view token, size_t count, const char* what, const LineReader& reader) {
    long long i = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), i);
    if (token.empty() || error != std::errc() || end != token.data() + token.size())
        reader.fail("expected a ", what, " index, got '", token, "'");
    const long long resolved = i < 0 ? static_cast<long long>(count) + i : i - 1;
    if (i == 0 || resolved < 0 || resolved >= static_cast<long long>(count))
        reader.fail(what, " index ", i, " is out of range (", count, " so far)");
    return static_cast<uint32_t>(resolved);
}

}  // namespace

PolygonFile loadObjPolygons(const std::filesystem::path& file, uint32_t maxFaceSize) {
    std::ifstream in(file);
    if (!in) fail(file.string(), ": cannot open the file");
    PolygonFile out;
    std::vector<glm::dvec2> texcoords;
    std::vector<int64_t> uvOfPosition;  // -1: none yet
    bool uvsUsable = true;
    LineReader reader{file};
    std::string text;
    while (std::getline(in, text)) {
        ++reader.line;
        std::string_view rest(text);
        const std::string_view keyword = nextToken(rest);
        if (keyword == "v") {
            DVec3 p;
            for (int k = 0; k < 3; ++k) p[k] = parseNumber(nextToken(rest), reader);
            out.positions.push_back(p);
            uvOfPosition.push_back(-1);
        } else if (keyword == "vt") {
            glm::dvec2 t;
            for (int k = 0; k < 2; ++k) t[k] = parseNumber(nextToken(rest), reader);
            texcoords.push_back(t);
        } else if (keyword == "f") {
            uint32_t size = 0;
            for (std::string_view corner = nextToken(rest); !corner.empty(); corner = nextToken(rest)) {
                const size_t slash = corner.find('/');
                const uint32_t v = parseIndex(corner.substr(0, slash), out.positions.size(), "vertex", reader);
                out.indices.push_back(v);
                ++size;
                const std::string_view after = slash == std::string_view::npos ? std::string_view{} : corner.substr(slash + 1);
                const std::string_view t = after.substr(0, after.find('/'));
                if (t.empty()) {
                    uvsUsable = false;
                    continue;
                }
                const uint32_t ti = parseIndex(t, texcoords.size(), "texture coordinate", reader);
                if (uvOfPosition[v] >= 0 && texcoords[size_t(uvOfPosition[v])] != texcoords[ti]) uvsUsable = false;
                uvOfPosition[v] = ti;
            }
            if (size < 3 || size > maxFaceSize)
                reader.fail("a face of ", size, " vertices (3 to ", maxFaceSize, ")");
            out.faceSizes.push_back(size);
        }
    }
    if (out.faceSizes.empty()) fail(file.string(), ": no faces");
    if (uvsUsable && !texcoords.empty()) {
        out.uvs.resize(out.positions.size(), glm::dvec2(0.0));
        for (size_t v = 0; v < out.positions.size(); ++v)
            if (uvOfPosition[v] >= 0) out.uvs[v] = texcoords[size_t(uvOfPosition[v])];
    }
    return out;
}

}  // namespace strahl
