#include "mitsuba_plugins.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <array>
#include <set>
#include <span>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "imported_document.h"
#include "mitsuba_named_materials.h"
#include "spectrum_to_rgb.h"
#include "strahl/core/error.h"

namespace strahl::scene_detail::mitsuba {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

[[noreturn]] void unsupported(const Object& o, const std::string& what) {
    fail(o.place.text(), ": ", o.element(), ": ", what);
}

// The parameters a plugin reads; any other is an error rather than a setting
// silently ignored. `ignored` are parameters that do not change the expected
// image (output formats, far clip planes).
void allowOnlyNames(const Object& o, std::span<const char* const> read,
                    std::span<const char* const> ignored) {
    for (const Property& p : o.properties) {
        const auto is = [&](const char* name) { return p.name == name; };
        if (std::none_of(read.begin(), read.end(), is) &&
            std::none_of(ignored.begin(), ignored.end(), is))
            fail(p.place.text(), ": ", o.element(), ": the parameter '", p.name,
                 "' is not supported (docs/mitsuba.md lists what is)");
    }
}

void allowOnly(const Object& o, std::initializer_list<const char*> read,
               std::initializer_list<const char*> ignored = {}) {
    allowOnlyNames(o, std::span(read.begin(), read.size()), std::span(ignored.begin(), ignored.size()));
}

double number(const Object& o, const std::string& name, double fallback) {
    const Property* p = o.property(name);
    if (!p) return fallback;
    if (p->tag != "float" && p->tag != "integer")
        fail(p->place.text(), ": '", name, "' must be a float, got <", p->tag, ">");
    const std::vector<double> v = numbers(p->value, p->place, name);
    if (v.size() != 1) fail(p->place.text(), ": '", name, "': expected one number");
    return v[0];
}

int integer(const Object& o, const std::string& name, int fallback) {
    const double v = number(o, name, fallback);
    if (v != std::floor(v) || std::abs(v) > 1e9)
        fail(o.property(name)->place.text(), ": '", name, "' must be an integer");
    return int(v);
}

bool boolean(const Object& o, const std::string& name, bool fallback) {
    const Property* p = o.property(name);
    if (!p) return fallback;
    if (p->tag != "boolean" || (p->value != "true" && p->value != "false"))
        fail(p->place.text(), ": '", name, "' must be <boolean> true or false");
    return p->value == "true";
}

std::string text(const Object& o, const std::string& name, const std::string& fallback) {
    const Property* p = o.property(name);
    if (!p) return fallback;
    if (p->tag != "string") fail(p->place.text(), ": '", name, "' must be a <string>");
    return p->value;
}

glm::dvec3 vec(const Object& o, const std::string& name, glm::dvec3 fallback) {
    const Property* p = o.property(name);
    if (!p) return fallback;
    if (p->tag != "point" && p->tag != "vector")
        fail(p->place.text(), ": '", name, "' must be a <point> or <vector>");
    return p->xyz;
}

glm::dmat4 transform(const Object& o, const std::string& name) {
    const Property* p = o.property(name);
    if (!p) return glm::dmat4(1.0);
    if (p->tag != "transform") fail(p->place.text(), ": '", name, "' must be a <transform>");
    return p->matrix;
}

json vec3(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }

// "scene.xml:12": names made for objects without an id.
std::string where(const Object& o) {
    return fs::path(o.place.file).filename().string() + ":" + std::to_string(o.place.line);
}

// Whether `name` is given, as a property or as a nested object (a texture).
bool given(const Object& o, const std::string& name) {
    return o.property(name) != nullptr ||
           std::any_of(o.children.begin(), o.children.end(), [&](const Child& c) { return c.name == name; });
}

const Child* child(const Object& o, const std::string& tag, const std::string& name = "") {
    for (const Child& c : o.children)
        if (c.object->tag == tag && (name.empty() || c.name == name || c.name.empty())) return &c;
    return nullptr;
}

class Converter {
public:
    Converter(const Scene& scene, const fs::path& folder) : scene_(scene), folder_(folder) {}

    json convert() {
        const Object& root = *scene_.root;
        refuseMedia(root);
        doc_["shapes"] = json::array();
        bool sensor = false, integrator = false;
        for (const Child& c : root.children) {
            const Object& o = *c.object;
            if (o.tag == "shape") {
                shape(o, doc_["shapes"]);
            } else if (o.tag == "emitter") {
                emitter(o);
            } else if (o.tag == "sensor") {
                if (sensor) unsupported(o, "a second sensor: strahl renders one camera");
                sensor = true;
                this->sensor(o);
            } else if (o.tag == "integrator") {
                if (integrator) unsupported(o, "a second integrator");
                integrator = true;
                this->integrator(o);
            } else if (o.tag == "medium" || o.tag == "volume" || o.tag == "phase") {
                unsupported(o, "participating media are not supported");
            } else if (o.tag == "bsdf" || o.tag == "texture") {
                // Declared for <ref>s; built where a shape uses it.
            } else {
                unsupported(o, "not supported at the top level of a scene");
            }
        }
        if (!sensor) fail(root.place.text(), ": <scene>: no <sensor> (strahl needs a camera)");
        if (!integrator) render_["integrator"] = "path", render_["max_depth"] = 1024;
        // Mitsuba picks an emitter uniformly, then a point on it by area.
        render_["light_selection"] = "uniform";
        if (!materials_.empty()) doc_["materials"] = materials_;
        if (!groups_.empty()) doc_["groups"] = groups_;
        if (!lights_.empty()) doc_["lights"] = lights_;
        doc_["render"] = render_;
        if (doc_["shapes"].empty())
            fail(root.place.text(), ": <scene>: no <shape> (strahl needs at least one)");
        return doc_;
    }

private:
    // Participating media anywhere (a medium, a volume or phase function, a
    // shape's interior or exterior) are refused first: what a scene with them
    // needs most is said before any detail.
    static void refuseMedia(const Object& o) {
        for (const Child& c : o.children) {
            const std::string& tag = c.object->tag;
            if (tag == "medium" || tag == "volume" || tag == "phase")
                unsupported(*c.object, "participating media are not supported");
            refuseMedia(*c.object);
        }
    }

    // --- files -------------------------------------------------------------
    // A file name as Mitsuba finds it: relative to the <path> folders, then
    // the scene's; in the document relative to the scene's folder.
    std::string file(const Object& o, const std::string& name) {
        const std::string given = text(o, "filename", "");
        if (given.empty()) unsupported(o, "needs a <string name=\"filename\">");
        fs::path found = fs::path(given);
        std::error_code ec;  // a name the file system refuses (too long) is found nowhere
        if (found.is_relative()) {
            found = o.folder / given;
            for (const fs::path& folder : scene_.searchPath)
                if (fs::exists(folder / given, ec)) {
                    found = folder / given;
                    break;
                }
        }
        found = fs::absolute(found, ec);
        if (!fs::exists(found, ec))
            fail(o.property("filename")->place.text(), ": ", o.element(), ": no ", name, " '",
                 given, "' (looked in the <path> folders and the scene's)");
        const fs::path relative = found.lexically_normal().lexically_relative(folder_);
        return relative.empty() ? found.lexically_normal().string() : relative.string();
    }

