// A pbrt-v4 scene as a strahl scene document (pbrt_mapping.h); docs/pbrt.md
// has the tables this code implements, directive by directive.

#include "pbrt_mapping.h"

#include "image_reader.h"
#include "strahl/core/srgb.h"
#include "strahl/core/equal_area.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/gtc/constants.hpp>

#include "imported_document.h"
#include "mitsuba_named_materials.h"
#include "spectrum_to_rgb.h"
#include "strahl/core/bounds.h"
#include "strahl/core/error.h"
#include "strahl/core/motion.h"
#include "strahl/geometry/bilinear_patches.h"
#include "strahl/geometry/loop_subdivision.h"
#include "strahl/meshio/mesh_file.h"

namespace strahl::scene_detail::pbrt {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// x mirrored: pbrt's left-handed camera seen in strahl's right-handed world.
const glm::dmat4 kMirrorX(glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0),
                          glm::dvec4(0, 0, 0, 1));

// Luminance of linear sRGB (Rec. 709 primaries, the Y row of RGB -> XYZ).
double luminance(glm::dvec3 c) { return 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b; }

// The illuminance that pbrt-v4's equal-area square image `file` sends to a
// surface facing +z in the light's frame: Σ Y(pixel) cos θ · 4π / pixels over
// the pixels whose direction has z > 0 (cos θ = z), Y the luminance
// above. In the octahedral layout z depends only on the pixel centre's
// distance from the centre, |2u − 1| + |2v − 1| = r: z = 1 − r² inside the
// central diamond (equalAreaSquareToSphere), so the image's orientation does
// not matter.
double upperHemisphereIlluminance(const std::filesystem::path& file) {
    const FloatImage image = readFloatImage(file, "environment image", size_t(1) << 28);
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const Vec3 w = equalAreaSquareToSphere(Vec2((float(x) + 0.5f) / float(image.width),
                                                        (float(y) + 0.5f) / float(image.height)));
            if (w.z <= 0.0f) continue;
            const float* p = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * size_t(image.channels)];
            const double Y = image.channels == 1 ? double(p[0]) : luminance(glm::dvec3(p[0], p[1], p[2]));
            sum += Y * double(w.z);
        }
    return sum * 4.0 * glm::pi<double>() / (double(image.width) * double(image.height));
}

// The mean luminance of an area light's image as strahl's texture system
// reads it for a colour (integer images decoded from sRGB): pbrt-v4's k_e,
// by which `power` divides.
double meanImageLuminance(const std::filesystem::path& file) {
    const FloatImage image = readFloatImage(file, "area light image", size_t(1) << 28);
    const auto linear = [&](float v) {
        return image.integer ? srgbToLinear(std::clamp(double(v), 0.0, 1.0)) : double(v);
    };
    double sum = 0.0;
    const size_t pixels = size_t(image.width) * size_t(image.height);
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = &image.pixels[i * size_t(image.channels)];
        sum += image.channels == 1 ? linear(p[0])
                                   : luminance(glm::dvec3(linear(p[0]), linear(p[1]), linear(p[2])));
    }
    return sum / double(pixels);
}

json vec3(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }
json color(glm::dvec3 c) {
    if (c.r == c.g && c.g == c.b) return c.r;
    return vec3(c);
}

[[noreturn]] void unsupported(const Entity& e, const std::string& what) {
    fail(e.place.text(), ": ", e.element(), ": ", what);
}
[[noreturn]] void bad(const Parameter& p, const std::string& what) {
    fail(p.place.text(), ": \"", p.type, " ", p.name, "\": ", what);
}

// The parameters an entity's mapping reads are marked; any other given is an
// error rather than a setting silently ignored.
void refuseUnread(const Entity& e) {
    for (const Parameter& p : e.params.items)
        if (!p.used)
            fail(p.place.text(), ": ", e.element(), ": parameter \"", p.type, " ", p.name,
                 "\" is not supported (docs/pbrt.md lists those that are)");
}

const Parameter* param(const Entity& e, const std::string& name) {
    const Parameter* p = e.params.find(name);
    if (p) p->used = true;
    return p;
}

const Parameter* typed(const Entity& e, const std::string& name, std::initializer_list<const char*> types) {
    const Parameter* p = param(e, name);
    if (!p) return nullptr;
    for (const char* t : types)
        if (p->type == t) return p;
    std::string list;
    for (const char* t : types) list += (list.empty() ? "" : ", ") + std::string(t);
    bad(*p, "expected type " + list);
}

double number(const Entity& e, const std::string& name, double fallback) {
    const Parameter* p = typed(e, name, {"float"});
    if (!p) return fallback;
    if (p->numbers.size() != 1) bad(*p, "expected one number");
    return p->numbers[0];
}
int integer(const Entity& e, const std::string& name, int fallback) {
    const Parameter* p = typed(e, name, {"integer"});
    if (!p) return fallback;
    if (p->numbers.size() != 1) bad(*p, "expected one integer");
    if (std::abs(p->numbers[0]) > 2e9) bad(*p, "out of range");
    return static_cast<int>(p->numbers[0]);
}
bool boolean(const Entity& e, const std::string& name, bool fallback) {
    const Parameter* p = typed(e, name, {"bool"});
    if (!p) return fallback;
    if (p->numbers.size() != 1) bad(*p, "expected one value");
    return p->numbers[0] != 0.0;
}
std::string text(const Entity& e, const std::string& name, const std::string& fallback) {
    const Parameter* p = typed(e, name, {"string"});
    if (!p) return fallback;
    if (p->strings.size() != 1) bad(*p, "expected one string");
    return p->strings[0];
}
glm::dvec3 point(const Entity& e, const std::string& name, glm::dvec3 fallback) {
    const Parameter* p = typed(e, name, {"point3", "vector3", "normal"});
    if (!p) return fallback;
    if (p->numbers.size() != 3) bad(*p, "expected three numbers");
    return {p->numbers[0], p->numbers[1], p->numbers[2]};
}

glm::dvec3 transformPoint(const glm::dmat4& m, glm::dvec3 p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }
glm::dvec3 transformVector(const glm::dmat4& m, glm::dvec3 v) { return glm::dvec3(m * glm::dvec4(v, 0.0)); }

// Wavelength/value pairs of a spectrum parameter: given inline or in a file
// of pairs ("# comments", one or more pairs per line), wavelengths increasing.
void spectrumPairs(const Parameter& p, const std::vector<double>& numbers, std::vector<double>& wl,
                   std::vector<double>& v) {
    if (numbers.size() < 4 || numbers.size() % 2 != 0) bad(p, "expected at least two wavelength-value pairs");
    for (size_t i = 0; i < numbers.size(); i += 2) {
        if (!wl.empty() && !(numbers[i] > wl.back())) bad(p, "the wavelengths must increase");
        wl.push_back(numbers[i]);
        v.push_back(numbers[i + 1]);
    }
}

// The normalised spectrum of a blackbody at `kelvin`, as linear sRGB of
// luminance 1 (pbrt-v4 lights divide any spectrum by its luminance).
glm::dvec3 blackbody(const Parameter& p, double kelvin) {
    if (!(kelvin > 0.0)) bad(p, "the temperature must be positive");
    std::vector<double> wl, v;
    // Planck's law, B(λ, T) = 2hc² / λ⁵ / (exp(hc / λkT) − 1); its scale drops out.
    constexpr double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;
    for (double nm = 360.0; nm <= 830.0; nm += 1.0) {
        const double l = nm * 1e-9;
        wl.push_back(nm);
        v.push_back(2.0 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * kelvin)) - 1.0)));
    }
    const glm::dvec3 rgb = glm::max(spectrumToLinearSrgb(wl, v, SpectrumUse::Emission), glm::dvec3(0.0));
    return rgb / luminance(rgb);
}

struct NamedGlass {
    std::string_view name;
    double ior;  // at 550 nm, from the Sellmeier coefficients of the Schott catalogue
};
constexpr NamedGlass kGlasses[] = {
    {"glass-BK7", 1.5185}, {"glass-BAF10", 1.6700}, {"glass-FK51A", 1.4870},
    {"glass-LASF9", 1.8550}, {"glass-F5", 1.6054},  {"glass-F10", 1.6241}, {"glass-F11", 1.6241},
};

// pbrt-v4's named illuminants (lights only) by their CIE 1931 2°
// chromaticities (CIE 15:2004, tables T.3 and T.8.1; ACES D60 from SMPTE ST
// 2065-1): pbrt scales a light's spectrum to luminance 1 before its `scale`
// or `power`, so the chromaticity is all that reaches an RGB render
// (chromaticityToLinearSrgb). D65 is sRGB's own white, (1, 1, 1) exactly.
struct NamedIlluminant {
    std::string_view name;
    double x, y;
};
constexpr NamedIlluminant kIlluminants[] = {
    {"stdillum-A", 0.44757, 0.40745},   {"stdillum-D50", 0.34567, 0.35850},
    {"stdillum-F1", 0.31310, 0.33727},  {"stdillum-F2", 0.37208, 0.37529},
    {"stdillum-F3", 0.40910, 0.39430},  {"stdillum-F4", 0.44018, 0.40329},
    {"stdillum-F5", 0.31379, 0.34531},  {"stdillum-F6", 0.37790, 0.38835},
    {"stdillum-F7", 0.31292, 0.32933},  {"stdillum-F8", 0.34588, 0.35875},
    {"stdillum-F9", 0.37417, 0.37281},  {"stdillum-F10", 0.34609, 0.35986},
    {"stdillum-F11", 0.38052, 0.37713}, {"stdillum-F12", 0.43695, 0.40441},
    {"illum-acesD60", 0.32168, 0.33767},
};

class Converter {
public:
    Converter(const Scene& scene, const fs::path& cwd) : s_(scene), cwd_(cwd) {}

