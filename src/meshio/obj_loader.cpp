// Wavefront OBJ loader with its .mtl material libraries. The file is read into
// memory at once and scanned line by line with std::from_chars; what is and is
// not supported is listed in docs/mesh-formats.md, the .mtl keys read in
// docs/mesh-files.md.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <unordered_map>
#include <utility>

#include "strahl/meshio/mesh_file.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace {

using meshio::LineScanner;

constexpr uint32_t kNone = UINT32_MAX;

// Calls fn(scanner) for every line of `text` (line numbers start at 1).
template <typename Fn>
void forEachLine(const std::string& file, std::string_view text, Fn&& fn) {
    const char* p = text.data();
    const char* const end = p + text.size();
    for (size_t line = 1; p < end; ++line) {
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        if (eol == nullptr) eol = end;
        LineScanner scanner{file, line, p, eol};
        fn(scanner);
        p = eol + (eol < end ? 1 : 0);
    }
}

// ---------------------------------------------------------------------------
// .mtl material libraries

using MaterialLibrary = std::unordered_map<std::string, MeshMaterial>;

// Kd / Ks / Ke / Tf: one value (grey) or three.
Color readColor(LineScanner& s, const char* what) {
    const float r = s.finiteFloat(what);
    if (s.atEnd()) return Color(r);
    const float g = s.finiteFloat(what);
    const float b = s.finiteFloat(what);
    s.expectEnd(what);
    return Color(r, g, b);
}

// Ns / Ni / d / Tr: exactly one number.
float readScalar(LineScanner& s, const char* what) {
    const float value = s.finiteFloat(what);
    s.expectEnd(what);
    return value;
}