    // --- colours and textures ----------------------------------------------
    // A reflectance or radiance: <rgb>, a uniform <spectrum> or <float>, or
    // a bitmap texture.
    json color(const Object& o, const std::string& name, double fallback) {
        for (const Child& c : o.children)
            if (c.object->tag == "texture" && c.name == name) return texture(*c.object);
        const Property* p = o.property(name);
        if (!p) return fallback;
        if (p->tag == "rgb" || p->tag == "float") {
            const std::vector<double> v = numbers(p->value, p->place, name);
            if (v.size() == 1) return v[0];
            if (v.size() == 3) return json::array({v[0], v[1], v[2]});
            fail(p->place.text(), ": '", name, "': expected 1 or 3 numbers");
        }
        if (p->tag == "spectrum") return spectrum(*p, o.tag == "emitter");
        fail(p->place.text(), ": '", name, "' must be <rgb>, <spectrum>, <float> or a texture");
    }

    // A scalar parameter: a number, a bitmap or a checkerboard (a colour
    // where one number is needed is refused). Mitsuba reads a checkerboard
    // as a scalar with the colours the other way round than as a colour (its
    // eval_1 takes color0 where eval takes color1), so they are exchanged.
    json scalar(const Object& o, const std::string& name, double fallback) {
        json value = color(o, name, fallback);
        if (value.is_array()) unsupported(o, "'" + name + "' must be one number or a texture");
        if (value.is_object() && value.contains("checkerboard")) {
            json& checker = value["checkerboard"];
            std::swap(checker["color0"], checker["color1"]);
        }
        return value;
    }

    // A <spectrum> as Mitsuba's RGB variants read it (docs/mitsuba.md):
    // wavelength:value pairs integrated against the CIE curves (weighted by
    // D65 for a reflectance; clamped to [0, 1] unless it is emitted light or
    // an index of refraction); one value is a constant spectrum, which an
    // emitter gives in Mitsuba's equal-energy white.
    static json spectrum(const Property& p, bool inEmitter) {
        static const std::set<std::string> unbounded = {"eta", "k", "int_ior", "ext_ior"};
        const bool isUnbounded = unbounded.count(p.name) > 0;
        if (p.value.find(':') == std::string::npos) {
            const std::vector<double> v = numbers(p.value, p.place, p.name);
            if (v.size() != 1) fail(p.place.text(), ": '", p.name, "': expected one number");
            if (!inEmitter || isUnbounded) return v[0];
            return vec3(v[0] * equalEnergyWhiteInLinearSrgb());
        }
        std::vector<double> wavelengths, values;
        for (const std::string& pair : spectrumPairs(p.value)) {
            const size_t colon = pair.find(':');
            if (colon == std::string::npos || pair.find(':', colon + 1) != std::string::npos)
                fail(p.place.text(), ": <spectrum name=\"", p.name, "\">: '", pair,
                     "' is not a wavelength:value pair");
            const std::vector<double> wv =
                numbers(pair.substr(0, colon) + " " + pair.substr(colon + 1), p.place, p.name);
            if (wv.size() != 2)
                fail(p.place.text(), ": <spectrum name=\"", p.name, "\">: '", pair,
                     "' is not a wavelength:value pair");
            if (!wavelengths.empty() && !(wv[0] > wavelengths.back()))
                fail(p.place.text(), ": <spectrum name=\"", p.name,
                     "\">: wavelengths must increase (", wv[0], " after ", wavelengths.back(), ")");
            wavelengths.push_back(wv[0]);
            values.push_back(wv[1]);
        }
        if (wavelengths.size() < 2)
            fail(p.place.text(), ": <spectrum name=\"", p.name, "\">: needs at least two wavelengths");
        glm::dvec3 rgb = spectrumToLinearSrgb(
            wavelengths, values, inEmitter && !isUnbounded ? SpectrumUse::Emission : SpectrumUse::Reflectance);
        rgb = glm::max(rgb, 0.0);
        if (!inEmitter && !isUnbounded) rgb = glm::min(rgb, 1.0);
        return vec3(rgb);
    }

    // "400:0.1, 500:0.3" → {"400:0.1", "500:0.3"} (commas and/or blanks between pairs).
    static std::vector<std::string> spectrumPairs(const std::string& text) {
        std::vector<std::string> pairs;
        std::string current;
        for (const char c : text + ",") {
            if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
                if (!current.empty()) pairs.push_back(current), current.clear();
            } else {
                current += c;
            }
        }
        return pairs;
    }

    // A bitmap, checkerboard or mesh attribute as a strahl texture object. A
    // bitmap says whether it is read raw (Mitsuba's default: sRGB-decoded,
    // whether a colour or a number is read from it).
    json texture(const Object& t) {
        if (t.type == "checkerboard") return checkerboard(t);
        if (t.type == "mesh_attribute") {
            // Read per vertex (interpolated) or per face, by the name the
            // PLY loader gives (docs/mesh-files.md, "Attributes").
            allowOnly(t, {"name", "scale"});
            const std::string name = text(t, "name", "");
            if (name.empty()) unsupported(t, "needs a <string name=\"name\">");
            json attribute = {{"attribute", name}};
            if (t.property("scale")) attribute["scale"] = number(t, "scale", 1.0);
            return attribute;
        }
        if (t.type != "bitmap")
            unsupported(t, "only bitmap, checkerboard and mesh_attribute textures are supported (not '" + t.type + "')");
        allowOnly(t, {"filename", "raw", "filter_type", "wrap_mode", "to_uv"}, {"format"});

        // Mitsuba reads a bitmap at the point, without MIP levels: strahl's
        // bilinear or nearest filter, not its default footprint filter.
        const std::string filter = text(t, "filter_type", "bilinear");
        if (filter != "bilinear" && filter != "nearest")
            fail(t.property("filter_type")->place.text(), ": filter_type must be bilinear or nearest");
        const std::string wrap = text(t, "wrap_mode", "repeat");
        if (wrap != "repeat" && wrap != "mirror" && wrap != "clamp")
            fail(t.property("wrap_mode")->place.text(), ": wrap_mode must be repeat, mirror or clamp");
        json texture = {{"texture", file(t, "texture image")},
                        {"filter", filter},
                        {"wrap", wrap},
                        {"raw", boolean(t, "raw", false)}};
        // to_uv acts on Mitsuba's uv, which is strahl's image coordinates
        // (s, t) = (u, 1 - v): its 2D affine part is the uv_transform.
        if (t.property("to_uv")) {
            const glm::dmat4 m = transform(t, "to_uv");
            if (m[0][2] != 0 || m[1][2] != 0 || m[2][0] != 0 || m[2][1] != 0 || m[0][3] != 0 ||
                m[1][3] != 0 || m[3][3] != 1)
                unsupported(t, "a to_uv that is not a 2D affine map (it mixes in z) is not supported");
            texture["uv_transform"] = {{m[0][0], m[1][0], m[3][0]}, {m[0][1], m[1][1], m[3][1]}};
        }
        return texture;
    }