    json convert() {
        film();
        camera();
        render();
        json shapes = json::array();
        for (const Shape& shape : s_.shapes) this->shape(shape, true, shapes);
        for (const Instance& instance : s_.instances) {
            json i = {{"type", "instance"}, {"group", group(instance.object)}};
            if (instance.toWorldEnd)
                i["motion"] = motion(instance.toWorld, *instance.toWorldEnd, mirror_);
            else
                i["transform"] = matrixTransform(mirror_ * instance.toWorld);
            i["name"] = "ObjectInstance@" + instance.place.text();
            shapes.push_back(i);
        }
        if (shapes.empty()) fail(label(), ": the scene has no shapes");
        for (const Light& light : s_.lights) this->light(light);
        // Moved, not copied: an inline mesh may hold millions of numbers.
        if (!materials_.empty()) doc_["materials"] = std::move(materials_);
        if (!groups_.empty()) doc_["groups"] = std::move(groups_);
        doc_["shapes"] = std::move(shapes);
        if (!lights_.empty()) doc_["lights"] = std::move(lights_);
        doc_["render"] = std::move(render_);
        return std::move(doc_);
    }

private:
    const Scene& s_;
    fs::path cwd_;
    json doc_ = json::object(), render_ = json::object();
    json materials_ = json::array(), groups_ = json::array(), lights_ = json::array();
    std::map<std::string, std::string> madeMaterials_;  // key -> strahl name
    std::set<std::string> materialNames_;
    std::map<std::string, std::string> madeGroups_;
    int width_ = 1280, height_ = 720;
    // What the world is mirrored by (pbrt_mapping.h): x, unless the camera
    // transform mirrors already (a "Scale -1 1 1" before the LookAt, as
    // exporters from right-handed programs write), when nothing.
    glm::dmat4 mirror_{1.0};

    const std::string& label() const { return s_.label; }

    std::string file(const Parameter& p) const {
        if (p.strings.size() != 1) bad(p, "expected one file name");
        const fs::path name = p.strings[0];
        const fs::path path = name.is_absolute() ? name : s_.folder / name;
        std::error_code ec;
        if (!fs::is_regular_file(path, ec))
            bad(p, "no such file '" + p.strings[0] + "' (looked at " + path.string() + ")");
        // pbrt resolves relative names against the main file's folder, as the
        // strahl document does: kept as written, `strahl convert` rewrites
        // them for where it writes.
        return p.strings[0];
    }

    // --- film, camera, sampler, integrator ------------------------------
    void film() {
        json film = json::object();
        std::string output = "pbrt.exr";
        if (s_.film) {
            const Entity& f = *s_.film;
            if (f.type != "rgb" && f.type != "gbuffer")
                unsupported(f, "only the \"rgb\" and \"gbuffer\" films are supported (strahl renders RGB)");
            width_ = integer(f, "xresolution", 1280);
            height_ = integer(f, "yresolution", 720);
            if (width_ < 1 || height_ < 1) unsupported(f, "the resolution must be positive");
            output = text(f, "filename", output);
            if (const Parameter* crop = typed(f, "cropwindow", {"float"})) {
                if (crop->numbers.size() != 4) bad(*crop, "expected x0 x1 y0 y1");
                const std::vector<double>& c = crop->numbers;
                for (double x : c)
                    if (x < 0.0 || x > 1.0) bad(*crop, "the window must lie in [0, 1]");
                // pbrt's pixel bounds: ceil(resolution · fraction) on both ends.
                const int x0 = static_cast<int>(std::ceil(width_ * std::min(c[0], c[1])));
                const int x1 = static_cast<int>(std::ceil(width_ * std::max(c[0], c[1])));
                const int y0 = static_cast<int>(std::ceil(height_ * std::min(c[2], c[3])));
                const int y1 = static_cast<int>(std::ceil(height_ * std::max(c[2], c[3])));
                if (x1 <= x0 || y1 <= y0) bad(*crop, "the window holds no pixel");
                film["crop"] = {x0, y0, x1, y1};
            }
            for (const char* ignored : {"diagonal", "savefp16"}) param(f, ignored);
            if (const Parameter* clamp = typed(f, "maxcomponentvalue", {"float"}))
                meshio::reportWarning(clamp->place.text() + ": \"float maxcomponentvalue\" (pbrt's sample clamp) " +
                                      "is ignored: strahl renders the unclamped image");
            if (const Parameter* iso = typed(f, "iso", {"float"}); iso && iso->numbers[0] != 100.0)
                bad(*iso, "only ISO 100 (pbrt's default, the image as rendered) is supported");
            if (const Parameter* e = typed(f, "exposuretime", {"float"}); e && e->numbers[0] != 1.0)
                bad(*e, "only exposure time 1 is supported");
            if (const Parameter* wb = typed(f, "whitebalance", {"float"}); wb && wb->numbers[0] != 0.0)
                bad(*wb, "white balancing is not supported");
            if (const Parameter* sensor = typed(f, "sensor", {"string"}); sensor && sensor->strings[0] != "cie1931")
                bad(*sensor, "only the \"cie1931\" sensor is supported");
            refuseUnread(f);
        }
        film["width"] = width_;
        film["height"] = height_;
        const fs::path out = fs::path(output).is_absolute() ? fs::path(output) : cwd_ / output;
        film["outputs"] = {out.string()};
        if (s_.filter) {
            const Entity& f = *s_.filter;
            // strahl's filters keep each pixel the mean of its own samples
            // (filter importance sampling), as pbrt-v4 does.
            if (f.type == "box") film["filter"] = "box";
            else if (f.type == "gaussian") film["filter"] = "gaussian";
            else if (f.type == "triangle") film["filter"] = "tent";
            else unsupported(f, "this pixel filter is not supported (box, gaussian, triangle)");
            const Parameter* xr = typed(f, "xradius", {"float"});
            const Parameter* yr = typed(f, "yradius", {"float"});
            if (xr || yr) {
                const double x = xr ? xr->numbers[0] : -1.0, y = yr ? yr->numbers[0] : x;
                if (xr && yr && x != y) unsupported(f, "different x and y radii are not supported");
                film["filter"] = {{"type", film["filter"]}, {"radius", xr ? x : y}};
            }
            // strahl's Gaussian keeps sigma 0.5 whatever its radius, as pbrt's default.
            if (const Parameter* sigma = typed(f, "sigma", {"float"}); sigma && sigma->numbers[0] != 0.5)
                bad(*sigma, "a Gaussian sigma other than 0.5 is not supported");
            refuseUnread(f);
        } else {
            // pbrt-v4's default filter: a Gaussian of radius 1.5 and sigma 0.5.
            film["filter"] = "gaussian";
        }
        doc_["film"] = film;
    }

    void camera() {
        json cam = json::object();
        // The camera frame in pbrt's world, then mirrored (pbrt_mapping.h).
        const glm::dmat4 worldFromCamera = glm::inverse(s_.cameraFromWorld);
        const glm::dvec3 eye = transformPoint(worldFromCamera, glm::dvec3(0.0));
        const glm::dvec3 dir = transformVector(worldFromCamera, glm::dvec3(0, 0, 1));
        const glm::dvec3 up = transformVector(worldFromCamera, glm::dvec3(0, 1, 0));
        mirror_ = glm::determinant(glm::dmat3(worldFromCamera)) > 0.0 ? kMirrorX : glm::dmat4(1.0);
        cam["eye"] = vec3(transformPoint(mirror_, eye));
        cam["back"] = vec3(-transformVector(mirror_, dir));
        cam["up"] = vec3(transformVector(mirror_, up));
        if (std::abs(glm::length(dir) - 1.0) > 1e-6 || std::abs(glm::length(up) - 1.0) > 1e-6 ||
            std::abs(glm::dot(dir, up)) > 1e-6)
            fail(s_.camera ? s_.camera->place.text() : label(),
                 ": Camera: the camera transform scales or shears; only rotations, mirrors and translations are supported");
        const double aspect = static_cast<double>(width_) / height_;
        // pbrt's screen window: [-aspect, aspect] x [-1, 1] for a wide image,
        // [-1, 1] x [-1/aspect, 1/aspect] for a tall one.
        std::array<double, 4> window = aspect >= 1.0 ? std::array<double, 4>{-aspect, aspect, -1.0, 1.0}
                                                     : std::array<double, 4>{-1.0, 1.0, -1.0 / aspect, 1.0 / aspect};
        std::string type = "perspective";
        double fov = 90.0, lensRadius = 0.0, focus = 1e6;
        std::array<double, 2> shutter = {0.0, 1.0};  // in pbrt's time
        if (s_.camera) {
            const Entity& c = *s_.camera;
            type = c.type;
            if (type != "perspective" && type != "orthographic")
                unsupported(c, "only the perspective and orthographic cameras are supported");
            if (const Parameter* w = typed(c, "screenwindow", {"float"})) {
                if (w->numbers.size() != 4) bad(*w, "expected four numbers");
                window = {w->numbers[0], w->numbers[1], w->numbers[2], w->numbers[3]};
                if (!(window[0] < 0 && 0 < window[1] && window[2] < 0 && 0 < window[3]))
                    bad(*w, "strahl needs a window around the axis (x0 < 0 < x1, y0 < 0 < y1)");
            }
            if (type == "perspective") fov = number(c, "fov", 90.0);
            lensRadius = number(c, "lensradius", 0.0);
            focus = number(c, "focaldistance", 1e6);
            shutter = {number(c, "shutteropen", 0.0), number(c, "shutterclose", 1.0)};
            if (!(shutter[0] <= shutter[1])) unsupported(c, "the shutter must open before it closes");
            if (const Parameter* a = param(c, "frameaspectratio"))
                bad(*a, "a frame aspect ratio other than the image's is not supported");
            refuseUnread(c);
            if (!(fov > 0.0 && fov < 180.0)) unsupported(c, "fov must lie in (0, 180)");
            if (lensRadius < 0.0 || !(focus > 0.0)) unsupported(c, "lensradius must be >= 0 and focaldistance > 0");
        }
        cam["type"] = type;
        if (type == "perspective") {
            // Rays leave pbrt's camera at its centre; strahl's start on the image
            // plane at focal_distance d, so d is small against any scene: 10⁻⁴
            // of the focus distance, at most 10⁻³ units.
            const double d = std::min(1e-3, focus * 1e-4);
            const double t = std::tan(glm::radians(fov) / 2.0) * d;
            cam["focal_distance"] = d;
            cam["window"] = {window[0] * t, window[1] * t, window[2] * t, window[3] * t};
        } else {
            cam["window"] = {window[0], window[1], window[2], window[3]};
        }
        if (lensRadius > 0.0) {
            cam["aperture_radius"] = lensRadius;
            cam["focus_distance"] = focus;
        }
        // strahl's frame time runs from the start transform (0) to the end
        // one (1), TransformTimes in pbrt's time; pbrt clamps times outside.
        const double t0 = s_.transformStart, t1 = s_.transformEnd;
        if (t1 > t0) {
            auto frame = [&](double t) { return std::clamp((t - t0) / (t1 - t0), 0.0, 1.0); };
            const std::array<double, 2> frameShutter = {frame(shutter[0]), frame(shutter[1])};
            if (frameShutter != std::array<double, 2>{0.0, 1.0}) cam["shutter"] = {frameShutter[0], frameShutter[1]};
        }
        doc_["camera"] = cam;
    }

