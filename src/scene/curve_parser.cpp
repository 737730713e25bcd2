// "curves" shapes of the scene file; see curve_parser.h.

#include "curve_parser.h"

#include <cmath>
#include <limits>

namespace strahl::scene_detail {

namespace {

CurveBasis basisFromName(const std::string& name) {
    for (CurveBasis b : {CurveBasis::Linear, CurveBasis::Bezier, CurveBasis::BSpline, CurveBasis::CatmullRom})
        if (name == curveBasisName(b)) return b;
    return CurveBasis::BSpline;  // oneOf() has checked the name
}

// [x, y, z, r], or [x, y, z] with the shape's "radius".
Vec4 parsePoint(const JsonValue& point, const std::optional<float>& radius) {
    if (!point.raw().is_array() || (point.size() != 3 && point.size() != 4))
        point.fail("expected [x, y, z, radius] or [x, y, z] (with the shape's 'radius'), got ", point.describe());
    if (point.size() == 3 && !radius) point.fail("gives no radius: add one, or the shape's 'radius'");
    Vec4 p(point.at(0).number(), point.at(1).number(), point.at(2).number(), radius.value_or(0.0f));
    if (point.size() == 4) p.w = point.at(3).number();
    if (!(p.w >= 0.0f)) point.fail("radius ", p.w, " must be >= 0");
    return p;
}

}  // namespace

void parseCurvesShape(const JsonValue& v, const std::filesystem::path& folder, ShapeDesc& s) {
    v.requireKeys({"type", "name", "material", "transform", "motion", "basis", "profile", "points", "strands", "radius",
                   "file", "flat_segments", "transform_radius", "normals"});
    s.kind = ShapeKind::Curves;
    s.name = s.where;
    if (auto name = v.find("name")) s.name = name->string();
    CurveSetDesc& c = s.curves;
    c.name = s.name;
    if (auto basis = v.find("basis"))
        c.basis = basisFromName(basis->oneOf({"linear", "bezier", "bspline", "catmull_rom"}));
    if (auto profile = v.find("profile")) {
        const std::string name = profile->oneOf({"round", "flat", "oriented"});
        c.type = name == "round" ? CurveType::Round : name == "flat" ? CurveType::Flat : CurveType::Oriented;
        if (c.type == CurveType::Oriented && c.basis == CurveBasis::Linear)
            profile->fail("an oriented ribbon needs a cubic basis (bezier, bspline or catmull_rom)");
    }
    const auto normals = v.find("normals");
    if (normals && c.type != CurveType::Oriented) normals->fail("only for \"profile\": \"oriented\"");
    if (auto segments = v.find("flat_segments")) {
        if (c.type != CurveType::Flat) segments->fail("only for \"profile\": \"flat\"");
        c.flatSegments = static_cast<int>(segments->integer(1, 64));
    }
    if (auto keep = v.find("transform_radius")) s.curveRadiusFollowsTransform = keep->boolean();
    std::optional<float> radius;
    if (auto r = v.find("radius")) radius = r->numberIn(0.0f, std::numeric_limits<float>::max());

    const auto file = v.find("file");
    const auto points = v.find("points");
    if (file && points) v.fail("'file' and 'points' are exclusive: give one");
    if (file) {
        if (auto extra = v.find("strands")) extra->fail("only with 'points' (a strand file separates its strands)");
        if (c.type == CurveType::Oriented)
            v.get("profile").fail("an oriented ribbon needs inline 'points' and 'normals' (a strand file has no normals)");
        if (radius) v.get("radius").fail("only with 'points' (a strand file gives every point's radius)");
        s.file = resolveExistingFile(folder, *file, "strand file");
        return;
    }
    if (!points) v.fail("needs 'points' (inline control points) or 'file' (a strand file)");
    if (points->size() == 0) points->fail("must contain control points");
    c.points.reserve(points->size());
    for (size_t i = 0; i < points->size(); ++i) c.points.push_back(parsePoint(points->at(i), radius));
    if (c.type == CurveType::Oriented) {
        if (!normals) v.fail("an oriented ribbon needs 'normals', one [x, y, z] per control point");
        if (normals->size() != c.points.size())
            normals->fail("expected one normal per control point (", c.points.size(), "), got ", normals->size());
        for (size_t i = 0; i < normals->size(); ++i) {
            const Vec3 n = normals->at(i).vec3();
            if (!(glm::length(n) > 0.0f)) normals->at(i).fail("a normal must not be zero");
            c.normals.push_back(n);
        }
    }
    std::vector<uint32_t> strands{static_cast<uint32_t>(std::min<size_t>(c.points.size(), UINT32_MAX))};
    if (auto counts = v.find("strands")) {
        strands.clear();
        uint64_t total = 0;
        for (size_t i = 0; i < counts->size(); ++i) {
            strands.push_back(static_cast<uint32_t>(counts->at(i).integer(1, UINT32_MAX)));
            total += strands.back();
        }
        if (total != c.points.size())
            counts->fail("the strands hold ", total, " points, but 'points' has ", c.points.size());
    }
    try {
        c.segments = curveSegmentsOfStrands(strands, c.basis, c.name);
    } catch (const Error& e) {
        (v.find("strands") ? *v.find("strands") : *points).fail(e.what());
    }
}

CurveSetDesc placeCurves(CurveSetDesc curves, const Mat4& transform, bool scaleRadius) {
    const float scale = scaleRadius ? std::cbrt(std::abs(glm::determinant(Mat3(transform)))) : 1.0f;
    for (Vec4& p : curves.points) {
        const Vec3 q = Vec3(transform * Vec4(Vec3(p), 1.0f));
        p = Vec4(q, p.w * scale);
    }
    // An oriented ribbon's normals are normals: the ribbon, across n x C',
    // keeps its place on the transformed surface.
    const Mat3 normalMap = glm::transpose(glm::inverse(Mat3(transform)));
    for (Vec3& n : curves.normals) n = glm::normalize(normalMap * n);
    return curves;
}

}  // namespace strahl::scene_detail