    // Colours only (a nested texture is refused); to_uv a scale along u and v.
    json checkerboard(const Object& t) {
        allowOnly(t, {"color0", "color1", "to_uv"});
        for (const Child& c : t.children) unsupported(*c.object, "a texture inside a checkerboard is not supported");
        const glm::dmat4 m = transform(t, "to_uv");
        const bool scaleOnly = m[1][0] == 0 && m[0][1] == 0 && m[3][0] == 0 && m[3][1] == 0 &&
                               m[0][0] > 0 && m[1][1] > 0;
        if (!scaleOnly) unsupported(t, "a to_uv other than a positive scale is not supported yet");
        json checker = {{"color0", color(t, "color0", 0.4)}, {"color1", color(t, "color1", 0.2)},
                        {"scale", {m[0][0], m[1][1]}}};
        return json{{"checkerboard", checker}};
    }

    // --- materials ---------------------------------------------------------
    // The strahl material of a BSDF (with an area emitter's radiance), made
    // once per (BSDF, emitter) pair.
    std::string material(const Object* bsdf, const Object* emitter) {
        const auto key = std::make_pair(bsdf, emitter);
        if (const auto found = madeMaterials_.find(key); found != madeMaterials_.end())
            return found->second;
        json m;
        std::string name = bsdf ? (bsdf->id.empty() ? "bsdf@" + where(*bsdf) : bsdf->id)
                                : "mitsuba-default";
        if (bsdf) {
            m = bsdfMaterial(*bsdf);
        } else {
            m = {{"type", "diffuse"}, {"color", 0.5}};  // Mitsuba's default BSDF
        }
        if (emitter) {
            if (bsdf && bsdf->type == "null")
                unsupported(*bsdf, "an emitter with a null BSDF (an invisible light) is not supported");
            allowOnly(*emitter, {"radiance"});
            m["emission"] = color(*emitter, "radiance", 1.0);
            name += "+emitter@" + where(*emitter);
        }
        m["name"] = name;
        materials_.push_back(m);
        madeMaterials_[key] = name;
        return name;
    }

    json bsdfMaterial(const Object& b) {
        if (b.type == "twosided") {
            // strahl's opaque materials reflect on both sides already.
            allowOnly(b, {});
            return nestedMaterial(b);
        }
        if (b.type == "normalmap") return normalMapMaterial(b);
        if (b.type == "bumpmap") return bumpMapMaterial(b);
        if (b.type == "mask") return maskMaterial(b);
        if (b.type == "blendbsdf") return blendMaterial(b);
        if (b.type == "null") {
            // Invisible: every ray passes through (a surface that is all hole).
            allowOnly(b, {});
            return {{"type", "diffuse"}, {"opacity", 0}};
        }
        if (b.type == "diffuse") {
            allowOnly(b, {"reflectance"});
            return {{"type", "diffuse"}, {"color", color(b, "reflectance", 0.5)}};
        }
        const bool rough = b.type.rfind("rough", 0) == 0;
        const std::string base = rough ? b.type.substr(5) : b.type;
        if (base == "conductor") return conductor(b, rough);
        if (base == "dielectric") return dielectric(b, rough);
        if (base == "plastic") return plastic(b, rough);
        if (b.type == "principled" || b.type == "principledthin") return principled(b);
        if (b.type == "thindielectric") {
            allowOnly(b, {"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance"});
            requireUntinted(b, {"specular_reflectance", "specular_transmittance"});
            return {{"type", "thin_dielectric"}, {"ior", relativeIor(b, "bk7")}};
        }
        unsupported(b, "this BSDF is not supported yet (docs/mitsuba.md lists those that are)");
    }

    // --- Mitsuba's adapters: one nested BSDF, and what they add to it ------
    json nestedMaterial(const Object& b) {
        const Child* inner = child(b, "bsdf");
        if (!inner) unsupported(b, "needs a nested <bsdf>");
        return bsdfMaterial(*inner->object);
    }

    // A spot's or projector's image: strahl reads it as a colour image,
    // sRGB-decoded; a raw one is refused.
    static json lightImage(const Object& t, json image) {
        if (image.value("raw", false)) unsupported(t, "a raw bitmap as a light's image is not supported");
        image.erase("raw");
        return image;
    }

    // The adapter's <texture>, which must be a bitmap read raw (as data):
    // strahl reads normal and height maps without sRGB decoding.
    json rawBitmap(const Object& b, const std::string& what) {
        const Child* map = nullptr;
        for (const Child& c : b.children)
            if (c.object->tag == "texture") map = &c;
        if (!map) unsupported(b, "needs a <texture>");
        const Object& t = *map->object;
        if (t.type != "bitmap" || !boolean(t, "raw", false))
            unsupported(t, what + " must be a bitmap with raw = true (strahl reads it as data)");
        json image = texture(t);
        image.erase("raw");  // strahl reads normal and height maps as data
        return image;
    }

    // Mitsuba's tangent-space normal map, n = 2 texel - 1 in the frame of
    // dp/du: strahl's normal_map, with the terminator shadowing Mitsuba's
    // normalmap applies. A rawconstant (0.5, 0.5, 1) is the identity.
    json normalMapMaterial(const Object& b) {
        allowOnly(b, {"normalmap"});
        json m = nestedMaterial(b);
        for (const Child& c : b.children) {
            const Object& t = *c.object;
            if (t.tag != "texture" || t.type != "rawconstant") continue;
            allowOnly(t, {"value"});
            if (vec(t, "value", {0.5, 0.5, 1.0}) != glm::dvec3(0.5, 0.5, 1.0))
                unsupported(t, "a constant normal map other than the identity (0.5, 0.5, 1) is not supported");
            return m;
        }
        json normalMap = rawBitmap(b, "a normal map");
        normalMap["shadowing"] = true;
        m["normal_map"] = normalMap;
        return m;
    }

    // Mitsuba's bump map: the luminance of the bitmap times `scale` as a
    // height over (u, v), with its terminator shadowing.
    json bumpMapMaterial(const Object& b) {
        allowOnly(b, {"scale"});
        json m = nestedMaterial(b);
        json bump = rawBitmap(b, "a bump map");
        bump["scale"] = number(b, "scale", 1.0);
        bump["shadowing"] = true;
        m["bump_map"] = bump;
        return m;
    }

    // Mitsuba's mask passes a ray through with probability 1 - opacity;
    // strahl's opacity cuts the same holes out of the surface.
    json maskMaterial(const Object& b) {
        allowOnly(b, {"opacity"});
        json m = nestedMaterial(b);
        if (m.contains("opacity")) unsupported(b, "a mask inside a mask is not supported");
        m["opacity"] = scalar(b, "opacity", 0.5);
        return m;
    }