    void render() {
        render_["integrator"] = "path";
        render_["max_depth"] = 5;
        render_["spp"] = 16;
        if (s_.sampler) {
            const Entity& smp = *s_.sampler;
            // Every sampler estimates the same image; strahl uses its own.
            const int spp = integer(smp, "pixelsamples", 16);
            if (spp < 1 || spp > 65536) unsupported(smp, "pixelsamples must lie in 1 ... 65536");
            render_["spp"] = spp;
            for (const char* ignored : {"seed", "randomization", "jitter", "xsamples", "ysamples", "dimensions"})
                param(smp, ignored);
            refuseUnread(smp);
        }
        if (s_.integrator) {
            const Entity& i = *s_.integrator;
            static const std::set<std::string> pathLike = {"path", "volpath", "bdpt", "mlt", "sppm", "lightpath",
                                                           "simplepath", "simplevolpath", "randomwalk"};
            if (i.type == "ambientocclusion") {
                render_["integrator"] = "ao";
                render_.erase("max_depth");
                if (boolean(i, "cossample", true) == false)
                    unsupported(i, "cossample false is not supported (strahl samples the cosine)");
                render_["ao_distance"] = number(i, "maxdistance", std::numeric_limits<float>::max() / 2);
            } else if (pathLike.count(i.type)) {
                const int depth = integer(i, "maxdepth", 5);
                if (depth < 0 || depth > 1024) unsupported(i, "maxdepth must lie in 0 ... 1024");
                render_["max_depth"] = depth;
                if (const Parameter* ls = typed(i, "lightsampler", {"string"})) {
                    const std::string& v = ls->strings[0];
                    if (v != "bvh" && v != "power" && v != "uniform") bad(*ls, "expected bvh, power or uniform");
                    render_["light_selection"] = v;
                }
                if (boolean(i, "regularize", false)) unsupported(i, "regularize is not supported");
                // How the estimator samples, not what it estimates:
                for (const char* ignored : {"samplelights", "samplebsdf", "bootstrapsamples", "chains",
                                            "mutationsperpixel", "largestepprobability", "sigma",
                                            "visualizestrategies", "visualizeweights", "photonsperiteration",
                                            "iterations", "radius", "seed"})
                    param(i, ignored);
                if (i.type != "path" && i.type != "volpath" && i.type != "simplepath")
                    meshio::reportWarning(i.place.text() + ": Integrator \"" + i.type +
                                          "\": rendered by strahl's path tracer (the same image, other noise)");
            } else {
                unsupported(i, "this integrator is not supported");
            }
            refuseUnread(i);
        }
    }

    // --- spectra and textures -------------------------------------------
    enum class Use { Reflectance, Unbounded, Light };

    // An RGB colour from an rgb, spectrum or blackbody parameter.
    glm::dvec3 spectrum(const Parameter& p, Use use) const {
        if (p.type == "rgb") {
            if (p.numbers.size() != 3) bad(p, "expected three numbers");
            const glm::dvec3 c(p.numbers[0], p.numbers[1], p.numbers[2]);
            if (c.r < 0 || c.g < 0 || c.b < 0) bad(p, "a colour must not be negative");
            if (use == Use::Reflectance && (c.r > 1 || c.g > 1 || c.b > 1))
                bad(p, "a reflectance above 1 is not physical (pbrt clamps it; give at most 1)");
            return c;
        }
        if (p.type == "blackbody") {
            if (use != Use::Light) bad(p, "a blackbody spectrum is only for lights");
            return blackbody(p, p.numbers[0]);
        }
        if (p.type == "float" && use == Use::Unbounded && p.numbers.size() == 1) return glm::dvec3(p.numbers[0]);
        if (p.type != "spectrum") bad(p, "expected an rgb, spectrum or blackbody value");
        std::vector<double> wl, v;
        if (!p.strings.empty()) {
            const std::string& name = p.strings[0];
            if (name == "stdillum-D65") {
                if (use != Use::Light) bad(p, "an illuminant is only for lights");
                return glm::dvec3(1.0);  // the white of sRGB, at luminance 1
            }
            for (const NamedIlluminant& i : kIlluminants)
                if (name == i.name) {
                    if (use != Use::Light) bad(p, "an illuminant is only for lights");
                    return chromaticityToLinearSrgb(i.x, i.y);
                }
            if (name.rfind("metal-", 0) == 0 || name.rfind("glass-", 0) == 0 || name.rfind("stdillum-", 0) == 0 ||
                name.rfind("illum-", 0) == 0 ||
                name.rfind("canon_", 0) == 0 || name.rfind("nikon_", 0) == 0 || name.rfind("sony_", 0) == 0)
                bad(p, "the named spectrum '" + name + "' is not supported here (docs/pbrt.md)");
            const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : s_.folder / name;
            std::error_code ec;
            std::ifstream in;
            if (fs::is_regular_file(path, ec)) in.open(path);
            if (!in) bad(p, "no named spectrum and no file '" + name + "' (looked at " + path.string() + ")");
            std::vector<double> numbers;
            std::string line;
            while (std::getline(in, line)) {
                line = line.substr(0, line.find('#'));
                std::istringstream words(line);
                double x;
                while (words >> x) numbers.push_back(x);
                if (!words.eof()) bad(p, path.string() + ": not a list of numbers");
            }
            spectrumPairs(p, numbers, wl, v);
        } else {
            spectrumPairs(p, p.numbers, wl, v);
        }
        glm::dvec3 rgb = spectrumToLinearSrgb(wl, v, use == Use::Light ? SpectrumUse::Emission : SpectrumUse::Reflectance);
        rgb = glm::max(rgb, glm::dvec3(0.0));
        if (use == Use::Reflectance) rgb = glm::min(rgb, glm::dvec3(1.0));
        if (use == Use::Light) {
            // pbrt-v4 divides a light's spectrum by its luminance (only an rgb
            // light keeps its magnitude, through its illuminant).
            const double y = luminance(rgb);
            if (!(y > 0.0)) bad(p, "the spectrum has no luminance");
            rgb /= y;
        }
        return rgb;
    }

    const Texture& texture(const Parameter& p, bool spectral) const {
        if (p.strings.size() != 1) bad(p, "expected one texture name");
        const auto& table = spectral ? s_.spectrumTextures : s_.floatTextures;
        const auto found = table.find(p.strings[0]);
        if (found == table.end())
            bad(p, std::string("no ") + (spectral ? "spectrum" : "float") + " texture named \"" + p.strings[0] + "\"");
        return found->second;
    }

    // pbrt's (u, v) mapping parameters as strahl's uv_transform, in the
    // coordinates strahl's image lookups use, (s, t) = (u, 1 − v): pbrt
    // reads the image at (su·u + du, 1 − (sv·v + dv)).
    static void uvMapping(const Entity& t, json& out) {
        if (text(t, "mapping", "uv") != "uv") unsupported(t, "only the \"uv\" texture mapping is supported");
        const double su = number(t, "uscale", 1.0), sv = number(t, "vscale", 1.0);
        const double du = number(t, "udelta", 0.0), dv = number(t, "vdelta", 0.0);
        if (su != 1.0 || sv != 1.0 || du != 0.0 || dv != 0.0)
            out["uv_transform"] = {{su, 0.0, du}, {0.0, sv, 1.0 - sv - dv}};
    }

    json imageTexture(const Texture& tex, bool spectral) const {
        const Entity& t = tex.entity;
        const Parameter* f = typed(t, "filename", {"string"});
        if (!f) unsupported(t, "needs \"string filename\"");
        const std::string path = file(*f);
        json out = {{"texture", path}};
        // 8-bit PNGs hold sRGB-encoded values by default in pbrt, other files linear.
        std::string lower = path;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const bool png = lower.size() > 4 && lower.substr(lower.size() - 4) == ".png";
        const std::string encoding = text(t, "encoding", png ? "sRGB" : "linear");
        if (encoding != "sRGB" && encoding != "linear") unsupported(t, "encoding \"" + encoding + "\" is not supported (sRGB, linear)");
        // strahl decodes 8-bit colour images and reads scalar ones as stored.
        if (spectral && encoding == "linear") out["raw"] = true;
        if (!spectral && encoding == "sRGB") out["raw"] = false;
        const double scale = number(t, "scale", 1.0);
        if (scale != 1.0) out["scale"] = scale;
        if (boolean(t, "invert", false)) unsupported(t, "invert is not supported");
        const std::string wrap = text(t, "wrap", "repeat");
        if (wrap == "clamp") out["wrap"] = "clamp";
        else if (wrap != "repeat") unsupported(t, "wrap \"" + wrap + "\" is not supported (repeat, clamp)");
        const std::string filter = text(t, "filter", "bilinear");
        if (filter == "bilinear") out["filter"] = "bilinear";
        else if (filter == "point") out["filter"] = "nearest";
        else if (filter != "trilinear" && filter != "ewa" && filter != "EWA")
            unsupported(t, "filter \"" + filter + "\" is not supported");
        param(t, "maxanisotropy");
        uvMapping(t, out);
        if (!spectral) out["channel"] = "r";
        return out;
    }

