#include "parametric_parser.h"

#include <cmath>
#include <map>
#include <memory>
#include <string_view>
#include <string>
#include <vector>

#include "json_surface_parameters.h"
#include "strahl/geometry/bilinear_patches.h"
#include "strahl/geometry/formula.h"
#include "strahl/geometry/parametric_kinds.h"
#include "strahl/geometry/parametric_formula.h"
#include "strahl/geometry/revolution_surface.h"

namespace strahl::scene_detail {

namespace {

// Per patch and direction. 4096² triangles is already 33 million.
constexpr int64_t kMaxSegments = 4096;
constexpr int64_t kMaxSubPatches = 256;

// A number read in double precision (scene numbers are otherwise floats), or
// a constant formula such as "2*pi" — so a periodic domain can end exactly at
// 2π, which no decimal literal read as float does.
double exactNumber(const JsonValue& v, const std::map<std::string, double>& parameters) {
    double x = 0.0;
    if (v.raw().is_string()) {
        try {
            x = Formula::compile(v.string(), {}, parameters).evaluate<double>(nullptr);
        } catch (const Error& e) {
            v.fail(e.what());
        }
    } else if (v.raw().is_number()) {
        x = v.raw().get<double>();
    } else {
        v.fail("expected a number or a constant formula such as \"2*pi\", got ", v.describe());
    }
    if (!std::isfinite(x)) v.fail("must be finite, got ", x);
    return x;
}

// The built-in kinds' number reader (json_surface_parameters.h): exactNumber.
double readExactNumber(const JsonValue& v, std::string_view key, double fallback) {
    const auto found = v.find(key);
    return found ? exactNumber(*found, {}) : fallback;
}

std::map<std::string, double> parseParameters(const JsonValue& v) {
    std::map<std::string, double> parameters;
    if (auto p = v.find("parameters")) {
        if (!p->raw().is_object()) p->fail("expected an object of name: number, got ", p->describe());
        for (const auto& item : p->raw().items())
            parameters[item.key()] = exactNumber(p->get(item.key()), {});
    }
    return parameters;
}

void parseRange(const JsonValue& v, const std::map<std::string, double>& parameters, double& lo,
                double& hi) {
    if (v.size() != 2) v.fail("expected [min, max]");
    lo = exactNumber(v.at(0), parameters);
    hi = exactNumber(v.at(1), parameters);
    if (!(lo < hi)) v.fail("the domain is empty or inverted: [", lo, ", ", hi, "]");
}


// The "type" names: the built-in kinds', then the surfaces built here.
const std::vector<std::string_view>& parametricSurfaceTypes() {
    static const std::vector<std::string_view> types =
        kindNamesThen(parametricKinds(), {"revolution", "bezier", "bilinear", "heightfield", "formula"});
    return types;
}

ParametricSurfacePtr parseFormula(const JsonValue& v) {
    v.requireKeys({"type", "x", "y", "z", "u", "v", "periodic_u", "periodic_v", "twisted_u",
                   "parameters"});
    const std::map<std::string, double> parameters = parseParameters(v);
    ParamDomain domain;
    parseRange(v.get("u"), parameters, domain.u0, domain.u1);
    parseRange(v.get("v"), parameters, domain.v0, domain.v1);
    if (auto p = v.find("periodic_u")) domain.periodicU = p->boolean();
    if (auto p = v.find("periodic_v")) domain.periodicV = p->boolean();
    if (auto p = v.find("twisted_u")) {
        domain.twistedU = p->boolean();
        if (domain.twistedU && !domain.periodicU) p->fail("a twisted seam needs \"periodic_u\": true");
    }
    const ParametricFormulaText text{v.get("x").string(), v.get("y").string(), v.get("z").string()};
    return buildAt(v, [&] { return makeParametricFormula(text, domain, parameters); });
}

// The shape's "surface": built now, or for a file kind named for the builder.
void parseSurface(const JsonValue& v, const std::filesystem::path& folder, ParametricDesc& p) {
    if (!v.raw().is_object()) v.fail("expected a surface object, got ", v.describe());
    const std::string type = v.get("type").oneOf(parametricSurfaceTypes());
    if (const ParametricKind* kind = findParametricKind(type)) {
        p.surface = kind->parse(JsonSurfaceParameters(v, type, &readExactNumber));
        return;
    }
    if (type == "revolution") {
        v.requireKeys({"type", "profile"});
        const JsonValue list = v.get("profile");
        std::vector<glm::dvec2> profile;
        for (size_t i = 0; i < list.size(); ++i) profile.push_back(glm::dvec2(list.at(i).vec2()));
        p.surface = buildAt(v, [&] { return makeSurfaceOfRevolution(std::move(profile)); });
        return;
    }
    if (type == "bezier") {
        v.requireKeys({"type", "file", "reverse"});
        const JsonValue file = v.get("file");
        ParametricFile f;
        f.kind = ParametricFile::Kind::BezierPatches;
        f.file = resolvePath(folder, file);
        f.at = file.place();
        const auto reverse = v.find("reverse");
        f.reverse = reverse && reverse->boolean();
        p.file = std::move(f);
        return;
    }
    if (type == "bilinear") {
        // {"positions": [[x, y, z], ...], "patches": [a, b, c, d, ...]}: four
        // corners per patch, in order around it (bilinear_patches.h).
        v.requireKeys({"type", "positions", "patches"});
        const JsonValue list = v.get("positions");
        std::vector<DVec3> positions;
        positions.reserve(list.size());
        for (size_t i = 0; i < list.size(); ++i) {
            const JsonValue point = list.at(i);
            if (!point.raw().is_array() || point.size() != 3) point.fail("expected [x, y, z]");
            positions.emplace_back(exactNumber(point.at(0), {}), exactNumber(point.at(1), {}),
                                   exactNumber(point.at(2), {}));
        }
        const JsonValue patches = v.get("patches");
        if (patches.size() == 0 || patches.size() % 4 != 0)
            patches.fail("expected four corner indices per patch, got ", patches.size(), " indices");
        std::vector<uint32_t> corners;
        corners.reserve(patches.size());
        for (size_t i = 0; i < patches.size(); ++i) {
            const JsonValue index = patches.at(i);
            const uint64_t value = index.unsignedInteger(UINT32_MAX);
            if (value >= positions.size())
                index.fail("index ", value, " is beyond the ", positions.size(), " positions");
            corners.push_back(static_cast<uint32_t>(value));
        }
        p.surface = buildAt(v, [&] { return makeBilinearPatchSet(positions, corners, ""); });
        return;
    }
    if (type == "heightfield") {
        v.requireKeys({"type", "image", "size", "height"});
        const JsonValue image = v.get("image");
        ParametricFile f;
        f.kind = ParametricFile::Kind::HeightImage;
        f.file = resolvePath(folder, image);
        f.at = image.place();
        if (auto s = v.find("size")) f.size = s->vec2();
        f.height = readExactNumber(v, "height", 1.0);
        p.file = std::move(f);
        return;
    }
    p.surface = parseFormula(v);
}

// "segments": n, or [nu, nv].
void parseSegments(const JsonValue& v, int& u, int& w) {
    if (v.raw().is_array()) {
        if (v.size() != 2) v.fail("expected a count or [count along u, count along v]");
        u = static_cast<int>(v.at(0).integer(1, kMaxSegments));
        w = static_cast<int>(v.at(1).integer(1, kMaxSegments));
    } else {
        u = w = static_cast<int>(v.integer(1, kMaxSegments));
    }
}

double positive(const JsonValue& v) {
    const double x = exactNumber(v, {});
    if (!(x > 0.0)) v.fail("must be a positive number, got ", x);
    return x;
}

}  // namespace

ParametricDesc parseParametricShape(const JsonValue& shape, const std::filesystem::path& folder) {
    ParametricDesc p;
    parseSurface(shape.get("surface"), folder, p);
    if (auto mode = shape.find("mode"))
        p.mode = mode->oneOf({"tessellated", "direct"}) == "direct" ? ParametricMode::Direct
                                                                     : ParametricMode::Tessellated;
    const auto tessellation = shape.find("tessellation");
    const auto direct = shape.find("direct");
    if (p.mode == ParametricMode::Direct && tessellation)
        tessellation->fail("only for \"mode\": \"tessellated\"");
    if (p.mode == ParametricMode::Tessellated && direct) direct->fail("only for \"mode\": \"direct\"");
    if (tessellation) {
        const JsonValue& t = *tessellation;
        t.requireKeys({"segments", "max_error", "max_edge_pixels", "normals"});
        if (auto s = t.find("segments")) parseSegments(*s, p.segmentsU, p.segmentsV);
        if (auto e = t.find("max_error")) p.maxError = positive(*e);
        if (auto e = t.find("max_edge_pixels")) p.maxEdgePixels = positive(*e);
        if (auto n = t.find("normals"))
            p.normals = n->oneOf({"exact", "interpolated"}) == "exact" ? ParametricNormals::Exact
                                                                       : ParametricNormals::Interpolated;
    }
    if (direct) {
        const JsonValue& d = *direct;
        d.requireKeys({"sub_patches", "tolerance"});
        if (auto s = d.find("sub_patches")) {
            // A fixed grid of sub-patches instead of the automatic flatness bound.
            p.direct.initialSegments = static_cast<int>(s->integer(1, kMaxSubPatches));
            p.direct.flatness = 0.0;
        }
        if (auto tol = d.find("tolerance")) {
            p.direct.relativeTolerance = exactNumber(*tol, {});
            if (!(p.direct.relativeTolerance >= 1e-14 && p.direct.relativeTolerance <= 1e-3))
                tol->fail("must lie in [1e-14, 1e-3], got ", p.direct.relativeTolerance);
        }
    }
    return p;
}

}  // namespace strahl::scene_detail