bool isNumber(std::string_view token) {
    double value = 0.0;
    const auto [next, ec] = meshio::parseNumber(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && next == token.data() + token.size();
}

// Skips the options in front of a texture file name ("-bm 0.5", "-o 1 1 0",
// "-clamp on", ...): each takes one argument, then as many further numeric
// arguments as it allows. Returns the rest of the line.
std::string_view skipTextureOptions(LineScanner& s) {
    static constexpr std::pair<std::string_view, int> kOptions[] = {
        {"-blendu", 1}, {"-blendv", 1},  {"-bm", 1},  {"-boost", 1}, {"-cc", 1},
        {"-clamp", 1},  {"-imfchan", 1}, {"-mm", 2},  {"-o", 3},     {"-s", 3},
        {"-t", 3},      {"-texres", 1},  {"-type", 1}};
    for (;;) {
        const char* start = s.p;
        const std::string_view option = s.token();
        int maxArgs = 0;
        for (const auto& [name, count] : kOptions) {
            if (option == name) maxArgs = count;
        }
        if (maxArgs == 0) {
            s.p = start;
            return s.rest();
        }
        s.token();
        for (int i = 1; i < maxArgs; ++i) {
            const char* argStart = s.p;
            if (!isNumber(s.token())) {
                s.p = argStart;
                break;
            }
        }
    }
}

// Resolves a texture name next to the .mtl: the whole rest of the line first
// (names may hold spaces), then its last token (options this reader does not
// know end up in front of the name).
fs::path resolveTexture(const fs::path& dir, std::string_view rest) {
    fs::path found = findFileCaseInsensitive(dir, std::string(rest));
    const size_t lastBlank = rest.find_last_of(" \t");
    if (found.empty() && lastBlank != std::string_view::npos)
        found = findFileCaseInsensitive(dir, std::string(rest.substr(lastBlank + 1)));
    return found;
}

// The .mtl texture statements strahl reads, and the MeshMaterial field each fills.
// map_Bump / bump are not here on purpose: in most OBJ files (Sponza, Sibenik)
// they name grey height maps, which are no tangent-space normal maps.
struct TextureKey {
    std::string_view keyword;
    fs::path MeshMaterial::*field;
    const char* what;  // for the warning: "gets no <what> texture"
};
constexpr TextureKey kTextureKeys[] = {
    {"map_Kd", &MeshMaterial::diffuseTexture, "diffuse"},
    {"map_Ke", &MeshMaterial::emissionTexture, "emission"},
    {"norm", &MeshMaterial::normalTexture, "normal"},
};

class MaterialLibraryReader {
public:
    MaterialLibraryReader(const fs::path& mtlFile, MaterialLibrary& library)
        : name_(mtlFile.string()), dir_(mtlFile.parent_path()), library_(library) {}

    void read(std::string_view text) {
        forEachLine(name_, text, [this](LineScanner& s) { statement(s); });
    }

private:
    void statement(LineScanner& s) {
        const std::string_view keyword = s.token();
        if (keyword == "newmtl") {
            const std::string_view materialName = s.rest();
            if (materialName.empty()) s.error("newmtl without a material name");
            auto [it, inserted] = library_.try_emplace(std::string(materialName));
            current_ = inserted ? &it->second : &duplicate_;
            *current_ = MeshMaterial{};
            current_->name = materialName;
            sawDissolve_ = false;
            return;
        }
        if (current_ == nullptr) return;  // statements before the first newmtl describe nothing
        MeshMaterial& m = *current_;
        if (keyword == "Kd") {
            m.diffuse = readColor(s, "Kd");
        } else if (keyword == "Ks") {
            m.specular = readColor(s, "Ks");
        } else if (keyword == "Ke") {
            m.emission = readColor(s, "Ke");
        } else if (keyword == "Tf") {
            m.transmission = readColor(s, "Tf");
        } else if (keyword == "Ns") {
            m.shininess = readScalar(s, "Ns");
            if (m.shininess < 0.0f) {
                warnValue(s, "Ns", m.shininess, "is negative; using 0");
                m.shininess = 0.0f;
            }
        } else if (keyword == "Ni") {
            const float ior = readScalar(s, "Ni");
            // Some exporters write "Ni 0" for "not set"; an IOR must be positive.
            if (ior > 0.0f)
                m.ior = ior;
            else
                warnValue(s, "Ni", ior, "is not positive; using 1.5");
        } else if (keyword == "d") {
            // "d -halo f" (dissolve depending on the view angle): read as plain d.
            const char* start = s.p;
            if (s.token() != "-halo") s.p = start;
            m.dissolve = unitInterval(s, "d", readScalar(s, "d"));
            sawDissolve_ = true;
        } else if (keyword == "Tr") {
            // Tr is the transparency 1 - d; when a material has both, d wins
            // whatever their order (exporters write both, consistently).
            const float tr = unitInterval(s, "Tr", readScalar(s, "Tr"));
            if (!sawDissolve_) m.dissolve = 1.0f - tr;
        } else if (keyword == "illum") {
            const double model = s.number("illum");
            s.expectEnd("illum");
            // The MTL specification defines illumination models 0 to 10.
            if (model >= 0.0 && model <= 10.0 && model == std::floor(model))
                m.illum = static_cast<int>(model);
            else
                warnValue(s, "illum", model, "is not a model 0..10; using 2");
        } else {
            for (const TextureKey& key : kTextureKeys) {
                if (keyword == key.keyword) texture(s, key);
            }
        }
    }

    void texture(LineScanner& s, const TextureKey& key) {
        const std::string_view textureName = skipTextureOptions(s);
        if (textureName.empty()) s.error(key.keyword, " without a file name");
        fs::path& field = current_->*key.field;
        field = resolveTexture(dir_, textureName);
        if (field.empty())
            meshio::warn(concat(name_, ':', s.line, ": texture '", textureName,
                                "' not found; material '", current_->name, "' gets no ", key.what,
                                " texture"));
    }

    // d and Tr outside [0, 1] are clamped with a warning.
    float unitInterval(LineScanner& s, const char* what, float value) {
        if (value >= 0.0f && value <= 1.0f) return value;
        const float clamped = std::clamp(value, 0.0f, 1.0f);
        warnValue(s, what, value, concat("is outside [0, 1]; using ", clamped));
        return clamped;
    }

    void warnValue(const LineScanner& s, const char* what, double value,
                   const std::string& problem) const {
        meshio::warn(concat(name_, ':', s.line, ": ", what, ' ', value, ' ', problem,
                            " (material '", current_->name, "')"));
    }

    std::string name_;
    fs::path dir_;
    MaterialLibrary& library_;
    MeshMaterial duplicate_;  // absorbs a repeated newmtl: the first definition wins
    MeshMaterial* current_ = nullptr;
    bool sawDissolve_ = false;  // the current material has a d statement
};

void readMaterialLibrary(const fs::path& mtlFile, MaterialLibrary& library) {
    MaterialLibraryReader(mtlFile, library).read(meshio::readWholeFile(mtlFile));
}

// ---------------------------------------------------------------------------
// OBJ

// One face corner: indices into the v, vt and vn arrays (kNone when absent).
struct Corner {
    uint32_t v = kNone;
    uint32_t vt = kNone;
    uint32_t vn = kNone;
};

// The distinct corners, each of which becomes one output vertex. Corners are
// chained per position index: few corners share a position, so a lookup walks
// a short list and needs no hashing.
struct CornerTable {
    std::vector<Corner> corners;
    std::vector<uint32_t> next;  // next corner with the same position
    std::vector<uint32_t> head;  // first corner of each position

    uint32_t insert(const Corner& c) {
        if (c.v >= head.size()) head.resize(size_t(c.v) + 1, kNone);
        for (uint32_t e = head[c.v]; e != kNone; e = next[e]) {
            if (corners[e].vt == c.vt && corners[e].vn == c.vn) return e;
        }
        const auto e = static_cast<uint32_t>(corners.size());
        corners.push_back(c);
        next.push_back(head[c.v]);
        head[c.v] = e;
        return e;
    }
};

class ObjReader {
public:
    explicit ObjReader(const fs::path& file) : path_(file), name_(file.string()) {}

    LoadedMesh read(std::string_view text) {
        forEachLine(name_, text, [this](LineScanner& s) { statement(s); });
        return finish();
    }

private:
    struct Slot {
        std::string name;  // empty: faces before any usemtl
        size_t line = 0;   // first usemtl naming it, for warnings
    };

    void statement(LineScanner& s) {
        const std::string_view keyword = s.token();
        if (keyword == "v") {
            Vec3 p(0.0f);
            p.x = s.finiteFloat("coordinate");
            p.y = s.finiteFloat("coordinate");
            p.z = s.finiteFloat("coordinate");
            while (!s.atEnd()) s.number("vertex value");  // w or a vertex colour: unused
            positions_.push_back(p);
        } else if (keyword == "vt") {
            Vec2 uv(0.0f);  // a missing v is 0
            uv.x = s.finiteFloat("texture coordinate");
            if (!s.atEnd()) uv.y = s.finiteFloat("texture coordinate");
            if (!s.atEnd()) s.number("texture coordinate");  // w: unused
            s.expectEnd("vt");
            texcoords_.push_back(uv);
        } else if (keyword == "vn") {
            Vec3 n(0.0f);
            n.x = s.finiteFloat("normal coordinate");
            n.y = s.finiteFloat("normal coordinate");
            n.z = s.finiteFloat("normal coordinate");
            s.expectEnd("vn");
            normals_.push_back(n);
        } else if (keyword == "f") {
            face(s);
        } else if (keyword == "usemtl") {
            const std::string_view material = s.rest();
            if (material.empty()) s.error("usemtl without a material name");
            currentName_ = material;
            currentLine_ = s.line;
            currentSlot_ = kNone;
        } else if (keyword == "mtllib") {
            materialLibraries(s);
        } else if (keyword.empty() || keyword[0] == '#' || keyword == "o" || keyword == "g" ||
                   keyword == "s" || keyword == "l" || keyword == "p" || keyword == "vp") {
            return;  // comments, grouping, smoothing, lines, points: nothing to render
        } else if (ignoredKeywords_.insert(std::string(keyword)).second) {
            meshio::warn(concat(name_, ':', s.line, ": ignoring unsupported statement '", keyword,
                                "' (reported once)"));
        }
    }

    // Parses one index of the corner starting at `corner`: 1-based, or negative =
    // relative to the end.
    uint32_t index(LineScanner& s, const char* corner, size_t count, const char* what) {
        int64_t i = 0;
        const auto [next, ec] = meshio::parseNumber(s.p, s.end, i);
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
        polygon_.clear();
        while (!s.atEnd()) {
            const char* start = s.p;
            Corner c;
            c.v = index(s, start, positions_.size(), "vertex");
            if (s.p < s.end && *s.p == '/') {
                ++s.p;
                if (s.p == s.end || *s.p != '/')
                    c.vt = index(s, start, texcoords_.size(), "texture");
                if (s.p < s.end && *s.p == '/') {
                    ++s.p;
                    c.vn = index(s, start, normals_.size(), "normal");
                }
            }
            if (s.p < s.end && !meshio::isBlank(*s.p)) {
                s.p = start;
                s.error("malformed face corner '", s.token(), "'");
            }
            (c.vt == kNone ? cornerWithoutUv_ : cornerWithUv_) = true;
            (c.vn == kNone ? cornerWithoutNormal_ : cornerWithNormal_) = true;
            if (table_.corners.size() == kNone) s.error("more than 2^32-1 distinct vertices");
            polygon_.push_back(table_.insert(c));
        }
        if (polygon_.size() < 3)
            s.error("face with ", polygon_.size(), " vertices (needs at least 3)");

        if (currentSlot_ == kNone) currentSlot_ = slot(currentName_, currentLine_);
        // Fan triangulation keeps the polygon's winding (convex polygons only).
        for (size_t i = 1; i + 1 < polygon_.size(); ++i) {
            indices_.insert(indices_.end(), {polygon_[0], polygon_[i], polygon_[i + 1]});
            faceSlots_.push_back(currentSlot_);
        }
    }

    uint32_t slot(const std::string& material, size_t line) {
        const auto [it, inserted] =
            slotByName_.try_emplace(material, static_cast<uint32_t>(slots_.size()));
        if (inserted) slots_.push_back({material, line});
        return it->second;
    }

    void materialLibraries(LineScanner& s) {
        const fs::path dir = path_.parent_path();
        const std::string_view rest = s.rest();
        // One name with spaces, or several names separated by blanks.
        std::vector<std::string> names;
        if (!findFileCaseInsensitive(dir, std::string(rest)).empty()) {
            names.emplace_back(rest);
        } else {
            LineScanner words{s.file, s.line, rest.data(), rest.data() + rest.size()};
            for (std::string_view w = words.token(); !w.empty(); w = words.token())
                names.emplace_back(w);
        }
        if (names.empty()) s.error("mtllib without a file name");
        for (const std::string& libraryName : names) {
            const fs::path file = findFileCaseInsensitive(dir, libraryName);
            if (file.empty()) {
                meshio::warn(concat(name_, ':', s.line, ": material library '", libraryName,
                                    "' not found; its materials get default values"));
            } else if (loadedLibraries_.insert(file).second) {
                readMaterialLibrary(file, library_);
            }
        }
    }

    std::vector<MeshMaterial> materials() const {
        std::vector<MeshMaterial> result;
        for (const Slot& s : slots_) {
            const auto it = library_.find(s.name);
            if (it != library_.end()) {
                result.push_back(it->second);
                continue;
            }
            if (!s.name.empty())
                meshio::warn(concat(name_, ':', s.line, ": unknown material '", s.name,
                                    "'; using a default material (diffuse 0.8)"));
            result.emplace_back().name = s.name;
        }
        return result;
    }

    LoadedMesh finish() {
        // An attribute only some corners carry cannot be per-vertex: drop it for
        // the whole mesh and merge the corners that differed only in it.
        const bool keepUvs = cornerWithUv_ && !cornerWithoutUv_;
        const bool keepNormals = cornerWithNormal_ && !cornerWithoutNormal_;
        if (cornerWithUv_ && !keepUvs)
            meshio::warn(name_ +
                         ": only some face corners have texture coordinates; "
                         "ignoring texture coordinates for the whole mesh");
        if (cornerWithNormal_ && !keepNormals)
            meshio::warn(name_ +
                         ": only some face corners have normals; "
                         "ignoring normals for the whole mesh");
        if ((cornerWithUv_ && !keepUvs) || (cornerWithNormal_ && !keepNormals)) {
            CornerTable merged;
            std::vector<uint32_t> remap(table_.corners.size());
            for (size_t i = 0; i < remap.size(); ++i) {
                Corner c = table_.corners[i];
                if (!keepUvs) c.vt = kNone;
                if (!keepNormals) c.vn = kNone;
                remap[i] = merged.insert(c);
            }
            for (uint32_t& i : indices_) i = remap[i];
            table_ = std::move(merged);
        }

        LoadedMesh result;
        TriangleMesh& mesh = result.mesh;
        const size_t n = table_.corners.size();
        mesh.positions.reserve(n + 1);  // the spare element Embree's 16-byte loads need
        if (keepUvs) mesh.uvs.reserve(n);
        if (keepNormals) mesh.normals.reserve(n);
        for (const Corner& c : table_.corners) {
            mesh.positions.push_back(positions_[c.v]);
            if (keepUvs) mesh.uvs.push_back(texcoords_[c.vt]);
            if (keepNormals) mesh.normals.push_back(normals_[c.vn]);
        }
        mesh.indices = std::move(indices_);
        // Only the implicit default slot in use: the file assigns no materials.
        const bool anyMaterial =
            slots_.size() > 1 || (slots_.size() == 1 && !slots_[0].name.empty());
        if (anyMaterial) {
            mesh.faceMaterials = std::move(faceSlots_);
            result.materials = materials();
        }
        mesh.validate(name_);
        return result;
    }

    fs::path path_;
    std::string name_;

    std::vector<Vec3> positions_;
    std::vector<Vec2> texcoords_;
    std::vector<Vec3> normals_;
    CornerTable table_;
    std::vector<uint32_t> indices_;
    std::vector<uint32_t> faceSlots_;
    std::vector<uint32_t> polygon_;  // corners of the face being parsed
    bool cornerWithUv_ = false;
    bool cornerWithoutUv_ = false;
    bool cornerWithNormal_ = false;
    bool cornerWithoutNormal_ = false;

    // Materials: a usemtl only takes a slot once a face uses it.
    std::string currentName_;
    size_t currentLine_ = 0;
    uint32_t currentSlot_ = kNone;
    std::vector<Slot> slots_;
    std::unordered_map<std::string, uint32_t> slotByName_;
    MaterialLibrary library_;
    std::set<fs::path> loadedLibraries_;
    std::set<std::string> ignoredKeywords_;
};

}  // namespace

LoadedMesh loadObj(const fs::path& file) {
    return loadObjFromMemory(meshio::readWholeFile(file), file);
}

LoadedMesh loadObjFromMemory(std::string_view data, const fs::path& file) {
    return ObjReader(file).read(data);
}

}  // namespace strahl