    // A texture as a strahl colour (spectral) or scalar input.
    json textureValue(const Parameter& p, bool spectral, Use use) const {
        const Texture& tex = texture(p, spectral);
        const Entity& t = tex.entity;
        json out;
        if (t.type == "imagemap") {
            out = imageTexture(tex, spectral);
        } else if (t.type == "constant") {
            const Parameter* v = param(t, "value");
            if (!v) unsupported(t, "needs \"value\"");
            out = spectral ? color(spectrum(*v, use)) : json(scalarOf(*v));
        } else if (t.type == "scale") {
            const Parameter* inner = param(t, "tex");
            const Parameter* s = param(t, "scale");
            const double factor = s ? constantScalar(*s) : 1.0;
            if (!inner) out = spectral ? json(1.0) : json(1.0);
            else out = input(*inner, spectral, use);
            out = scaled(out, factor, t);
        } else if (t.type == "checkerboard") {
            if (!spectral) unsupported(t, "a float checkerboard is not supported");
            if (integer(t, "dimension", 2) != 2) unsupported(t, "only the 2D checkerboard is supported");
            const Parameter* t1 = param(t, "tex1");
            const Parameter* t2 = param(t, "tex2");
            const glm::dvec3 c1 = t1 ? constantColor(*t1, use) : glm::dvec3(1.0);
            const glm::dvec3 c2 = t2 ? constantColor(*t2, use) : glm::dvec3(0.0);
            if (text(t, "mapping", "uv") != "uv") unsupported(t, "only the \"uv\" texture mapping is supported");
            const double su = number(t, "uscale", 1.0), sv = number(t, "vscale", 1.0);
            if (number(t, "udelta", 0.0) != 0.0 || number(t, "vdelta", 0.0) != 0.0)
                unsupported(t, "udelta and vdelta are not supported on a checkerboard");
            // pbrt: tex1 where ⌊su·u⌋ + ⌊sv·v⌋ is even. strahl's checkerboard
            // of scale k has squares 1/(2k) wide, counted from the top (1 − v),
            // so k = s/2; flipping v swaps the parity when sv is even.
            if (!(su > 0 && sv > 0) || sv != std::floor(sv))
                unsupported(t, "a checkerboard needs positive scales and a whole vscale");
            const bool swap = std::fmod(sv, 2.0) == 0.0;
            out = {{"checkerboard", {{"color0", color(swap ? c2 : c1)}, {"color1", color(swap ? c1 : c2)},
                                     {"scale", {su / 2.0, sv / 2.0}}}}};
        } else if (t.type == "mix") {
            // pbrt-v4: (1 − amount) tex1 + amount tex2, each a value or a
            // texture (tex1 0, tex2 1, amount 0.5 by default): strahl's mix.
            const Parameter* t1 = param(t, "tex1");
            const Parameter* t2 = param(t, "tex2");
            const Parameter* amount = param(t, "amount");
            json a = t1 ? input(*t1, spectral, use) : json(0.0);
            json b = t2 ? input(*t2, spectral, use) : json(1.0);
            json blend = amount ? input(*amount, false, Use::Unbounded) : json(0.5);
            if (blend.is_number() && !(blend.get<double>() >= 0.0 && blend.get<double>() <= 1.0))
                bad(*amount, "an amount outside [0, 1] is not supported");
            out = {{"mix", json::array({std::move(a), std::move(b)})}, {"amount", std::move(blend)}};
        } else {
            unsupported(t, "this texture is not supported (imagemap, constant, scale, mix, checkerboard)");
        }
        refuseUnread(t);
        return out;
    }

    static json scaled(json value, double factor, const Entity& where) {
        if (factor == 1.0) return value;
        if (value.is_number()) return value.get<double>() * factor;
        if (value.is_array()) {
            for (json& c : value) c = c.get<double>() * factor;
            return value;
        }
        if (value.contains("checkerboard")) {
            value["scale"] = factor;
            return value;
        }
        if (value.contains("scale")) {
            if (value["scale"].is_number()) value["scale"] = value["scale"].get<double>() * factor;
            else unsupported(where, "a scale of a scaled texture is not supported");
        } else {
            value["scale"] = factor;
        }
        return value;
    }

    double scalarOf(const Parameter& p) const {
        if (p.type != "float" || p.numbers.size() != 1) bad(p, "expected one float");
        return p.numbers[0];
    }
    double constantScalar(const Parameter& p) const {
        if (p.type == "texture") {
            const Texture& tex = texture(p, false);
            if (tex.entity.type != "constant") bad(p, "only a constant texture is supported here");
            const Parameter* v = param(tex.entity, "value");
            if (!v) unsupported(tex.entity, "needs \"value\"");
            refuseUnread(tex.entity);
            return scalarOf(*v);
        }
        return scalarOf(p);
    }
    glm::dvec3 constantColor(const Parameter& p, Use use) const {
        if (p.type == "texture") {
            const Texture& tex = texture(p, true);
            if (tex.entity.type != "constant") bad(p, "only constant colours are supported here");
            const Parameter* v = param(tex.entity, "value");
            if (!v) unsupported(tex.entity, "needs \"value\"");
            refuseUnread(tex.entity);
            return spectrum(*v, use);
        }
        return spectrum(p, use);
    }

    // A material input: a constant or a texture.
    json input(const Parameter& p, bool spectral, Use use) const {
        if (p.type == "texture") return textureValue(p, spectral, use);
        if (spectral) return color(spectrum(p, use));
        return scalarOf(p);
    }
    std::optional<json> colorInput(const Entity& e, const std::string& name, Use use = Use::Reflectance) const {
        const Parameter* p = param(e, name);
        if (!p) return std::nullopt;
        return input(*p, true, use);
    }
    std::optional<json> floatInput(const Entity& e, const std::string& name) const {
        const Parameter* p = param(e, name);
        if (!p) return std::nullopt;
        return input(*p, false, Use::Unbounded);
    }

    // --- materials ------------------------------------------------------
    // pbrt's roughness as strahl's: pbrt's GGX alpha is the roughness itself,
    // or √roughness when remaproughness (the default) is on; strahl's
    // roughness is √alpha.
    json roughness(const Entity& m, json value, bool remap) const {
        auto convert = [&](double r) {
            if (r < 0.0) unsupported(m, "roughness must not be negative");
            const double alpha = remap ? std::sqrt(r) : r;
            if (alpha > 1.0) unsupported(m, "a GGX alpha above 1 is not supported");
            return std::sqrt(alpha);
        };
        if (value.is_number()) return convert(value.get<double>());
        unsupported(m, "a textured roughness is not supported (strahl's roughness is √alpha, a texture cannot be remapped)");
    }

    // Sets strahl's `key` (or key_u and key_v when they differ) from pbrt's
    // roughness/uroughness/vroughness, after `prefix` ("conductor." in a
    // coatedconductor).
    void microfacets(const Entity& m, json& out, double fallback, const std::string& prefix = "",
                     const std::string& key = "roughness") const {
        const bool remap = boolean(m, "remaproughness", true);
        const std::optional<json> r = floatInput(m, prefix + "roughness");
        const std::optional<json> u = floatInput(m, prefix + "uroughness");
        const std::optional<json> v = floatInput(m, prefix + "vroughness");
        const json ru = u ? *u : (r ? *r : json(fallback));
        const json rv = v ? *v : (r ? *r : json(fallback));
        const json a = roughness(m, ru, remap), b = roughness(m, rv, remap);
        if (a == b) {
            if (a.get<double>() != 0.0) out[key] = a;
        } else {
            out[key + "_u"] = a;
            out[key + "_v"] = b;
        }
    }

    double eta(const Entity& m, const std::string& name, double fallback) const {
        const Parameter* p = param(m, name);
        if (!p) return fallback;
        if (p->type == "float") return scalarOf(*p);
        if (p->type == "spectrum" && !p->strings.empty()) {
            for (const NamedGlass& g : kGlasses)
                if (p->strings[0] == g.name) return g.ior;
            bad(*p, "unknown named spectrum for an index of refraction (docs/pbrt.md lists the glasses)");
        }
        if (p->type == "texture") bad(*p, "a textured index of refraction is not supported");
        bad(*p, "a spectrally varying index of refraction is not supported (give a float)");
    }

    // eta and k from pbrt's eta and k (after `prefix`: "conductor." in a
    // coatedconductor) or reflectance.
    json conductorEtaK(const Entity& m, json& out, const std::string& prefix = "") const {
        const Parameter* etaP = param(m, prefix + "eta");
        const Parameter* kP = param(m, prefix + "k");
        const Parameter* refl = param(m, "reflectance");
        if (refl && (etaP || kP)) unsupported(m, "give either reflectance or eta and k");
        if (refl) {
            // pbrt: eta 1 and k = 2√r / √(1 − r), per channel.
            const glm::dvec3 r = constantColor(*refl, Use::Reflectance);
            const glm::dvec3 k = 2.0 * glm::sqrt(r) / glm::sqrt(glm::max(1.0 - r, glm::dvec3(1e-4)));
            out["eta"] = 1.0;
            out["k"] = color(k);
            return out;
        }
        auto metal = [&](const Parameter* p, const char* which, const std::string& fallback) -> glm::dvec3 {
            std::string name = fallback;
            if (p) {
                if (p->type == "spectrum" && !p->strings.empty()) name = p->strings[0];
                else if (p->type == "texture") bad(*p, "a textured eta or k is not supported");
                else return spectrum(*p, Use::Unbounded);
            }
            // metal-Cu-eta: Mitsuba's measured data for the same metal, reduced
            // to RGB (docs/mitsuba.md).
            const std::string suffix = std::string("-") + which;
            if (name.rfind("metal-", 0) == 0 && name.size() > 6 + suffix.size() &&
                name.substr(name.size() - suffix.size()) == suffix) {
                const std::string element = name.substr(6, name.size() - 6 - suffix.size());
                if (const auto c = mitsuba::namedConductor(element)) return which[0] == 'e' ? c->eta : c->k;
            }
            if (p) bad(*p, "unknown named spectrum '" + name + "' (docs/pbrt.md lists the metals)");
            fail("internal: no data for ", name);
        };
        out["eta"] = color(metal(etaP, "eta", "metal-Cu-eta"));
        out["k"] = color(metal(kP, "k", "metal-Cu-k"));
        return out;
    }