    // Mitsuba's blendbsdf: (1 - weight) first + weight second, strahl's blend
    // of the two nested BSDFs' kinds.
    json blendMaterial(const Object& b) {
        allowOnly(b, {"weight"});
        std::vector<const Object*> parts;
        for (const Child& c : b.children)
            if (c.object->tag == "bsdf") parts.push_back(c.object.get());
        if (parts.size() != 2) unsupported(b, "needs two nested <bsdf>s");
        if (!given(b, "weight")) unsupported(b, "needs a weight");
        const json weight = scalar(b, "weight", 0.5);
        json materials = json::array();
        for (const Object* part : parts) {
            json m = bsdfMaterial(*part);
            for (const char* key : {"normal_map", "bump_map", "opacity"})
                if (m.contains(key))
                    unsupported(*part, "a normalmap, bumpmap, mask or null BSDF inside a blendbsdf is not supported");
            materials.push_back(m);
        }
        return {{"type", "blend"}, {"weight", weight}, {"materials", materials}};
    }

    // Mitsuba's principled and principledthin: strahl's principled, which is
    // defined as Mitsuba's (docs/materials.md, Principled), its parameters
    // renamed; the sampling rates change only the noise.
    json principled(const Object& b) {
        const bool thin = b.type == "principledthin";
        static const std::vector<std::pair<const char*, const char*>> kSolid = {
            {"roughness", "roughness"}, {"anisotropic", "anisotropic"}, {"metallic", "metallic"},
            {"spec_tint", "specular_tint"}, {"sheen", "sheen"}, {"sheen_tint", "sheen_tint"},
            {"clearcoat", "clearcoat"}, {"clearcoat_gloss", "clearcoat_gloss"},
            {"spec_trans", "transmission"}, {"flatness", "flatness"}};
        static const std::vector<std::pair<const char*, const char*>> kThin = {
            {"roughness", "roughness"}, {"anisotropic", "anisotropic"}, {"spec_tint", "specular_tint"},
            {"sheen", "sheen"}, {"sheen_tint", "sheen_tint"}, {"spec_trans", "transmission"},
            {"flatness", "flatness"}, {"diff_trans", "diffuse_transmission"}};
        const auto& names = thin ? kThin : kSolid;
        std::vector<const char*> allowed = {"base_color", "eta"};
        for (const auto& [mitsuba, strahl] : names) allowed.push_back(mitsuba);
        if (!thin) allowed.push_back("specular");
        const std::vector<const char*> rates =
            thin ? std::vector<const char*>{"specular_reflectance_sampling_rate",
                                            "specular_transmittance_sampling_rate",
                                            "diffuse_reflectance_sampling_rate",
                                            "diffuse_transmittance_sampling_rate"}
                 : std::vector<const char*>{"diffuse_reflectance_sampling_rate",
                                            "main_specular_sampling_rate", "clearcoat_sampling_rate"};
        allowOnlyNames(b, allowed, rates);
        for (const Child& c : b.children)
            if (std::none_of(allowed.begin(), allowed.end(), [&](const char* n) { return c.name == n; }))
                unsupported(*c.object, "not a parameter of " + b.type + " (docs/mitsuba.md lists them)");
        json m = {{"type", "principled"}, {"color", color(b, "base_color", 0.5)}};
        if (thin) m["thin"] = true;
        for (const auto& [mitsuba, strahl] : names)
            if (given(b, mitsuba)) m[strahl] = scalar(b, mitsuba, 0.0);
        for (const Child& c : b.children)
            if (c.name == "eta") unsupported(*c.object, "a textured 'eta' is not supported");
        if (b.property("eta") && b.property("specular")) unsupported(b, "give either eta or specular");
        if (b.property("eta")) m["ior"] = number(b, "eta", 1.5);
        if (b.property("specular")) m["specular"] = number(b, "specular", 0.5);
        return m;
    }

    // Mitsuba's microfacet BSDFs: its `distribution` (beckmann by default),
    // its `alpha` (or `alpha_u` and `alpha_v`; 0.1 by default) as strahl's
    // roughness = sqrt(alpha), and its masking, the separable Smith product.
    void microfacets(const Object& b, json& m, bool anisotropic) {
        const std::string distribution = text(b, "distribution", "beckmann");
        if (distribution != "beckmann" && distribution != "ggx")
            fail(b.property("distribution")->place.text(), ": distribution must be beckmann or ggx");
        m["distribution"] = distribution;
        m["masking"] = "separable";
        const auto roughness = [&](const std::string& name) {
            for (const Child& c : b.children)
                if (c.name == name) unsupported(*c.object, "a textured '" + name + "' is not supported");
            const double alpha = number(b, name, 0.1);
            if (!(alpha >= 0.0 && alpha <= 1.0))
                fail(b.property(name)->place.text(), ": '", name, "' must be in [0, 1]");
            return std::sqrt(alpha);
        };
        const bool u = b.property("alpha_u") != nullptr, v = b.property("alpha_v") != nullptr;
        if (u != v || (u && b.property("alpha")))
            unsupported(b, "give either alpha or both alpha_u and alpha_v");
        if (!u) {
            m["roughness"] = roughness("alpha");
        } else if (!anisotropic) {
            unsupported(b, "an anisotropic roughness (alpha_u, alpha_v) is only supported on conductors");
        } else {
            m["roughness_u"] = roughness("alpha_u");
            m["roughness_v"] = roughness("alpha_v");
        }
    }

    // The parameters only the rough variants read are unknown to the smooth ones.
    static void refuseMicrofacetParameters(const Object& b) {
        for (const char* name : {"distribution", "alpha", "alpha_u", "alpha_v", "sample_visible"})
            if (const Property* p = b.property(name))
                fail(p->place.text(), ": ", b.element(), ": the parameter '", name,
                     "' is not supported (docs/mitsuba.md lists what is)");
    }

    // An index of refraction: a number or one of Mitsuba's named materials.
    double ior(const Object& b, const std::string& name, const std::string& fallback) {
        const Property* p = b.property(name);
        if (p && (p->tag == "float" || p->tag == "integer")) return number(b, name, 0.0);
        const std::string given = text(b, name, fallback);
        const std::optional<double> value = namedIor(given);
        if (!value)
            fail(p->place.text(), ": ", b.element(), ": unknown ", name, " '", given, "' (known: ",
                 namedIorList(), ")");
        return *value;
    }

    // The relative index int_ior / ext_ior, which strahl's dielectrics take in [1.0001, 4].
    double relativeIor(const Object& b, const std::string& fallbackInside) {
        const double eta = ior(b, "int_ior", fallbackInside) / ior(b, "ext_ior", "air");
        if (!(eta >= 1.0001 && eta <= 4.0))
            unsupported(b, "int_ior / ext_ior = " + std::to_string(eta) +
                               ": strahl's interfaces need a relative index in [1.0001, 4] "
                               "(denser inside)");
        return eta;
    }

    // Mitsuba's optional specular tints: strahl renders them only when absent or 1.
    void requireUntinted(const Object& b, std::initializer_list<const char*> names) {
        for (const char* name : names) {
            for (const Child& c : b.children)
                if (c.name == name) unsupported(*c.object, std::string("a textured '") + name + "' is not supported");
            if (b.property(name) && color(b, name, 1.0) != json(1.0))
                unsupported(b, std::string("'") + name + "' other than 1 is not supported");
        }
    }

