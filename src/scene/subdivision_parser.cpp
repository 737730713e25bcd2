// "subdivision" shapes of the scene file; see subdivision_parser.h.

#include "subdivision_parser.h"

#include <cmath>
#include <limits>
#include <map>

#include <glm/glm.hpp>

#include "height_image.h"
#include "strahl/meshio/polygon_file.h"

namespace strahl::scene_detail {

namespace {

// A crease or corner sharpness: a number ≥ 0, or "inf" (infinitely sharp).
float parseSharpness(const JsonValue& v) {
    if (v.raw().is_string()) {
        v.oneOf({"inf"});
        return std::numeric_limits<float>::infinity();
    }
    return v.numberIn(0.0f, std::numeric_limits<float>::max());
}

DisplacementDesc parseDisplacement(const JsonValue& v, const std::filesystem::path& folder) {
    v.requireKeys({"formula", "parameters", "image", "scale", "offset"});
    DisplacementDesc d;
    const auto formula = v.find("formula");
    const auto image = v.find("image");
    if (formula && image) v.fail("give 'formula' or 'image', not both");
    if (!formula && !image) v.fail("needs 'formula' (of x, y, z, u, v) or 'image' (a height image)");
    if (auto s = v.find("scale")) d.scale = s->number();
    if (auto o = v.find("offset")) d.offset = o->number();
    if (formula) {
        std::map<std::string, double> parameters;
        if (auto p = v.find("parameters")) {
            if (!p->raw().is_object()) p->fail("expected an object of name: number, got ", p->describe());
            for (const auto& item : p->raw().items()) parameters[item.key()] = p->get(item.key()).number();
        }
        static const std::string variables[] = {"x", "y", "z", "u", "v"};
        try {
            d.formula = std::make_shared<const Formula>(Formula::compile(formula->string(), variables, parameters));
        } catch (const Error& e) {
            formula->fail(e.what());
        }
        d.text = concat("'", formula->string(), "'");
    } else {
        if (v.has("parameters")) v.get("parameters").fail("only with 'formula'");
        d.image = resolveExistingFile(folder, *image, "displacement image");
        d.text = concat("image ", d.image.filename().string());
    }
    if (d.scale != 1.0) d.text += concat(" x ", d.scale);
    if (d.offset != 0.0) d.text += concat(" + ", d.offset);
    return d;
}

// Bilinear lookup with repeat wrapping; v = 0 is the image's bottom row
// (row 0 of a HeightImage is its top).
double sampleImage(const HeightImage& image, double u, double v) {
    const auto value = [&](int x, int y) {
        x = ((x % image.columns) + image.columns) % image.columns;
        y = ((y % image.rows) + image.rows) % image.rows;
        return double(image.heights[size_t(image.rows - 1 - y) * size_t(image.columns) + size_t(x)]);
    };
    const double x = u * image.columns - 0.5, y = v * image.rows - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const int x0 = int(fx), y0 = int(fy);
    const double tx = x - fx, ty = y - fy;
    return (1 - tx) * (1 - ty) * value(x0, y0) + tx * (1 - ty) * value(x0 + 1, y0) + (1 - tx) * ty * value(x0, y0 + 1) +
           tx * ty * value(x0 + 1, y0 + 1);
}

}  // namespace

void parseSubdivisionShape(const JsonValue& v, const std::filesystem::path& folder, ShapeDesc& s) {
    v.requireKeys({"type", "name", "material", "transform", "motion", "positions", "faces", "uvs", "file", "levels",
                   "max_edge_pixels", "creases", "corners", "holes", "boundary", "displacement"});
    s.kind = ShapeKind::Subdivision;
    s.name = s.where;
    if (auto name = v.find("name")) s.name = name->string();
    SubdivisionShapeDesc& d = s.subdivision;
    SubdivisionCage& cage = d.cage;
    const auto file = v.find("file");
    const auto positions = v.find("positions");
    if (file && positions) v.fail("'file' and 'positions' are exclusive: give one");
    if (file) {
        for (std::string_view key : {"faces", "uvs"})
            if (auto extra = v.find(key)) extra->fail("only with 'positions' (an inline cage), not with 'file'");
        d.file = resolveExistingFile(folder, *file, "cage file");
        if (d.file.extension() != ".obj" && d.file.extension() != ".OBJ")
            file->fail("a cage file must be an OBJ file (.obj), got '", d.file.filename().string(), "'");
    } else if (positions) {
        if (positions->size() == 0) positions->fail("must contain positions");
        for (size_t i = 0; i < positions->size(); ++i) cage.positions.emplace_back(positions->at(i).vec3());
        const JsonValue faces = v.get("faces");
        if (faces.size() == 0) faces.fail("must contain faces");
        for (size_t f = 0; f < faces.size(); ++f) {
            const JsonValue face = faces.at(f);
            if (!face.raw().is_array() || face.size() < 3 || face.size() > size_t(kMaxFaceSize))
                face.fail("expected an array of 3 to ", kMaxFaceSize, " vertex indices, got ",
                          face.raw().is_array() ? concat(face.size(), " indices") : face.describe());
            for (size_t k = 0; k < face.size(); ++k)
                cage.indices.push_back(uint32_t(face.at(k).integer(0, int64_t(cage.positions.size()) - 1)));
            cage.faceSizes.push_back(uint32_t(face.size()));
        }
        if (auto uvs = v.find("uvs")) {
            if (uvs->size() != cage.positions.size())
                uvs->fail("expected one [u, v] per position (", cage.positions.size(), "), got ", uvs->size());
            for (size_t i = 0; i < uvs->size(); ++i) cage.uvs.emplace_back(uvs->at(i).vec2());
        }
    } else {
        v.fail("needs 'positions' and 'faces' (an inline cage) or 'file' (an OBJ cage)");
    }
    if (auto levels = v.find("levels")) d.levels = int(levels->integer(1, kMaxSubdivisionLevels));
    if (auto pixels = v.find("max_edge_pixels")) {
        if (v.has("levels")) v.fail("give 'levels' or 'max_edge_pixels', not both");
        d.maxEdgePixels = pixels->numberIn(1e-3f, 1e6f);
    }
    if (auto creases = v.find("creases")) {
        for (size_t k = 0; k < creases->size(); ++k) {
            const JsonValue c = creases->at(k);
            if (!c.raw().is_array() || c.size() != 3) c.fail("expected [vertex, vertex, sharpness], got ", c.describe());
            cage.creaseEdges.push_back(uint32_t(c.at(0).integer(0, UINT32_MAX)));
            cage.creaseEdges.push_back(uint32_t(c.at(1).integer(0, UINT32_MAX)));
            cage.creaseWeights.push_back(parseSharpness(c.at(2)));
        }
    }
    if (auto corners = v.find("corners")) {
        for (size_t k = 0; k < corners->size(); ++k) {
            const JsonValue c = corners->at(k);
            if (!c.raw().is_array() || c.size() != 2) c.fail("expected [vertex, sharpness], got ", c.describe());
            cage.cornerVertices.push_back(uint32_t(c.at(0).integer(0, UINT32_MAX)));
            cage.cornerWeights.push_back(parseSharpness(c.at(1)));
        }
    }
    if (auto holes = v.find("holes")) {
        for (size_t k = 0; k < holes->size(); ++k) cage.holes.push_back(uint32_t(holes->at(k).integer(0, UINT32_MAX)));
    }
    if (auto boundary = v.find("boundary"))
        cage.boundary = subdivisionBoundaryFromName(boundary->oneOf({"smooth", "pin_corners", "pin_boundary", "pin_all"}));
    if (auto displacement = v.find("displacement")) d.displacement = parseDisplacement(*displacement, folder);
    // An inline cage is checked now, so its errors name their place.
    if (positions) {
        try {
            (void)refineCatmullClark(cage, 1, s.name == s.where ? std::string("the cage") : s.name);
        } catch (const Error& e) {
            v.fail(e.what());
        }
        if (d.displacement && d.displacement->formula == nullptr && cage.uvs.empty())
            v.get("displacement").fail("a displacement image needs the cage's 'uvs'");
    }
}

int levelsForEdgeLength(const SubdivisionCage& cage, const std::function<double(const DVec3&)>& maxEdgeLength,
                        size_t memoryLimitBytes, bool& capped) {
    int levels = 1;
    size_t first = 0;
    for (uint32_t n : cage.faceSizes) {
        for (uint32_t i = 0; i < n; ++i) {
            const DVec3& a = cage.positions[cage.indices[first + i]];
            const DVec3& b = cage.positions[cage.indices[first + (i + 1) % n]];
            const double allowed = std::min(maxEdgeLength(a), maxEdgeLength(b));
            const double length = glm::length(b - a);
            while (levels < kMaxSubdivisionLevels && length > allowed * double(1 << levels)) ++levels;
        }
        first += n;
    }
    capped = false;
    if (memoryLimitBytes == 0) return levels;
    // Refined quads: 4^levels per quad face, n · 4^(levels − 1) per n-gon.
    size_t quadsAtOne = 0;  // after one level
    for (uint32_t n : cage.faceSizes) quadsAtOne += n;
    while (levels > 1 && quadsAtOne * (size_t(1) << (2 * (levels - 1))) * kBytesPerRefinedQuad > memoryLimitBytes) {
        --levels;
        capped = true;
    }
    return levels;
}

std::shared_ptr<const SubdivisionSurface> makeSubdivisionSurface(const ShapeDesc& shape, const std::string& source,
                                                                 const SubdivisionBudget& budget) {
    const SubdivisionShapeDesc& d = shape.subdivision;
    SubdivisionDesc desc;
    desc.name = source;
    desc.cage = d.cage;
    desc.levels = d.levels;
    if (!d.file.empty()) {
        PolygonFile obj;
        try {
            obj = loadObjPolygons(d.file, uint32_t(kMaxFaceSize));
        } catch (const Error& e) {
            fail(source, ": ", e.what());  // the file's own errors name it and the line
        }
        desc.cage.positions = std::move(obj.positions);
        desc.cage.uvs = std::move(obj.uvs);
        desc.cage.faceSizes = std::move(obj.faceSizes);
        desc.cage.indices = std::move(obj.indices);
    }
    // Catmull-Clark commutes with affine maps: refining the moved cage is
    // moving the refined surface.
    const glm::dmat4 toWorld(shape.transform);
    for (DVec3& p : desc.cage.positions) p = DVec3(toWorld * glm::dvec4(p, 1.0));
    if (d.maxEdgePixels > 0.0 && budget.maxEdgeLength) {
        bool capped = false;
        desc.levels = levelsForEdgeLength(desc.cage, budget.maxEdgeLength, budget.memoryLimitBytes, capped);
        desc.levelsText = concat("from max_edge_pixels ", d.maxEdgePixels, capped ? ", capped by the memory limit" : "");
    }
    if (d.displacement) {
        const DisplacementDesc& disp = *d.displacement;
        if (!disp.formula && desc.cage.uvs.empty())
            fail(source, ": a displacement image needs uvs on the cage (the OBJ file's vt, without seams)");
        // Heights are in object units: scaled to world units by the
        // transform's mean scale; the formula sees object-space x, y, z.
        const double meanScale = std::cbrt(std::abs(glm::determinant(glm::dmat3(toWorld))));
        const glm::dmat4 toObject = glm::inverse(toWorld);
        desc.displacementText = disp.text;
        if (disp.formula) {
            const std::shared_ptr<const Formula> formula = disp.formula;
            const double scale = disp.scale, offset = disp.offset;
            desc.displacement = [formula, toObject, meanScale, scale, offset](const DVec3& p, const DVec3&,
                                                                               const DVec2& uv) {
                const DVec3 q(toObject * glm::dvec4(p, 1.0));
                const double vars[5] = {q.x, q.y, q.z, uv.x, uv.y};
                return meanScale * (scale * formula->evaluate<double>(vars) + offset);
            };
        } else {
            // Read as a height field's image is (height_image.h): one
            // channel, or the luminance of three.
            auto image = std::make_shared<const HeightImage>(loadHeightImage(disp.image));
            const double scale = disp.scale, offset = disp.offset;
            desc.displacement = [image, meanScale, scale, offset](const DVec3&, const DVec3&, const DVec2& uv) {
                return meanScale * (scale * sampleImage(*image, uv.x, uv.y) + offset);
            };
        }
    }
    return std::make_shared<const SubdivisionSurface>(std::move(desc));
}

}  // namespace strahl::scene_detail