    // A pbrt material as a strahl material object (no name): its type and keys.
    json materialObject(const Entity& m, int depth) {
        if (depth > 16) unsupported(m, "mix materials nested deeper than 16");
        json out;
        param(m, "type");
        if (m.type == "diffuse") {
            out = {{"type", "diffuse"}};
            out["color"] = colorInput(m, "reflectance").value_or(json(0.5));
        } else if (m.type == "coateddiffuse") {
            // A Lambert base under a dielectric coat with the inter-reflections
            // between them: strahl's plastic with the base colour in the series.
            out = {{"type", "plastic"}, {"nonlinear", true}};
            out["color"] = colorInput(m, "reflectance").value_or(json(0.5));
            const double ior = eta(m, "eta", 1.5);
            if (!(ior > 1.0 && ior <= 4.0)) unsupported(m, "eta must lie in (1, 4]");
            out["ior"] = ior;
            microfacets(m, out, 0.0);
            if (out.contains("roughness_u")) unsupported(m, "an anisotropic coat is not supported");
            if (out.contains("roughness")) out["coat_transmittance"] = "microfacet";
            if (const Parameter* a = param(m, "albedo"); a && glm::length(constantColor(*a, Use::Reflectance)) > 0.0)
                bad(*a, "a scattering medium in the coat is not supported (albedo must be 0)");
            param(m, "g");
            // thickness only matters with albedo (docs/pbrt.md); maxdepth and
            // nsamples tune pbrt's stochastic evaluation.
            for (const char* ignored : {"thickness", "maxdepth", "nsamples"}) param(m, ignored);
        } else if (m.type == "coatedconductor") {
            // A conductor under a dielectric coat, with the layer's absorption
            // (pbrt's thickness at albedo 0: exp(-thickness / cos) per crossing).
            out = {{"type", "coated_conductor"}};
            conductorEtaK(m, out, "conductor.");
            microfacets(m, out, 0.0, "conductor.");
            const double ior = eta(m, "interface.eta", 1.5);
            if (!(ior > 1.0 && ior <= 4.0)) unsupported(m, "interface.eta must lie in (1, 4]");
            out["ior"] = ior;
            microfacets(m, out, 0.0, "interface.", "coat_roughness");
            if (out.contains("roughness_u") || out.contains("coat_roughness_u"))
                unsupported(m, "an anisotropic coated conductor is not supported");
            if (const Parameter* a = param(m, "albedo"); a && glm::length(constantColor(*a, Use::Reflectance)) > 0.0)
                bad(*a, "a scattering medium in the coat is not supported (albedo must be 0)");
            const double thickness = number(m, "thickness", 0.01);
            if (!(thickness >= 0.0 && thickness <= 100.0)) unsupported(m, "thickness must lie in [0, 100]");
            if (thickness > 0.0) out["thickness"] = thickness;
            param(m, "g");
            for (const char* ignored : {"maxdepth", "nsamples"}) param(m, ignored);
        } else if (m.type == "conductor") {
            out = {{"type", "conductor"}};
            conductorEtaK(m, out);
            microfacets(m, out, 0.0);
        } else if (m.type == "dielectric" || m.type == "thindielectric") {
            const double ior = eta(m, "eta", 1.5);
            if (!(ior > 1.0 && ior <= 4.0)) unsupported(m, "eta must lie in (1, 4] (strahl has no index below 1)");
            if (m.type == "thindielectric") {
                out = {{"type", "thin_dielectric"}, {"ior", ior}};
            } else {
                out = {{"type", "dielectric"}, {"ior", ior}};
                microfacets(m, out, 0.0);
                if (out.contains("roughness_u")) unsupported(m, "an anisotropic rough dielectric is not supported");
            }
        } else if (m.type == "diffusetransmission") {
            out = {{"type", "diffuse_transmission"}};
            const double scale = number(m, "scale", 1.0);
            if (!(scale >= 0.0)) unsupported(m, "scale must not be negative");
            out["color"] = scaled(colorInput(m, "reflectance").value_or(json(0.25)), scale, m);
            out["transmittance"] = scaled(colorInput(m, "transmittance").value_or(json(0.25)), scale, m);
        } else if (m.type == "mix") {
            const Parameter* names = typed(m, "materials", {"string"});
            if (!names || names->strings.size() != 2) unsupported(m, "needs \"string materials\" with two names");
            json parts = json::array();
            for (const std::string& name : names->strings) {
                const auto found = s_.namedMaterials.find(name);
                if (found == s_.namedMaterials.end()) bad(*names, "no material named \"" + name + "\"");
                const Entity& part = s_.materials[static_cast<size_t>(found->second)];
                json object = materialObject(part, depth + 1);
                for (const char* common : {"normal_map", "opacity"})
                    if (object.contains(common)) unsupported(part, "a normal map inside a mix is not supported");
                parts.push_back(object);
            }
            out = {{"type", "blend"}, {"materials", parts}};
            // pbrt picks the second material with probability amount.
            const std::optional<json> amount = floatInput(m, "amount");
            out["weight"] = amount.value_or(json(0.5));
        } else if (m.type == "hair") {
            // pbrt's precedence: sigma_a, else reflectance, else melanin
            // (eumelanin 1.3 when nothing is given).
            out = {{"type", "hair"}};
            const Parameter* sigma = param(m, "sigma_a");
            const std::optional<json> reflectance = colorInput(m, "reflectance");
            const Parameter* eu = param(m, "eumelanin");
            const Parameter* pheo = param(m, "pheomelanin");
            if (sigma) {
                out["sigma_a"] = color(spectrum(*sigma, Use::Unbounded));
            } else if (reflectance) {
                out["color"] = *reflectance;
            } else if (eu || pheo) {
                out["eumelanin"] = number(m, "eumelanin", 0.0);
                out["pheomelanin"] = number(m, "pheomelanin", 0.0);
            }
            out["ior"] = eta(m, "eta", 1.55);
            out["beta_m"] = number(m, "beta_m", 0.3);
            out["beta_n"] = number(m, "beta_n", 0.3);
            out["alpha"] = number(m, "alpha", 2.0);
        } else if (m.type == "interface") {
            // A boundary between media, invisible to light.
            out = {{"type", "diffuse"}, {"opacity", 0}};
        } else {
            unsupported(m, "this material is not supported (diffuse, coateddiffuse, coatedconductor, conductor, dielectric, "
                           "thindielectric, diffusetransmission, hair, mix, interface)");
        }
        if (const Parameter* n = param(m, "normalmap")) {
            if (n->type != "string") bad(*n, "expected a file name");
            out["normal_map"] = file(*n);
        }
        if (const Parameter* d = m.params.find("displacement")) bad(*d, "displacement is not supported");
        refuseUnread(m);
        return out;
    }

    // The strahl material for a shape: its pbrt material, with the shape's
    // area light as emission and its alpha as opacity. Made once per
    // combination.
    std::string material(const Shape& shape) {
        const Entity& m = s_.materials[static_cast<size_t>(shape.material)];
        std::string key = std::to_string(shape.material);
        std::string name = m.directive == "MakeNamedMaterial" ? std::string()
                           : shape.material == 0      ? std::string("pbrt-default")
                                                      : m.type + "@" + m.place.text();
        if (name.empty())
            for (const auto& [n, i] : s_.namedMaterials)
                if (i == shape.material) name = n;
        json emission;
        bool twoSided = false;
        if (shape.areaLight >= 0) {
            const Entity& light = s_.areaLights[static_cast<size_t>(shape.areaLight)];
            key += "+light" + std::to_string(shape.areaLight);
            name += "+" + light.type + "@" + light.place.text();
            emission = areaEmission(light, shape, twoSided);
        }
        json opacity;
        if (const Parameter* a = shape.entity.params.find("alpha")) {
            a->used = true;
            opacity = a->type == "texture" ? textureValue(*a, false, Use::Unbounded) : json(scalarOf(*a));
            if (opacity.is_number() && opacity.get<double>() == 1.0) opacity = nullptr;
            if (!opacity.is_null()) {
                key += "+alpha" + opacity.dump();
                name += "+alpha@" + a->place.text();
            }
        }
        if (const auto found = madeMaterials_.find(key); found != madeMaterials_.end()) return found->second;
        json object = materialObject(m, 0);
        if (!emission.is_null()) {
            if (!opacity.is_null()) unsupported(shape.entity, "an area light on a shape with alpha is not supported");
            object["emission"] = emission;
            if (twoSided) object["two_sided"] = true;
        }
        if (!opacity.is_null()) {
            if (object.contains("opacity")) unsupported(shape.entity, "alpha on an interface material");
            object["opacity"] = opacity;
        }
        std::string unique = name;
        for (int i = 2; !materialNames_.insert(unique).second || unique == "default"; ++i)
            unique = name + "#" + std::to_string(i);
        object["name"] = unique;
        materials_.push_back(object);
        madeMaterials_[key] = unique;
        return unique;
    }

    json areaEmission(const Entity& light, const Shape& shape, bool& twoSided) const {
        if (light.type != "diffuse") unsupported(light, "only the \"diffuse\" area light is supported");
        const Parameter* L = param(light, "L");
        glm::dvec3 radiance = L ? spectrum(*L, Use::Light) : glm::dvec3(1.0);
        double scale = number(light, "scale", 1.0);
        twoSided = boolean(light, "twosided", false);
        // An image: pbrt-v4 emits scale × the image's RGB at the point's
        // (u, 1 − v), bilinear, clamped at the borders — strahl's textured
        // emission (a triangle light per triangle, sampled by its texels).
        const Parameter* image = typed(light, "filename", {"string"});
        if (image && L) unsupported(light, "give either L or filename");
        if (const Parameter* power = typed(light, "power", {"float"})) {
            // pbrt: the radiance that gives each triangle this power (W), k_e
            // = π (2π two-sided) × its area, times an image's mean
            // luminance; an rgb radiance keeps its colour.
            const double area = shapeArea(shape);
            double k = (twoSided ? 2.0 : 1.0) * glm::pi<double>() * area;
            if (!(area > 0.0)) unsupported(shape.entity, "power needs a shape with an area");
            if (image) {
                const fs::path name = file(*image);
                k *= meanImageLuminance(name.is_absolute() ? name : s_.folder / name);
                if (!(k > 0.0)) bad(*image, "the image is black: no scale gives it a power");
            }
            scale *= power->numbers[0] / k;
        }
        refuseUnread(light);
        if (image) {
            json out = {{"texture", file(*image)}, {"wrap", "clamp"}, {"filter", "bilinear"}};
            if (scale != 1.0) out["scale"] = scale;
            return out;
        }
        return color(radiance * scale);
    }