    json conductor(const Object& b, bool rough) {
        allowOnly(b, {"material", "eta", "k", "specular_reflectance", "distribution", "alpha",
                      "alpha_u", "alpha_v"},
                  {"sample_visible"});
        if (!rough) refuseMicrofacetParameters(b);
        requireUntinted(b, {"specular_reflectance"});
        json m = {{"type", "conductor"}};
        if (b.property("material") && (b.property("eta") || b.property("k")))
            unsupported(b, "give either material or eta and k");
        if (b.property("eta") || b.property("k")) {
            m["eta"] = color(b, "eta", 0.0);
            m["k"] = color(b, "k", 1.0);
        } else {
            const std::string name = text(b, "material", "none");
            const std::optional<NamedConductor> c = namedConductor(name);
            if (!c)
                unsupported(b, "the conductor material '" + name +
                                   "' is not available (docs/mitsuba.md lists those that are)");
            m["eta"] = vec3(c->eta);
            m["k"] = vec3(c->k);
        }
        if (rough) microfacets(b, m, true);
        return m;
    }

    json dielectric(const Object& b, bool rough) {
        allowOnly(b, {"int_ior", "ext_ior", "specular_reflectance", "specular_transmittance",
                      "distribution", "alpha", "alpha_u", "alpha_v"},
                  {"sample_visible"});
        if (!rough) refuseMicrofacetParameters(b);
        requireUntinted(b, {"specular_reflectance", "specular_transmittance"});
        json m = {{"type", "dielectric"}, {"ior", relativeIor(b, "bk7")}};
        if (rough) microfacets(b, m, false);
        return m;
    }

    // Mitsuba's plastic: the linear series by default (`nonlinear` false);
    // the rough one lets through what its rough interface transmits.
    json plastic(const Object& b, bool rough) {
        allowOnly(b, {"diffuse_reflectance", "int_ior", "ext_ior", "nonlinear",
                      "specular_reflectance", "distribution", "alpha"},
                  {"sample_visible"});
        if (!rough) refuseMicrofacetParameters(b);
        requireUntinted(b, {"specular_reflectance"});
        json m = {{"type", "plastic"},
                  {"color", color(b, "diffuse_reflectance", 0.5)},
                  {"ior", relativeIor(b, "polypropylene")},
                  {"nonlinear", boolean(b, "nonlinear", false)}};
        if (rough) {
            microfacets(b, m, false);
            m["coat_transmittance"] = "microfacet";
        }
        return m;
    }

    // --- shapes ------------------------------------------------------------
    void shape(const Object& s, json& into) {
        const Child* bsdf = child(s, "bsdf");
        const Child* emitter = child(s, "emitter");
        if (emitter && emitter->object->type != "area")
            unsupported(*emitter->object, "only area emitters can be attached to shapes");
        for (const Child& c : s.children)
            if (c.object->tag != "bsdf" && c.object->tag != "emitter" && c.object->tag != "shape")
                unsupported(*c.object, "not supported inside a <shape>");
        const bool flip = boolean(s, "flip_normals", false);
        const glm::dmat4 toWorld = transform(s, "to_world");
        glm::dmat4 localToWorld(1.0);  // the shape's own placement, before to_world
        json shape;
        if (s.type == "obj" || s.type == "ply") {
            allowOnly(s, {"filename", "to_world", "face_normals", "flip_normals"});
            // Mitsuba computes the normals a file lacks (smooth) unless
            // face_normals asks for flat shading.
            shape = {{"type", "mesh"},
                     {"file", file(s, "mesh file")},
                     {"normals", boolean(s, "face_normals", false) ? "flat" : "smooth"}};
        } else if (s.type == "serialized") {
            allowOnly(s, {"filename", "shape_index", "to_world", "face_normals", "flip_normals"});
            const std::string name = file(s, "serialized mesh");
            if (fs::path(name).extension() != ".serialized")
                unsupported(s, "the file must end in .serialized (strahl picks a mesh format by its extension)");
            const int index = integer(s, "shape_index", 0);
            if (index < 0) fail(s.property("shape_index")->place.text(), ": shape_index must not be negative");
            shape = {{"type", "mesh"},
                     {"file", name},
                     {"shape_index", index},
                     {"normals", boolean(s, "face_normals", false) ? "flat" : "smooth"}};
        } else if (s.type == "rectangle") {
            allowOnly(s, {"to_world", "flip_normals"});
            // [-1, 1]² in the xy plane, facing +z. Mitsuba's uv is
            // ((x+1)/2, (y+1)/2) with its v the image row from the top;
            // strahl's image row is 1 − v, so v = (1−y)/2 here.
            shape = {{"type", "mesh"},
                     {"positions", {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}},
                     {"normals", {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}},
                     {"uvs", {{0, 1}, {1, 1}, {1, 0}, {0, 0}}},
                     {"indices", {0u, 1u, 2u, 0u, 2u, 3u}}};
        } else if (s.type == "cube") {
            allowOnly(s, {"to_world", "flip_normals"});
            shape = cube();
        } else if (s.type == "sphere") {
            allowOnly(s, {"to_world", "center", "radius", "flip_normals"});
            if (flip) unsupported(s, "flip_normals on a sphere is not supported yet (use a mesh)");
            const glm::dvec3 center = vec(s, "center", glm::dvec3(0.0));
            const double radius = number(s, "radius", 1.0);
            if (!(radius > 0.0)) fail(s.property("radius")->place.text(), ": radius must be positive");
            localToWorld = glm::dmat4(glm::dvec4(radius, 0, 0, 0), glm::dvec4(0, radius, 0, 0),
                                      glm::dvec4(0, 0, radius, 0), glm::dvec4(center, 1.0));
            // Exact as an implicit surface; an emitter becomes a fine mesh,
            // which next-event estimation samples (analytic shapes it cannot).
            shape = emitter ? analyticMesh({{"type", "sphere"}, {"radius", 1}}, {128, 256})
                            : json{{"type", "implicit"}, {"surface", {{"type", "sphere"}, {"radius", 1}}}};
        } else if (s.type == "disk") {
            allowOnly(s, {"to_world", "flip_normals"});
            // The unit disk in z = 0 facing +z: the profile from r = 1 in to
            // the centre turns about z with the normal up.
            shape = analyticMesh({{"type", "revolution"}, {"profile", {{1, 0}, {0, 0}}}}, {256, 1});
        } else if (s.type == "cylinder") {
            allowOnly(s, {"to_world", "p0", "p1", "radius", "flip_normals"});
            const glm::dvec3 p0 = vec(s, "p0", glm::dvec3(0.0)), p1 = vec(s, "p1", glm::dvec3(0, 0, 1));
            const double radius = number(s, "radius", 1.0), length = glm::length(p1 - p0);
            if (!(radius > 0.0)) fail(s.property("radius")->place.text(), ": radius must be positive");
            if (!(length > 0.0)) unsupported(s, "p0 and p1 must differ");
            // The open tube of the radius around z from 0 to the length,
            // turned onto p0 -> p1.
            const glm::dvec3 z = (p1 - p0) / length;
            const glm::dvec3 x = glm::normalize(std::abs(z.x) < 0.9 ? glm::cross(glm::dvec3(1, 0, 0), z)
                                                                    : glm::cross(glm::dvec3(0, 1, 0), z));
            localToWorld = glm::dmat4(glm::dvec4(x, 0), glm::dvec4(glm::cross(z, x), 0), glm::dvec4(z, 0),
                                      glm::dvec4(p0, 1));
            const json surface = {{"type", "cylinder"}, {"radius", radius}, {"z_min", 0}, {"z_max", length}};
            shape = emitter ? analyticMesh(surface, {256, 1})
                            : json{{"type", "parametric"}, {"mode", "direct"}, {"surface", surface}};
        } else if (s.type == "bsplinecurve" || s.type == "linearcurve") {
            allowOnly(s, {"filename", "to_world"});
            // The strand file as Mitsuba reads it: cubic B-spline or linear
            // round curves, to_world moving the points but not the radii.
            shape = {{"type", "curves"},
                     {"file", file(s, "curve file")},
                     {"basis", s.type == "bsplinecurve" ? "bspline" : "linear"},
                     {"transform_radius", false}};
        } else if (s.type == "instance") {
            allowOnly(s, {"to_world"});
            const Child* group = child(s, "shape");
            if (!group || group->object->type != "shapegroup")
                unsupported(s, "needs a <ref> to a <shape type=\"shapegroup\">");
            shape = {{"type", "instance"}, {"group", shapegroup(*group->object)}};
        } else if (s.type == "shapegroup") {
            shapegroup(s);  // placed by instances
            return;
        } else {
            unsupported(s, "this shape is not supported yet (docs/mitsuba.md lists those that are)");
        }
        shape["transform"] = matrixTransform(toWorld * localToWorld);
        if (flip) shape["flip_normals"] = true;  // the meshes: winding and normals turned
        if (s.type != "instance")
            shape["material"] = material(bsdf ? bsdf->object.get() : nullptr,
                                         emitter ? emitter->object.get() : nullptr);
        // The analytic shapes' (u, v) are not Mitsuba's uv: no textures on them.
        const bool analytic = s.type == "sphere" || s.type == "disk" || s.type == "cylinder" ||
                              s.type == "bsplinecurve" || s.type == "linearcurve";
        if (analytic && shape.contains("material") && readsTextures(materialNamed(materials_, shape["material"])))
            unsupported(s, "a textured material on a Mitsuba " + s.type +
                               " is not supported (its uv is not Mitsuba's; use a mesh)");
        shape["name"] = s.id.empty() ? s.type + "@" + where(s) : s.id;
        into.push_back(shape);
    }

