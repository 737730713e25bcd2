// Reader of .mtl material libraries (the keys read are listed in
// docs/mesh-files.md, "OBJ .mtl keys").

#include "mtl_reader.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl::meshio {

namespace {

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
    const auto [next, ec] = parseNumber(token.data(), token.data() + token.size(), value);
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
            warn(concat(name_, ':', s.line, ": texture '", textureName,
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
        warn(concat(name_, ':', s.line, ": ", what, ' ', value, ' ', problem,
                            " (material '", current_->name, "')"));
    }

    std::string name_;
    fs::path dir_;
    MaterialLibrary& library_;
    MeshMaterial duplicate_;  // absorbs a repeated newmtl: the first definition wins
    MeshMaterial* current_ = nullptr;
    bool sawDissolve_ = false;  // the current material has a d statement
};

}  // namespace

void readMaterialLibrary(const fs::path& mtlFile, MaterialLibrary& library) {
    MaterialLibraryReader(mtlFile, library).read(readWholeFile(mtlFile));
}


}  // namespace strahl::meshio