    // The area that an area light's power is divided by. pbrt-v4 makes one
    // light per triangle, each normalised by its own area, so a mesh of n
    // triangles given power P emits n P, each triangle with radiance
    // P / (k area_i). strahl's emission is one radiance per material: the
    // triangles must share one area (a quad's two halves, a regular grid),
    // which is returned; a mesh whose triangle areas differ is refused.
    double shapeArea(const Shape& shape) const {
        const Entity& e = shape.entity;
        // The quadrics' areas are pbrt's Shape::Area(), in object space (the
        // transform does not enter, as in pbrt).
        const double pi = glm::pi<double>();
        if (e.type == "sphere") {
            const double r = number(e, "radius", 1.0);
            return 4.0 * pi * r * r;
        }
        if (e.type == "disk") {
            const double r = number(e, "radius", 1.0), ri = number(e, "innerradius", 0.0);
            return pi * (r * r - ri * ri);
        }
        if (e.type == "cylinder") {
            const double r = number(e, "radius", 1.0);
            return 2.0 * pi * r * (number(e, "zmax", 1.0) - number(e, "zmin", -1.0));
        }
        if (e.type == "bilinearmesh") return patchArea(shape);
        if (e.type == "plymesh") return plyArea(shape);
        if (e.type != "trianglemesh" && e.type != "loopsubdiv")
            unsupported(e, "an area light given by power needs a trianglemesh, plymesh, loopsubdiv, bilinearmesh, "
                           "sphere, disk or cylinder");
        const Parameter* P = e.params.find("P");
        if (!P) return 0.0;
        const std::vector<uint32_t> indices = pointIndices(e, *P, 3, {0, 1, 2});
        TriangleMesh mesh;
        for (uint32_t i = 0; i < P->numbers.size() / 3; ++i) mesh.positions.emplace_back(worldPoint(shape, *P, i));
        mesh.indices = indices;
        // loopsubdiv: pbrt makes a light of each triangle of the subdivided
        // mesh (its refinement is strahl's, loop_subdivision.h).
        if (e.type == "loopsubdiv") mesh = loopSubdivide(mesh, integer(e, "levels", 3), e.place.text());
        return commonArea(e, triangleAreas(mesh), "triangles");
    }