    // A parametric surface tessellated into a fixed grid of segments (along
    // its u and v): a mesh, so that next-event estimation finds it as a light.
    static json analyticMesh(const json& surface, std::array<int, 2> segments) {
        return {{"type", "parametric"},
                {"surface", surface},
                {"tessellation", {{"segments", {segments[0], segments[1]}}}}};
    }

    std::string shapegroup(const Object& g) {
        if (const auto found = groupNames_.find(&g); found != groupNames_.end()) return found->second;
        const std::string name = g.id.empty() ? "shapegroup@" + where(g) : g.id;
        json shapes = json::array();
        for (const Child& c : g.children) {
            if (c.object->tag != "shape") unsupported(*c.object, "a shapegroup holds shapes only");
            shape(*c.object, shapes);
        }
        groups_.push_back({{"name", name}, {"shapes", shapes}});
        groupNames_[&g] = name;
        return name;
    }

    static json cube() {
        json positions = json::array(), normals = json::array(), uvs = json::array(),
             indices = json::array();
        // Each face of [-1, 1]³: its normal n and two axes a, b with a × b = n.
        const int faces[6][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                    {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                                    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
        for (int f = 0; f < 6; ++f) {
            const glm::dvec3 n(faces[f][0][0], faces[f][0][1], faces[f][0][2]);
            const glm::dvec3 a(faces[f][1][0], faces[f][1][1], faces[f][1][2]);
            const glm::dvec3 b(faces[f][2][0], faces[f][2][1], faces[f][2][2]);
            const int base = 4 * f;
            const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (const auto& c : corners) {
                positions.push_back(vec3(n + c[0] * a + c[1] * b));
                normals.push_back(vec3(n));
                uvs.push_back({(c[0] + 1) / 2, (1 - c[1]) / 2});  // as the rectangle's
            }
            for (int i : {0, 1, 2, 0, 2, 3}) indices.push_back(static_cast<unsigned>(base + i));
        }
        return {{"type", "mesh"}, {"positions", positions}, {"normals", normals}, {"uvs", uvs},
                {"indices", indices}};
    }

    // --- emitters ----------------------------------------------------------
    void emitter(const Object& e) {
        const glm::dmat4 toWorld = transform(e, "to_world");
        if (e.type == "point") {
            allowOnly(e, {"position", "intensity", "to_world"});
            const glm::dvec3 position =
                e.property("position") ? vec(e, "position", glm::dvec3(0.0)) : glm::dvec3(toWorld[3]);
            lights_.push_back({{"type", "point"}, {"position", vec3(position)},
                               {"intensity", color(e, "intensity", 1.0)}});
        } else if (e.type == "directional") {
            allowOnly(e, {"direction", "irradiance", "to_world"});
            const glm::dvec3 direction = e.property("direction")
                                             ? vec(e, "direction", glm::dvec3(0, 0, 1))
                                             : glm::dvec3(toWorld * glm::dvec4(0, 0, 1, 0));
            lights_.push_back({{"type", "directional"}, {"direction", vec3(direction)},
                               {"irradiance", color(e, "irradiance", 1.0)}});
        } else if (e.type == "constant") {
            allowOnly(e, {"radiance"});
            if (doc_.contains("background")) unsupported(e, "a second constant emitter");
            doc_["background"] = color(e, "radiance", 1.0);
        } else if (e.type == "spot") {
            spot(e, toWorld);
        } else if (e.type == "projector") {
            projector(e, toWorld);
        } else if (e.type == "envmap") {
            allowOnly(e, {"filename", "scale", "to_world"}, {"mis_compensation"});
            // Mitsuba's lat-long map: u = atan2(x, -z) / 2π, so its image
            // centre looks along +z, where strahl's looks along +x: the same
            // map turned -90° about +y (docs/mitsuba.md). Its rows run from
            // pole to pole.
            const double rotation = -90.0 + rotationAboutY(e, toWorld);
            lights_.push_back({{"type", "environment"},
                               {"file", file(e, "environment image")},
                               {"scale", number(e, "scale", 1.0)},
                               {"rotation", std::remainder(rotation, 360.0)},
                               {"rows", "poles"}});
        } else if (e.type == "area") {
            unsupported(e, "an area emitter belongs inside a <shape>");
        } else {
            unsupported(e, "this emitter is not supported yet (docs/mitsuba.md lists those that are)");
        }
    }

    // Mitsuba's spot: at to_world's origin, along its +z, its image's up
    // along +y; full intensity inside beam_width, then linear in the angle to
    // zero at cutoff_angle; an optional bitmap projected over the cone.
    // A light's to_world must turn (and may scale uniformly) its local frame:
    // +z the light's axis, +y the up side of its image.
    static void requireRotation(const Object& e, const glm::dmat4& m) {
        const glm::dvec3 x(m[0]), y(m[1]), z(m[2]);
        const double length = glm::length(z);
        if (!(length > 0.0) || std::abs(glm::length(x) - length) > 1e-6 * length ||
            std::abs(glm::length(y) - length) > 1e-6 * length ||
            glm::length(glm::cross(x, y) - length * z) > 1e-6 * length * length)
            unsupported(e, "a to_world that is not a rotation (times a uniform scale) is not supported");
    }

    void spot(const Object& e, const glm::dmat4& m) {
        allowOnly(e, {"intensity", "cutoff_angle", "beam_width", "texture", "to_world"});
        requireRotation(e, m);
        const glm::dvec3 y(m[1]), z(m[2]);
        const double cutoff = number(e, "cutoff_angle", 20.0);
        const double beam = number(e, "beam_width", cutoff * 3.0 / 4.0);
        if (!(cutoff > 0.0 && cutoff <= 180.0 && beam >= 0.0 && beam <= cutoff))
            unsupported(e, "needs 0 < beam_width <= cutoff_angle <= 180 degrees");
        json light = {{"type", "spot"},
                      {"position", vec3(glm::dvec3(m[3]))},
                      {"direction", vec3(glm::normalize(z))},
                      {"intensity", color(e, "intensity", 1.0)},
                      {"cone_angle", cutoff},
                      {"falloff_start", beam},
                      {"falloff", "linear"}};
        for (const Child& c : e.children) {
            if (c.object->tag != "texture" || c.name != "texture")
                unsupported(*c.object, "not supported inside a spot emitter");
            if (c.object->type != "bitmap") unsupported(*c.object, "a spot projects a bitmap only");
            light["texture"] = lightImage(*c.object, texture(*c.object));
            light["up"] = vec3(glm::normalize(y));
        }
        lights_.push_back(light);
    }

    // Mitsuba's projector: the reciprocal of its perspective camera at
    // to_world (+z forward, +y up), with the camera's fov conventions; the
    // irradiance texture's aspect shapes the frustum. Mitsuba's code gives a
    // plane one unit away π × scale × irradiance (docs/mitsuba.md).
    void projector(const Object& e, const glm::dmat4& m) {
        allowOnly(e, {"irradiance", "scale", "fov", "fov_axis", "focal_length", "to_world"});
        requireRotation(e, m);
        const auto [fov, axis] = fieldOfView(e);
        const double scale = glm::pi<double>() * number(e, "scale", 1.0);
        json light = {{"type", "projector"},
                      {"position", vec3(glm::dvec3(m[3]))},
                      {"direction", vec3(glm::normalize(glm::dvec3(m[2])))},
                      {"up", vec3(glm::normalize(glm::dvec3(m[1])))},
                      {"fov", fov},
                      {"fov_axis", axis}};
        const json irradiance = color(e, "irradiance", 1.0);
        if (irradiance.is_object()) {
            if (!irradiance.contains("texture"))
                unsupported(e, "a projector projects a bitmap or a constant irradiance only");
            const Child* image = nullptr;
            for (const Child& c : e.children)
                if (c.name == "irradiance") image = &c;
            light["texture"] = lightImage(*image->object, irradiance);
            light["irradiance"] = scale;
        } else if (irradiance.is_array()) {
            light["irradiance"] = {scale * irradiance[0].get<double>(), scale * irradiance[1].get<double>(),
                                   scale * irradiance[2].get<double>()};
        } else {
            light["irradiance"] = scale * irradiance.get<double>();
        }
        lights_.push_back(light);
    }

    // The angle in degrees of a to_world that turns about +y only (strahl's
    // environment light turns that way); any other is refused.
    static double rotationAboutY(const Object& e, const glm::dmat4& m) {
        const double angle = std::atan2(m[2][0], m[0][0]);  // where +z goes: (sin a, 0, cos a)
        const glm::dmat4 expected = glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(0, 1, 0));
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (std::abs(m[c][r] - expected[c][r]) > 1e-6)
                    unsupported(e, "a to_world other than a rotation about +y is not supported yet");
        return glm::degrees(angle);
    }

    // --- sensor, film, sampler ---------------------------------------------
    void sensor(const Object& s) {
        const Child* filmChild = child(s, "film");
        const Object* film = filmChild ? filmChild->object.get() : nullptr;
        const int width = film ? integer(*film, "width", 768) : 768;
        const int height = film ? integer(*film, "height", 576) : 576;
        if (film) this->film(*film, width, height);
        else doc_["film"] = {{"width", width}, {"height", height}, {"filter", {{"type", "gaussian"}, {"radius", 2.0}}}};
        if (const Child* sampler = child(s, "sampler")) this->sampler(*sampler->object);
        for (const Child& c : s.children)
            if (c.object->tag != "film" && c.object->tag != "sampler")
                unsupported(*c.object, "not supported inside a <sensor>");

        const glm::dmat4 m = transform(s, "to_world");
        const glm::dvec3 eye(m[3]);
        const glm::dvec3 forward(m[2]), up(m[1]), left(m[0]);
        json camera = {{"eye", vec3(eye)}, {"back", vec3(-glm::normalize(forward))},
                       {"up", vec3(glm::normalize(up))}};
        const double aspect = double(width) / double(height);
        if (s.type == "perspective" || s.type == "thinlens") {
            allowOnly(s, {"to_world", "fov", "fov_axis", "near_clip", "focal_length",
                          "aperture_radius", "focus_distance"},
                      {"far_clip"});
            if (s.type == "perspective" &&
                (s.property("aperture_radius") || s.property("focus_distance")))
                unsupported(s, "aperture_radius and focus_distance belong to a thinlens sensor");
            camera["fov"] = verticalFov(s, aspect);
            camera["focal_distance"] = number(s, "near_clip", 1e-2);
            if (s.type == "thinlens") {
                camera["aperture_radius"] = number(s, "aperture_radius", 0.0);
                // Absent: strahl's default, the focal distance.
                if (s.property("focus_distance"))
                    camera["focus_distance"] = number(s, "focus_distance", 0.0);
            }
        } else if (s.type == "orthographic") {
            allowOnly(s, {"to_world", "near_clip"}, {"far_clip"});
            // Mitsuba's view is [-1, 1] wide and [-1/aspect, 1/aspect] high in
            // the sensor's space, scaled by to_world.
            const double sx = glm::length(left), sy = glm::length(up);
            camera["type"] = "orthographic";
            camera["window"] = {-sx, sx, -sy / aspect, sy / aspect};
            // Mitsuba's rays start on the plane at near_clip; strahl's on the
            // plane through the eye: move the eye there.
            const glm::dvec3 view = glm::normalize(forward);
            camera["eye"] = vec3(eye + number(s, "near_clip", 1e-2) * view);
        } else {
            unsupported(s, "this sensor is not supported (perspective, thinlens, orthographic are)");
        }
        doc_["camera"] = camera;
    }

    // A camera's (or projector's) field of view in degrees and the axis it
    // spans: fov along fov_axis (default x), or without fov a focal_length
    // (default 50mm) in mm on 35 mm film (36 x 24 mm), along the diagonal.
    static std::pair<double, std::string> fieldOfView(const Object& s) {
        double fov = 0.0;
        std::string axis = text(s, "fov_axis", "x");
        if (s.property("fov")) {
            fov = number(s, "fov", 0.0);
        } else {
            const std::string given = text(s, "focal_length", "50mm");
            const std::string digits = given.substr(0, given.find("mm"));
            const double f = numbers(digits, s.place, "focal_length").at(0);
            fov = glm::degrees(2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * f)));
            axis = "diagonal";
        }
        if (!(fov > 0.0 && fov < 180.0)) unsupported(s, "fov must be between 0 and 180 degrees");
        static const std::set<std::string> axes = {"x", "y", "diagonal", "smaller", "larger"};
        if (!axes.count(axis))
            fail(s.property("fov_axis")->place.text(), ": fov_axis must be x, y, diagonal, smaller or larger");
        return {fov, axis};
    }

    // Mitsuba's fov is along fov_axis (default x); strahl's is vertical.
    static double verticalFov(const Object& s, double aspect) {
        const auto [fov, axis] = fieldOfView(s);
        const double t = std::tan(glm::radians(fov) / 2.0);
        double ty = 0.0;  // tan of half the vertical fov
        if (axis == "x") ty = t / aspect;
        else if (axis == "y") ty = t;
        else if (axis == "diagonal") ty = t / std::sqrt(aspect * aspect + 1.0);
        else if (axis == "smaller") ty = aspect >= 1.0 ? t : t / aspect;
        else ty = aspect >= 1.0 ? t / aspect : t;  // larger
        return glm::degrees(2.0 * std::atan(ty));
    }

    void film(const Object& f, int width, int height) {
        if (f.type != "hdrfilm") unsupported(f, "only hdrfilm is supported");
        allowOnly(f, {"width", "height", "component_format", "crop_offset_x", "crop_offset_y",
                      "crop_width", "crop_height"},
                  {"pixel_format", "file_format", "banner", "sample_border"});
        json filter = {{"type", "gaussian"}, {"radius", 2.0}};  // Mitsuba's default: σ 0.5, 4σ
        if (const Child* rfilter = child(f, "rfilter")) {
            const Object& r = *rfilter->object;
            if (r.type == "box") {
                allowOnly(r, {});
                filter = "box";
            } else if (r.type == "gaussian") {
                allowOnly(r, {"stddev"});
                if (number(r, "stddev", 0.5) != 0.5)
                    unsupported(r, "only the default stddev 0.5 is supported");
            } else if (r.type == "tent") {
                allowOnly(r, {"radius"});
                filter = json{{"type", "tent"}, {"radius", number(r, "radius", 1.0)}};
            } else {
                unsupported(r, "this reconstruction filter is not supported (box, tent and gaussian are)");
            }
        }
        doc_["film"] = {{"width", width},
                        {"height", height},
                        {"filter", filter},
                        {"exr_float", text(f, "component_format", "float16") == "float32"}};
        // Mitsuba's crop window (the rest of the film is not rendered).
        const int x0 = integer(f, "crop_offset_x", 0), y0 = integer(f, "crop_offset_y", 0);
        const int cw = integer(f, "crop_width", width - x0), ch = integer(f, "crop_height", height - y0);
        if (x0 < 0 || y0 < 0 || cw < 1 || ch < 1 || x0 + cw > width || y0 + ch > height)
            unsupported(f, "the crop window (offset " + std::to_string(x0) + ", " + std::to_string(y0) +
                               ", size " + std::to_string(cw) + " x " + std::to_string(ch) +
                               ") must lie inside the film");
        if (x0 != 0 || y0 != 0 || cw != width || ch != height)
            doc_["film"]["crop"] = {x0, y0, x0 + cw, y0 + ch};
    }

    void sampler(const Object& s) {
        static const std::set<std::string> kinds = {"independent", "stratified", "multijitter",
                                                    "orthogonal", "ldsampler"};
        if (!kinds.count(s.type)) unsupported(s, "unknown sampler");
        // Every kind becomes strahl's own sampler: the same expected image.
        allowOnly(s, {"sample_count", "seed"}, {"jitter"});
        render_["spp"] = integer(s, "sample_count", 4);
        const int seed = integer(s, "seed", 0);
        if (seed < 0) unsupported(s, "seed must not be negative");
        render_["seed"] = static_cast<uint64_t>(seed);
    }

    // --- integrator --------------------------------------------------------
    void integrator(const Object& i) {
        if (i.type == "moment" || i.type == "aov") {
            // The wrapped integrator's image is the beauty; the moments and
            // AOV channels are not written.
            allowOnly(i, {}, {"aovs"});
            const Child* inner = child(i, "integrator");
            if (!inner) unsupported(i, "needs a nested <integrator>");
            integrator(*inner->object);
            return;
        }
        if (i.type == "path" || i.type == "ptracer" || i.type == "volpath" || i.type == "volpathmis") {
            // ptracer traces from the lights; volpath and volpathmis add
            // media, which a scene reaching here has none of (they are refused
            // first): the expected image of each is the path tracer's.
            allowOnly(i, {"max_depth", "rr_depth", "hide_emitters"}, {"samples_per_pass"});
            if (boolean(i, "hide_emitters", false)) render_["hide_emitters"] = true;
            const int maxDepth = integer(i, "max_depth", -1);
            if (maxDepth == 0 || maxDepth < -1) unsupported(i, "max_depth must be -1 or at least 1");
            // Mitsuba counts path vertices: 1 sees emitters only, 2 adds direct
            // light. strahl counts bounces: 0 sees emitters only.
            render_["integrator"] = "path";
            render_["max_depth"] = maxDepth == -1 ? 1024 : maxDepth - 1;
            // Both count bounces from 1 for the roulette: Mitsuba's depth is
            // 1 after the first BSDF sample.
            render_["russian_roulette_depth"] = std::clamp(integer(i, "rr_depth", 5), 1, 1024);
            return;
        }
        if (i.type == "direct") {
            allowOnly(i, {"hide_emitters"}, {"emitter_samples", "bsdf_samples", "shading_samples"});
            if (boolean(i, "hide_emitters", false)) render_["hide_emitters"] = true;
            render_["integrator"] = "direct";
            render_.erase("max_depth");
            return;
        }
        unsupported(i, "this integrator is not supported (path, volpath, volpathmis, direct, ptracer, moment, aov are)");
    }

    const Scene& scene_;
    fs::path folder_;
    json doc_ = json::object();
    json render_ = {{"integrator", "path"}, {"max_depth", 1024}, {"spp", 4}};
    json materials_ = json::array(), groups_ = json::array(), lights_ = json::array();
    std::map<std::pair<const Object*, const Object*>, std::string> madeMaterials_;
    std::map<const Object*, std::string> groupNames_;
};

}  // namespace

json toStrahlDocument(const Scene& scene, const fs::path& sceneFolder) {
    return Converter(scene, sceneFolder).convert();
}

}  // namespace strahl::scene_detail::mitsuba