    static std::vector<double> triangleAreas(const TriangleMesh& mesh) {
        std::vector<double> areas;
        areas.reserve(mesh.triangleCount());
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
                c(mesh.positions[mesh.indices[3 * t + 2]]);
            areas.push_back(0.5 * glm::length(glm::cross(b - a, c - a)));
        }
        return areas;
    }

    // A plymesh's triangle areas in world space: the file is read now. pbrt
    // makes bilinear patches of a PLY's quads, each a light of the power, so
    // a file with quads is refused rather than given twice the power.
    double plyArea(const Shape& shape) const {
        const Entity& e = shape.entity;
        const Parameter* f = typed(e, "filename", {"string"});
        if (!f) return 0.0;
        const fs::path name = f->strings.at(0);
        const fs::path path = name.is_absolute() ? name : s_.folder / name;
        LoadedMesh loaded = loadMeshFile(path);
        if (loaded.mesh.triangleCount() != plyFileFaceCount(path))
            unsupported(e, "an area light given by power on a plymesh with quads is not supported (pbrt makes each "
                           "quad a bilinear patch with that power); give L instead");
        TriangleMesh& mesh = loaded.mesh;
        for (Vec3& p : mesh.positions) p = Vec3(transformPoint(shape.toWorld, glm::dvec3(p)));
        return commonArea(e, triangleAreas(mesh), "triangles");
    }

    // The world-space area of a bilinear mesh's patches: the integral of
    // |df/du x df/dv| by 8 x 8-point Gauss-Legendre quadrature (exact for
    // flat patches up to rounding).
    double patchArea(const Shape& shape) const {
        const Entity& e = shape.entity;
        const Parameter* P = e.params.find("P");
        if (!P) return 0.0;
        const std::vector<uint32_t> corners = pointIndices(e, *P, 4, {0, 1, 2, 3});
        // Gauss-Legendre nodes on [0, 1] (8 points, exact for polynomials of
        // degree 15; |df/du x df/dv| of a twisted patch is a smooth root).
        static const double x[4] = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355, 0.4082826787521751};
        static const double w[4] = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436, 0.1813418916891810};
        std::vector<double> areas;
        for (size_t p = 0; p + 3 < corners.size(); p += 4) {
            glm::dvec3 q[4];  // p00, p10, p01, p11
            for (size_t k = 0; k < 4; ++k) q[k] = worldPoint(shape, *P, corners[p + k]);
            double area = 0.0;
            for (int a = 0; a < 8; ++a) {
                const double u = a < 4 ? x[a] : 1.0 - x[7 - a], wu = a < 4 ? w[a] : w[7 - a];
                for (int b = 0; b < 8; ++b) {
                    const double v = b < 4 ? x[b] : 1.0 - x[7 - b], wv = b < 4 ? w[b] : w[7 - b];
                    const glm::dvec3 du = (1 - v) * (q[1] - q[0]) + v * (q[3] - q[2]);
                    const glm::dvec3 dv = (1 - u) * (q[2] - q[0]) + u * (q[3] - q[1]);
                    area += wu * wv * glm::length(glm::cross(du, dv));
                }
            }
            areas.push_back(area);
        }
        return commonArea(e, areas, "patches");
    }

    // The one area every primitive of a shape has, which an area light's
    // power is divided by: pbrt-v4 makes each triangle (patch) a light of
    // that power, normalised by its own area. strahl's emission is one
    // radiance per material, so the areas must agree; otherwise an error.
    double commonArea(const Entity& e, const std::vector<double>& areas, const char* primitives) const {
        if (areas.empty()) return 0.0;
        const auto [smallest, largest] = std::minmax_element(areas.begin(), areas.end());
        // 10^-4: the rounding of the points, not a difference anyone drew.
        if (*largest > *smallest * (1.0 + 1e-4))
            unsupported(e, concat("an area light given by power on ", primitives,
                                  " that differ in area is not supported (pbrt gives each that power, with its "
                                  "own radiance); give L instead"));
        return *largest;
    }

    // The indices into P of a mesh-like shape, `perPrimitive` to a primitive,
    // each checked; `single` when the shape gives none.
    std::vector<uint32_t> pointIndices(const Entity& e, const Parameter& P, size_t perPrimitive,
                                       std::vector<uint32_t> single) const {
        const size_t points = P.numbers.size() / 3;
        const Parameter* idx = e.params.find("indices");
        if (!idx) {
            if (points != single.size()) unsupported(e, "\"integer indices\" may only be left out for a single primitive");
            return single;
        }
        if (idx->numbers.empty() || idx->numbers.size() % perPrimitive != 0)
            bad(*idx, concat("expected ", perPrimitive, " indices per primitive"));
        std::vector<uint32_t> indices;
        indices.reserve(idx->numbers.size());
        for (double i : idx->numbers) {
            if (!(i >= 0.0 && i < static_cast<double>(points)))
                bad(*idx, concat("index ", i, " is out of range (", points, " points)"));
            indices.push_back(static_cast<uint32_t>(i));
        }
        return indices;
    }

    // An animated CTM (ActiveTransform) as strahl's keyframes: pbrt turns the
    // rotation between the start and end transforms as a rotation (slerp),
    // so one keyframe per 10° of it keeps strahl's linear interpolation
    // within 0.4 % of the radius of pbrt's arc (core/motion.h); `outer`
    // (the mirror of pbrt_mapping.h) applies to every keyframe.
    static json motion(const glm::dmat4& start, const glm::dmat4& end, const glm::dmat4& outer) {
        json keys = json::array();
        for (const Mat4& key : rotationAwareKeyframes(start, end, glm::radians(10.0)))
            keys.push_back(matrixTransform(outer * glm::dmat4(key)));
        return keys;
    }

    glm::dvec3 worldPoint(const Shape& shape, const Parameter& P, uint32_t i) const {
        return transformPoint(shape.toWorld, {P.numbers[3 * size_t(i)], P.numbers[3 * size_t(i) + 1], P.numbers[3 * size_t(i) + 2]});
    }

    // --- shapes ---------------------------------------------------------
    void shape(const Shape& s, bool world, json& into) {
        const Entity& e = s.entity;
        glm::dmat4 local(1.0);  // the shape's own placement before its CTM
        json shape;
        bool hasNormals = false;
        const bool emitter = s.areaLight >= 0;
        const std::string materialName = material(s);
        const bool textured = readsTextures(materialNamed(materials_, materialName));
        if (e.type == "trianglemesh") {
            shape = triangleMesh(e, hasNormals);
        } else if (e.type == "plymesh") {
            const Parameter* f = typed(e, "filename", {"string"});
            if (!f) unsupported(e, "needs \"string filename\"");
            const std::string path = file(*f);
            if (e.params.find("displacement")) bad(*e.params.find("displacement"), "displacement is not supported");
            param(e, "edgelength");
            shape = {{"type", "mesh"}, {"file", path}};
            // Resolved as pbrt resolves it: against the main file's folder.
            hasNormals = plyFileHasVertexNormals(fs::path(path).is_absolute() ? fs::path(path) : s_.folder / path);
        } else if (e.type == "sphere") {
            const double radius = number(e, "radius", 1.0);
            if (!(radius > 0.0)) unsupported(e, "radius must be positive");
            if (number(e, "zmin", -radius) > -radius || number(e, "zmax", radius) < radius ||
                number(e, "phimax", 360.0) < 360.0)
                unsupported(e, "a partial sphere (zmin, zmax, phimax) is not supported");
            local = glm::dmat4(radius);
            local[3][3] = 1.0;
            // Exact as an implicit surface; an emitter (or one turned inside
            // out) becomes a fine mesh, which next-event estimation samples.
            // A textured one is parametrised as pbrt parametrises it, so the
            // textures land where pbrt puts them: u = phi / 2 pi, v = (pi -
            // theta) / pi from the south pole (f's normal points outwards).
            const json surface = textured ? json{{"type", "formula"},
                                                 {"x", "sin(v)*cos(u)"},
                                                 {"y", "sin(v)*sin(u)"},
                                                 {"z", "-cos(v)"},
                                                 {"u", {0, "2*pi"}},
                                                 {"v", {0, "pi"}},
                                                 {"periodic_u", true}}
                                          : json{{"type", "sphere"}, {"radius", 1}};
            if (emitter || s.reverseOrientation)
                shape = {{"type", "parametric"}, {"surface", surface}, {"tessellation", {{"segments", {256, 128}}}}};
            else if (textured)
                shape = {{"type", "parametric"}, {"mode", "direct"}, {"surface", surface}};
            else
                shape = {{"type", "implicit"}, {"surface", surface}};
        } else if (e.type == "disk") {
            const double radius = number(e, "radius", 1.0), inner = number(e, "innerradius", 0.0);
            const double height = number(e, "height", 0.0);
            if (!(radius > 0.0) || inner < 0.0 || inner >= radius) unsupported(e, "needs 0 <= innerradius < radius");
            if (number(e, "phimax", 360.0) < 360.0) unsupported(e, "a partial disk (phimax) is not supported");
            // The annulus in z = height facing +z: the profile from the rim
            // inwards turns about z with the normal up.
            shape = {{"type", "parametric"},
                     {"surface", {{"type", "revolution"}, {"profile", {{radius, height}, {inner, height}}}}},
                     {"tessellation", {{"segments", {256, 1}}}}};
        } else if (e.type == "cylinder") {
            const double radius = number(e, "radius", 1.0);
            const double zmin = number(e, "zmin", -1.0), zmax = number(e, "zmax", 1.0);
            if (!(radius > 0.0) || !(zmin < zmax)) unsupported(e, "needs radius > 0 and zmin < zmax");
            if (number(e, "phimax", 360.0) < 360.0) unsupported(e, "a partial cylinder (phimax) is not supported");
            const json surface = {{"type", "cylinder"}, {"radius", radius}, {"z_min", zmin}, {"z_max", zmax}};
            shape = emitter || s.reverseOrientation
                        ? json{{"type", "parametric"}, {"surface", surface}, {"tessellation", {{"segments", {256, 1}}}}}
                        : json{{"type", "parametric"}, {"mode", "direct"}, {"surface", surface}};
        } else if (e.type == "loopsubdiv") {
            // The control mesh, subdivided by strahl as pbrt does (levels 3 by default).
            const Parameter* idx = typed(e, "indices", {"integer"});
            if (!idx) unsupported(e, "needs \"integer indices\"");
            for (const char* other : {"N", "uv", "S"})
                if (const Parameter* p = e.params.find(other)) bad(*p, "not a parameter of loopsubdiv");
            shape = triangleMesh(e, hasNormals);
            hasNormals = false;  // the subdivided mesh's normals follow its winding, as pbrt's do
            const int levels = integer(e, "levels", 3);
            if (levels < 0 || levels > 8) unsupported(e, "levels must lie in 0 ... 8");
            param(e, "scheme");  // pbrt reads it and always subdivides by Loop's rules
            shape["subdivision"] = {{"scheme", "loop"}, {"levels", levels}};
        } else if (e.type == "bilinearmesh") {
            shape = bilinearMesh(e, hasNormals);
        } else if (e.type == "curve") {
            shape = curve(e);
        } else {
            unsupported(e, "this shape is not supported (trianglemesh, plymesh, bilinearmesh, sphere, disk, "
                           "cylinder, loopsubdiv)");
        }
        const glm::dmat4 outer = world ? mirror_ : glm::dmat4(1.0);
        if (s.toWorldEnd)
            shape["motion"] = motion(s.toWorld * local, *s.toWorldEnd * local, outer);
        else
            shape["transform"] = matrixTransform(outer * s.toWorld * local);
        // pbrt's front is the winding's side transformed, turned around by
        // ReverseOrientation, or with shading normals the side they point to
        // (pbrt ignores ReverseOrientation then); strahl keeps the winding's
        // side through any transform, mirrors included (docs/pbrt.md).
        // (A parametric surface's front, ∂u f × ∂v f mapped as a normal, is
        // kept through mirrors as a mesh's winding side is: tested on
        // twisted and flat bilinear patches.)
        if (s.reverseOrientation && !hasNormals && e.type != "curve") shape["flip_normals"] = true;  // a tube has no front
        // The analytic shapes' (u, v) are pbrt's: the disk's and the
        // cylinder's normalised (phi, radius from the rim) and (phi, z) as
        // strahl's, the textured sphere's by its formula above.
        shape["material"] = materialName;
        shape["name"] = e.type + "@" + e.place.text();
        refuseUnread(e);
        into.push_back(std::move(shape));
    }

    // pbrt-v4's curve: one strand of Bézier or B-spline segments of degree 2
    // or 3, its width running linearly from width0 to width1 along the whole
    // curve. It becomes strahl's cubic Bézier curve exactly: B-spline
    // segments are converted to their Bézier points, quadratics are degree
    // elevated, and the radius control values of each segment are those of
    // the linear width (a Bézier reproduces a linear function). pbrt's
    // "cylinder" type, a ribbon shaded as a tube, becomes a true round tube;
    // "flat" a ray-facing ribbon; "ribbon" strahl's oriented ribbon, each
    // control point's normal pbrt's slerp between the two N at its u.
    json curve(const Entity& e) const {
        const Parameter* P = typed(e, "P", {"point3"});
        if (!P || P->numbers.size() % 3 != 0) unsupported(e, "needs \"point3 P\"");
        const size_t n = P->numbers.size() / 3;
        const std::string basis = text(e, "basis", "bezier");
        if (basis != "bezier" && basis != "bspline") bad(*param(e, "basis"), "expected \"bezier\" or \"bspline\"");
        const int degree = integer(e, "degree", 3);
        if (degree != 2 && degree != 3) bad(*param(e, "degree"), "expected 2 or 3");
        const std::string type = text(e, "type", "flat");
        if (type != "flat" && type != "cylinder" && type != "ribbon")
            bad(*param(e, "type"), "expected \"flat\", \"cylinder\" or \"ribbon\"");
        const Parameter* N = typed(e, "N", {"normal"});
        if (N && type != "ribbon") bad(*N, "only for curves of type \"ribbon\"");
        if (type == "ribbon" && (!N || N->numbers.size() != 6))
            unsupported(e, "a ribbon needs \"normal N\" with two normals, at the curve's start and end");
        glm::dvec3 n0(0.0), n1(0.0);
        if (N) {
            n0 = {N->numbers[0], N->numbers[1], N->numbers[2]};
            n1 = {N->numbers[3], N->numbers[4], N->numbers[5]};
            if (!(glm::length(n0) > 0.0) || !(glm::length(n1) > 0.0)) bad(*N, "the normals must not be zero");
            n0 = glm::normalize(n0);
            n1 = glm::normalize(n1);
        }
        // pbrt's normal at u along the whole curve: the great-circle slerp.
        const auto normalAt = [&](double u) {
            const double cosAngle = std::clamp(glm::dot(n0, n1), -1.0, 1.0), angle = std::acos(cosAngle);
            if (angle < 1e-6) return n0;
            return (std::sin((1.0 - u) * angle) * n0 + std::sin(u * angle) * n1) / std::sin(angle);
        };
        json normals = json::array();
        const double width = number(e, "width", 1.0);
        const double w0 = number(e, "width0", width), w1 = number(e, "width1", width);
        if (!(w0 >= 0.0 && w1 >= 0.0 && std::isfinite(w0) && std::isfinite(w1)))
            unsupported(e, "the widths must be finite and >= 0");
        param(e, "splitdepth");  // pbrt's own refinement depth; Embree needs none
        const size_t d = static_cast<size_t>(degree);
        size_t segments = 0;
        if (basis == "bezier") {
            if (n < d + 1 || (n - 1) % d != 0)
                bad(*P, "a Bezier curve of degree " + std::to_string(degree) + " needs " + std::to_string(degree) +
                            "k + 1 points (got " + std::to_string(n) + ")");
            segments = (n - 1) / d;
        } else {
            if (n < d + 1)
                bad(*P, "a B-spline of degree " + std::to_string(degree) + " needs at least " +
                            std::to_string(degree + 1) + " points (got " + std::to_string(n) + ")");
            segments = n - d;
        }
        const auto p = [&](size_t i) { return DVec3(P->numbers[3 * i], P->numbers[3 * i + 1], P->numbers[3 * i + 2]); };
        json points = json::array();
        for (size_t k = 0; k < segments; ++k) {
            // The segment's Bézier points (degree 2 or 3).
            std::vector<DVec3> b;
            if (basis == "bezier") {
                for (size_t i = 0; i <= d; ++i) b.push_back(p(k * d + i));
            } else if (degree == 3) {
                const DVec3 q0 = p(k), q1 = p(k + 1), q2 = p(k + 2), q3 = p(k + 3);
                b = {(q0 + 4.0 * q1 + q2) / 6.0, (2.0 * q1 + q2) / 3.0, (q1 + 2.0 * q2) / 3.0, (q1 + 4.0 * q2 + q3) / 6.0};
            } else {
                const DVec3 q0 = p(k), q1 = p(k + 1), q2 = p(k + 2);
                b = {(q0 + q1) / 2.0, q1, (q1 + q2) / 2.0};
            }
            if (degree == 2) b = {b[0], b[0] + 2.0 / 3.0 * (b[1] - b[0]), b[2] + 2.0 / 3.0 * (b[1] - b[2]), b[2]};
            for (size_t i = k == 0 ? 0 : 1; i < 4; ++i) {
                const double u = (double(k) + double(i) / 3.0) / double(segments);
                points.push_back({b[i].x, b[i].y, b[i].z, 0.5 * ((1.0 - u) * w0 + u * w1)});
                if (N) {
                    const glm::dvec3 nu = normalAt(u);
                    normals.push_back({nu.x, nu.y, nu.z});
                }
            }
        }
        json out = {{"type", "curves"},
                    {"basis", "bezier"},
                    {"profile", type == "flat" ? "flat" : type == "ribbon" ? "oriented" : "round"},
                    {"points", std::move(points)}};
        if (N) out["normals"] = std::move(normals);
        return out;
    }

    // pbrt-v4's bilinear patches: four indices per patch, the corners p00,
    // p10, p01, p11. Flat patches (all of them, within 10^-4 of their size)
    // are two triangles each, (p00, p10, p11) and (p00, p11, p01): a mesh,
    // which keeps pbrt's N and uv. Otherwise the exact surface, a parametric
    // bilinear patch set in strahl's order around each patch, tessellated
    // from one cell per patch until it is within 10^-3 of the mesh's size
    // (docs/pbrt.md).
    json bilinearMesh(const Entity& e, bool& hasNormals) const {
        const Parameter* P = typed(e, "P", {"point3"});
        if (!P) unsupported(e, "needs \"point3 P\"");
        const size_t n = P->numbers.size() / 3;
        typed(e, "indices", {"integer"});
        const std::vector<uint32_t> corners = pointIndices(e, *P, 4, {0, 1, 2, 3});
        auto point = [&](uint32_t i) { return DVec3(P->numbers[3 * i], P->numbers[3 * i + 1], P->numbers[3 * i + 2]); };
        bool flat = true;
        for (size_t p = 0; flat && p < corners.size(); p += 4)
            flat = bilinearPatchIsFlat(point(corners[p]), point(corners[p + 1]), point(corners[p + 3]),
                                       point(corners[p + 2]), 1e-4);
        json positions = json::array();
        positions.get_ref<json::array_t&>().reserve(n);
        for (size_t i = 0; i < n; ++i)
            positions.push_back({P->numbers[3 * i], P->numbers[3 * i + 1], P->numbers[3 * i + 2]});
        const Parameter* N = typed(e, "N", {"normal"});
        const Parameter* uv = typed(e, "uv", {"point2", "float"});
        if (const Parameter* S = e.params.find("S")) bad(*S, "not a parameter of bilinearmesh");
        param(e, "faceIndices");  // ptex face ids: no ptex textures here
        if (flat) {
            json indices = json::array();
            for (size_t p = 0; p < corners.size(); p += 4) {
                const uint32_t p00 = corners[p], p10 = corners[p + 1], p01 = corners[p + 2], p11 = corners[p + 3];
                for (uint32_t i : {p00, p10, p11, p00, p11, p01}) indices.push_back(i);
            }
            json mesh = {{"type", "mesh"}, {"positions", std::move(positions)}, {"indices", std::move(indices)}};
            vertexAttributes(N, uv, n, mesh, hasNormals);
            return mesh;
        }
        if (N) bad(*N, "shading normals on twisted bilinear patches are not supported (their normals are exact)");
        if (uv) bad(*uv, "\"uv\" on twisted bilinear patches is not supported (their (u, v) are the patch's own, pbrt's default)");
        json order = json::array();
        Bounds3 box;
        for (size_t p = 0; p < corners.size(); p += 4) {
            for (uint32_t i : {corners[p], corners[p + 1], corners[p + 3], corners[p + 2]}) {
                order.push_back(i);
                box.expand(Vec3(point(i)));
            }
        }
        // The tessellation's chord error: 10^-3 of the patches' extent.
        const double maxError = 1e-3 * std::max(static_cast<double>(glm::length(box.diagonal())), 1e-30);
        return {{"type", "parametric"},
                {"surface", {{"type", "bilinear"}, {"positions", std::move(positions)}, {"patches", std::move(order)}}},
                {"tessellation", {{"segments", 1}, {"max_error", maxError}}}};
    }

    json triangleMesh(const Entity& e, bool& hasNormals) const {
        const Parameter* P = typed(e, "P", {"point3"});
        if (!P) unsupported(e, "needs \"point3 P\"");
        const size_t n = P->numbers.size() / 3;
        const Parameter* idx = typed(e, "indices", {"integer"});
        json indices = json::array();
        if (idx) {
            indices.get_ref<json::array_t&>().reserve(idx->numbers.size());
            if (idx->numbers.size() % 3 != 0 || idx->numbers.empty())
                bad(*idx, "expected three indices per triangle");
            for (double i : idx->numbers) {
                if (i < 0 || i >= static_cast<double>(n))
                    bad(*idx, concat("index ", i, " is out of range (", n, " points)"));
                indices.push_back(static_cast<uint32_t>(i));
            }
        } else {
            if (n != 3) unsupported(e, "\"integer indices\" may only be left out for a single triangle");
            indices = {0u, 1u, 2u};
        }
        json positions = json::array();
        positions.get_ref<json::array_t&>().reserve(n);
        for (size_t i = 0; i < n; ++i)
            positions.push_back({P->numbers[3 * i], P->numbers[3 * i + 1], P->numbers[3 * i + 2]});
        json mesh = {{"type", "mesh"}};
        mesh["positions"] = std::move(positions);
        mesh["indices"] = std::move(indices);
        vertexAttributes(typed(e, "N", {"normal"}), typed(e, "uv", {"point2", "float"}), n, mesh, hasNormals);
        if (const Parameter* S = e.params.find("S")) bad(*S, "per-vertex tangents are not supported");
        param(e, "faceIndices");  // ptex face ids: no ptex textures here
        return mesh;
    }

    // A mesh's per-point normals N and texture coordinates uv, when given.
    void vertexAttributes(const Parameter* N, const Parameter* uv, size_t n, json& mesh, bool& hasNormals) const {
        if (N) {
            if (N->numbers.size() != 3 * n) bad(*N, "expected one normal per point");
            json normals = json::array();
            for (size_t i = 0; i < n; ++i)
                normals.push_back({N->numbers[3 * i], N->numbers[3 * i + 1], N->numbers[3 * i + 2]});
            mesh["normals"] = std::move(normals);
            hasNormals = true;
        }
        if (uv) {
            if (uv->numbers.size() != 2 * n) bad(*uv, "expected one (u, v) per point");
            json uvs = json::array();
            for (size_t i = 0; i < n; ++i) uvs.push_back({uv->numbers[2 * i], uv->numbers[2 * i + 1]});
            mesh["uvs"] = std::move(uvs);
        }
    }

    std::string group(const std::string& object) {
        if (const auto found = madeGroups_.find(object); found != madeGroups_.end()) return found->second;
        const ObjectDefinition& def = s_.objects.at(object);
        json shapes = json::array();
        for (const Shape& s : def.shapes) shape(s, false, shapes);
        if (shapes.empty()) fail(def.place.text(), ": ObjectBegin \"", object, "\": the object has no shapes");
        json group = {{"name", object}};
        group["shapes"] = std::move(shapes);
        groups_.push_back(std::move(group));
        madeGroups_[object] = object;
        return object;
    }

    // --- lights ---------------------------------------------------------
    void light(const Light& l) {
        const Entity& e = l.entity;
        const glm::dmat4 m = mirror_ * l.toWorld;
        const double scale = number(e, "scale", 1.0);
        json out;
        auto spectral = [&](const char* name) {
            const Parameter* p = param(e, name);
            return p ? spectrum(*p, Use::Light) : glm::dvec3(1.0);
        };
        if (e.type == "point" || e.type == "spot") {
            glm::dvec3 I = spectral("I") * scale;
            const glm::dvec3 from = point(e, "from", glm::dvec3(0.0));
            out = {{"type", e.type}, {"position", vec3(transformPoint(m, from))}};
            double kE = 4.0 * glm::pi<double>();
            if (e.type == "spot") {
                const glm::dvec3 to = point(e, "to", glm::dvec3(0, 0, 1));
                const double cone = number(e, "coneangle", 30.0), delta = number(e, "conedeltaangle", 5.0);
                if (!(cone > 0.0 && cone <= 180.0) || delta < 0.0) unsupported(e, "needs 0 < coneangle <= 180 and conedeltaangle >= 0");
                const glm::dvec3 dir = transformVector(m, to - from);
                if (!(glm::length(dir) > 0.0)) unsupported(e, "from and to coincide");
                out["direction"] = vec3(glm::normalize(dir));
                out["cone_angle"] = cone;
                out["falloff_start"] = std::max(0.0, cone - delta);
                const double cosTotal = std::cos(glm::radians(cone)), cosStart = std::cos(glm::radians(std::max(0.0, cone - delta)));
                kE = 2.0 * glm::pi<double>() * (1.0 - 0.5 * (cosStart + cosTotal));
            }
            // pbrt normalises only a spectrum's luminance, never an rgb's
            // colour, before power scales it: I · power / k_e.
            if (const Parameter* power = typed(e, "power", {"float"})) I *= power->numbers[0] / kE;
            out["intensity"] = color(I);
        } else if (e.type == "distant") {
            glm::dvec3 L = spectral("L") * scale;
            const glm::dvec3 from = point(e, "from", glm::dvec3(0.0)), to = point(e, "to", glm::dvec3(0, 0, 1));
            const glm::dvec3 dir = transformVector(m, to - from);
            if (!(glm::length(dir) > 0.0)) unsupported(e, "from and to coincide");
            if (const Parameter* E = typed(e, "illuminance", {"float"})) L *= E->numbers[0];
            out = {{"type", "directional"}, {"direction", vec3(glm::normalize(dir))}, {"irradiance", color(L)}};
        } else if (e.type == "infinite" && e.params.find("filename")) {
            // pbrt-v4's image: a square in the equal-area octahedral layout, +z
            // up in the light's frame, looked up at the light-space direction
            // of pbrt's world direction (the mirror of strahl's).
            const Parameter* f = typed(e, "filename", {"string"});
            if (e.params.find("L")) unsupported(e, "give either L or filename");
            double imageScale = scale;
            if (const Parameter* E = typed(e, "illuminance", {"float"})) {
                // pbrt-v4 scales the image so that a surface facing the
                // light's +z receives E: E_image = Σ L(w) cos θ dω over the
                // pixels of the upper hemisphere, each dω = 4π / pixels
                // (the layout has equal areas).
                const fs::path name = f->strings.at(0);
                const double illuminance =
                    upperHemisphereIlluminance(name.is_absolute() ? name : s_.folder / name);
                if (!(illuminance > 0.0)) bad(*E, "the image sends no light to a surface facing up (+z)");
                imageScale *= E->numbers[0] / illuminance;
            }
            const glm::dmat3 mapFromWorld = glm::inverse(glm::dmat3(l.toWorld)) * glm::dmat3(mirror_);
            json rows = json::array();
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) rows.push_back(mapFromWorld[c][r]);
            param(e, "portal");  // where pbrt samples, not what it shows
            out = {{"type", "environment"}, {"file", file(*f)}, {"mapping", "equal_area"},
                   {"map_transform", rows}};
            if (imageScale != 1.0) out["scale"] = imageScale;
        } else if (e.type == "infinite") {
            glm::dvec3 L = spectral("L") * scale;
            if (const Parameter* E = typed(e, "illuminance", {"float"}))
                // A constant sky of radiance L gives an upward plane E = π L.
                L *= E->numbers[0] / glm::pi<double>();
            param(e, "portal");  // where pbrt samples, not what it shows
            out = {{"type", "sky"}, {"radiance", color(L)}};
        } else {
            unsupported(e, "this light is not supported (point, spot, distant, infinite)");
        }
        refuseUnread(e);
        lights_.push_back(out);
    }
};

}  // namespace

json toStrahlDocument(const Scene& scene, const fs::path& cwd) { return Converter(scene, cwd).convert(); }

}  // namespace strahl::scene_detail::pbrt
