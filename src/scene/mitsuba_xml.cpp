#include "mitsuba_xml.h"

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <set>
#include <sstream>

#include "file_identity.h"
#include "strahl/core/error.h"

namespace strahl::scene_detail::mitsuba {

namespace fs = std::filesystem;

const Property* Object::property(const std::string& name) const {
    for (const Property& p : properties)
        if (p.name == name) return &p;
    return nullptr;
}

std::string Object::element() const {
    std::string text = "<" + tag;
    if (!type.empty()) text += " type=\"" + type + "\"";
    if (!id.empty()) text += " id=\"" + id + "\"";
    return text + ">";
}

std::vector<double> numbers(const std::string& text, const Place& place, const std::string& what) {
    std::vector<double> out;
    const char* p = text.c_str();
    while (true) {
        while (*p == ',' || std::isspace(static_cast<unsigned char>(*p))) ++p;
        if (*p == '\0') break;
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(p, &end);
        if (end == p || errno == ERANGE || !std::isfinite(v))
            fail(place.text(), ": ", what, ": '", text, "' is not a list of numbers");
        out.push_back(v);
        p = end;
        if (*p != '\0' && *p != ',' && !std::isspace(static_cast<unsigned char>(*p)))
            fail(place.text(), ": ", what, ": '", text, "' is not a list of numbers");
    }
    return out;
}

namespace {

// The elements that are objects (plugins) and those that are properties.
const std::set<std::string> kObjectTags = {"shape",   "bsdf",    "emitter", "sensor",
                                           "film",    "rfilter", "sampler", "integrator",
                                           "texture", "medium",  "phase",   "volume"};
const std::set<std::string> kPropertyTags = {"integer", "float",  "boolean", "string", "point",
                                             "vector",  "rgb",    "spectrum", "transform"};

// Nested includes deeper than this are refused (a cycle is caught earlier).
constexpr int kMaxIncludeDepth = 32;

std::string readFile(const fs::path& file, const Place& from) {
    std::error_code ec;
    if (fs::exists(file, ec) && !fs::is_regular_file(file, ec))
        fail(from.text(), ": cannot open '", file.string(), "': not a regular file");
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(from.text(), ": cannot open '", file.string(), "': ", std::strerror(errno));
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// One XML file being read: its text (for line numbers) and its name.
struct Source {
    std::string name;  // as in messages
    fs::path folder;
    const std::string* text;
    int line(ptrdiff_t offset) const {
        if (offset < 0) return 0;
        const auto end = text->begin() + std::min<ptrdiff_t>(offset, ptrdiff_t(text->size()));
        return 1 + int(std::count(text->begin(), end, '\n'));
    }
};

class Reader {
public:
    Reader(const Defines& defines) : params_(defines) {
        for (const auto& [name, value] : defines) defined_.insert(name);
    }

    Scene read(const std::string& text, const fs::path& file) {
        pugi::xml_document doc;
        const Source source{file.string(), file.parent_path(), &text};
        sceneFolder_ = source.folder;
        parse(doc, source);
        const pugi::xml_node root = doc.document_element();
        const Place place{source.name, source.line(root.offset_debug())};
        if (std::string(root.name()) != "scene")
            fail(place.text(), ": <", root.name(), ">: the document must be a <scene>");
        checkVersion(root, place);
        auto scene = std::make_shared<Object>();
        scene->tag = "scene";
        scene->place = place;
        scene->folder = source.folder;
        including_.push_back(fileIdentity(file));
        readChildren(root, source, *scene);
        for (const std::string& name : defined_)
            if (!used_.count(name))
                fail(file.string(), ": -D ", name, ": the scene has no <default name=\"", name,
                     "\"> and no $", name);
        Scene result;
        result.root = scene;
        result.searchPath = searchPath_;
        result.searchPath.push_back(source.folder);
        return result;
    }

private:
    static void parse(pugi::xml_document& doc, const Source& source) {
        const pugi::xml_parse_result parsed =
            doc.load_buffer(source.text->data(), source.text->size(), pugi::parse_default);
        if (!parsed)
            fail(source.name, ":", source.line(parsed.offset), ": malformed XML: ",
                 parsed.description());
    }

    static void checkVersion(const pugi::xml_node& root, const Place& place) {
        const pugi::xml_attribute version = root.attribute("version");
        if (!version) fail(place.text(), ": <scene>: no version attribute (Mitsuba 3 scenes say version=\"3.0.0\")");
        // Mitsuba 3 reads 2.x files as they are (the same names); older ones
        // need its upgrade of parameter names, which strahl does not do.
        const int major = std::atoi(version.value());
        if (major != 2 && major != 3)
            fail(place.text(), ": <scene version=\"", version.value(),
                 "\">: only scene versions 2.x and 3.x are read (upgrade older scenes with "
                 "Mitsuba 3)");
    }

    // `text` with every $name replaced by its parameter.
    std::string substitute(const std::string& text, const Place& place) {
        std::string out;
        for (size_t i = 0; i < text.size(); ++i) {
            if (text[i] != '$') {
                out += text[i];
                continue;
            }
            size_t end = i + 1;
            while (end < text.size() &&
                   (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))
                ++end;
            const std::string name = text.substr(i + 1, end - i - 1);
            const auto found = params_.find(name);
            if (name.empty() || found == params_.end())
                fail(place.text(), ": $", name, ": no <default> or -D gives it a value");
            used_.insert(name);
            out += found->second;
            i = end - 1;
        }
        return out;
    }

    std::string attribute(const pugi::xml_node& node, const char* name, const Place& place,
                          bool required = true) {
        const pugi::xml_attribute a = node.attribute(name);
        if (!a) {
            if (required) fail(place.text(), ": <", node.name(), ">: missing attribute '", name, "'");
            return {};
        }
        return substitute(a.value(), place);
    }

    void readChildren(const pugi::xml_node& node, const Source& source, Object& object) {
        for (const pugi::xml_node& child : node.children()) {
            if (child.type() != pugi::node_element) continue;
            const std::string tag = child.name();
            const Place place{source.name, source.line(child.offset_debug())};
            if (kObjectTags.count(tag)) {
                auto nested = readObject(child, source, place);
                object.children.push_back({attribute(child, "name", place, false), nested, place});
            } else if (kPropertyTags.count(tag)) {
                object.properties.push_back(readProperty(child, tag, source, place));
            } else if (tag == "ref") {
                const std::string id = attribute(child, "id", place);
                const auto found = ids_.find(id);
                if (found == ids_.end())
                    fail(place.text(), ": <ref id=\"", id, "\">: no object with this id before it");
                object.children.push_back({attribute(child, "name", place, false), found->second, place});
            } else if (tag == "default") {
                const std::string name = attribute(child, "name", place);
                const std::string value = attribute(child, "value", place);
                if (!defined_.count(name)) params_[name] = value;
                used_.insert(name);
            } else if (tag == "path") {
                if (object.tag != "scene") fail(place.text(), ": <path> belongs in the <scene>");
                searchPath_.push_back(source.folder / attribute(child, "value", place));
            } else if (tag == "include") {
                if (object.tag != "scene") fail(place.text(), ": <include> belongs in the <scene>");
                include(child, source, place, object);
            } else if (tag == "alias") {
                const std::string id = attribute(child, "id", place), as = attribute(child, "as", place);
                const auto found = ids_.find(id);
                if (found == ids_.end())
                    fail(place.text(), ": <alias id=\"", id, "\">: no object with this id before it");
                ids_[as] = found->second;
            } else {
                fail(place.text(), ": <", tag, ">: not an element of Mitsuba 3's scene language");
            }
        }
    }

    std::shared_ptr<const Object> readObject(const pugi::xml_node& node, const Source& source,
                                             const Place& place) {
        auto object = std::make_shared<Object>();
        object->tag = node.name();
        object->type = attribute(node, "type", place);
        object->id = attribute(node, "id", place, false);
        object->place = place;
        object->folder = source.folder;
        readChildren(node, source, *object);
        if (!object->id.empty()) {
            if (ids_.count(object->id))
                fail(place.text(), ": ", object->element(), ": the id '", object->id,
                     "' is already taken");
            ids_[object->id] = object;
        }
        return object;
    }

    Property readProperty(const pugi::xml_node& node, const std::string& tag, const Source& source,
                          const Place& place) {
        Property p;
        p.tag = tag;
        p.place = place;
        p.name = attribute(node, "name", place);
        if (tag == "transform") {
            p.matrix = readTransform(node, source);
        } else if (tag == "point" || tag == "vector") {
            if (node.attribute("value")) {
                p.value = attribute(node, "value", place);
                const std::vector<double> v = numbers(p.value, place, "<" + tag + " name=\"" + p.name + "\">");
                if (v.size() == 1) p.xyz = glm::dvec3(v[0]);
                else if (v.size() == 3) p.xyz = glm::dvec3(v[0], v[1], v[2]);
                else fail(place.text(), ": <", tag, " name=\"", p.name, "\">: expected 1 or 3 numbers, got ", v.size());
            } else {
                p.xyz = xyzAttributes(node, place, 0.0);
            }
        } else if (tag == "spectrum" && !node.attribute("value")) {
            p.value = spectrumFile(attribute(node, "filename", place), source, place);
        } else {
            p.value = attribute(node, "value", place);
        }
        return p;
    }

    glm::dvec3 xyzAttributes(const pugi::xml_node& node, const Place& place, double fallback) {
        glm::dvec3 v(fallback);
        const char* names[3] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i)
            if (node.attribute(names[i])) {
                const std::vector<double> n = numbers(attribute(node, names[i], place), place,
                                                      std::string("attribute ") + names[i]);
                if (n.size() != 1) fail(place.text(), ": attribute ", names[i], ": expected one number");
                v[i] = n[0];
            }
        return v;
    }

    glm::dvec3 vector3(const pugi::xml_node& node, const char* name, const Place& place) {
        const std::vector<double> v = numbers(attribute(node, name, place), place,
                                              std::string("<") + node.name() + "> " + name);
        if (v.size() != 3)
            fail(place.text(), ": <", node.name(), "> ", name, ": expected 3 numbers, got ", v.size());
        return {v[0], v[1], v[2]};
    }

    // The operations in order, each applied after those before it.
    glm::dmat4 readTransform(const pugi::xml_node& node, const Source& source) {
        glm::dmat4 m(1.0);
        for (const pugi::xml_node& op : node.children()) {
            if (op.type() != pugi::node_element) continue;
            const Place place{source.name, source.line(op.offset_debug())};
            const std::string name = op.name();
            glm::dmat4 t(1.0);
            if (name == "translate") {
                const glm::dvec3 v = op.attribute("value") ? vector3(op, "value", place)
                                                           : xyzAttributes(op, place, 0.0);
                t = glm::translate(glm::dmat4(1.0), v);
            } else if (name == "scale") {
                glm::dvec3 v(1.0);
                if (op.attribute("value")) {
                    const std::vector<double> n = numbers(attribute(op, "value", place), place, "<scale> value");
                    if (n.size() == 1) v = glm::dvec3(n[0]);
                    else if (n.size() == 3) v = glm::dvec3(n[0], n[1], n[2]);
                    else fail(place.text(), ": <scale> value: expected 1 or 3 numbers");
                } else {
                    v = xyzAttributes(op, place, 1.0);
                }
                t = glm::scale(glm::dmat4(1.0), v);
            } else if (name == "rotate") {
                const glm::dvec3 axis = op.attribute("axis") ? vector3(op, "axis", place)
                                                             : xyzAttributes(op, place, 0.0);
                const std::vector<double> angle = numbers(attribute(op, "angle", place), place, "<rotate> angle");
                if (angle.size() != 1 || glm::length(axis) == 0.0)
                    fail(place.text(), ": <rotate>: needs a non-zero axis and one angle in degrees");
                t = glm::rotate(glm::dmat4(1.0), glm::radians(angle[0]), glm::normalize(axis));
            } else if (name == "matrix") {
                const std::vector<double> v = numbers(attribute(op, "value", place), place, "<matrix> value");
                if (v.size() != 16 && v.size() != 9)
                    fail(place.text(), ": <matrix>: expected 16 (or 9) numbers, row by row, got ", v.size());
                const int n = v.size() == 16 ? 4 : 3;
                for (int r = 0; r < n; ++r)
                    for (int c = 0; c < n; ++c) t[c][r] = v[size_t(r * n + c)];  // glm: column-major
            } else if (name == "lookat") {
                const glm::dvec3 origin = vector3(op, "origin", place);
                const glm::dvec3 target = vector3(op, "target", place);
                glm::dvec3 up(0.0, 1.0, 0.0);
                if (op.attribute("up")) up = vector3(op, "up", place);
                t = lookAt(origin, target, up, place);
            } else {
                fail(place.text(), ": <", name, ">: not a transform operation (translate, rotate, "
                     "scale, matrix, lookat)");
            }
            m = t * m;
        }
        return m;
    }

    // Mitsuba's look-at: the camera (or object) frame with +z towards the
    // target, +y up, and +x = up × dir (pointing left in the image).
    static glm::dmat4 lookAt(const glm::dvec3& origin, const glm::dvec3& target,
                             const glm::dvec3& up, const Place& place) {
        const glm::dvec3 dir = target - origin;
        if (glm::length(dir) == 0.0) fail(place.text(), ": <lookat>: origin and target coincide");
        const glm::dvec3 d = glm::normalize(dir);
        const glm::dvec3 leftRaw = glm::cross(glm::normalize(up), d);
        if (glm::length(leftRaw) < 1e-9) fail(place.text(), ": <lookat>: up is parallel to the view direction");
        const glm::dvec3 left = glm::normalize(leftRaw);
        const glm::dvec3 newUp = glm::cross(d, left);
        glm::dmat4 m(1.0);
        m[0] = glm::dvec4(left, 0.0);
        m[1] = glm::dvec4(newUp, 0.0);
        m[2] = glm::dvec4(d, 0.0);
        m[3] = glm::dvec4(origin, 1.0);
        return m;
    }

    // A file named in `source`, as Mitsuba's file resolver finds it: in the
    // main scene's folder, the <path> folders, then the naming file's own.
    fs::path resolve(const std::string& name, const Source& source) const {
        std::vector<fs::path> folders = {sceneFolder_};
        folders.insert(folders.end(), searchPath_.begin(), searchPath_.end());
        std::error_code ec;  // a name the file system refuses (too long) is found nowhere
        for (const fs::path& folder : folders)
            if (fs::exists(folder / name, ec)) return folder / name;
        return source.folder / name;
    }

    // A spectrum file (Mitsuba's .spd: lines "wavelength value", '#' starts a
    // comment) as the value of an inline spectrum, "w1:v1, w2:v2, ...".
    std::string spectrumFile(const std::string& name, const Source& source, const Place& place) {
        const fs::path file = resolve(name, source);
        const std::string text = readFile(file, place);
        std::ostringstream pairs;
        pairs.precision(17);  // every digit of the file's numbers survives the round trip
        bool any = false;
        std::istringstream lines(text);
        std::string line;
        for (int number = 1; std::getline(lines, line); ++number) {
            line = line.substr(0, line.find('#'));
            const Place at{file.string(), number};
            const std::vector<double> v = numbers(line, at, "a spectrum file line");
            if (v.empty()) continue;
            if (v.size() != 2) fail(at.text(), ": expected a wavelength and a value, got ", v.size(), " numbers");
            pairs << (any ? ", " : "") << v[0] << ":" << v[1];
            any = true;
        }
        if (!any) fail(place.text(), ": the spectrum file '", file.string(), "' has no values");
        return pairs.str();
    }

    void include(const pugi::xml_node& node, const Source& source, const Place& place,
                 Object& scene) {
        const std::string name = attribute(node, "filename", place);
        const fs::path file = resolve(name, source);
        const fs::path canonical = fileIdentity(file);
        if (std::find(including_.begin(), including_.end(), canonical) != including_.end())
            fail(place.text(), ": <include filename=\"", name, "\">: includes itself (a cycle)");
        if (including_.size() >= kMaxIncludeDepth)
            fail(place.text(), ": <include>: more than ", kMaxIncludeDepth, " nested includes");
        const std::string text = readFile(file, place);
        pugi::xml_document doc;
        const Source included{file.lexically_normal().string(), file.parent_path(), &text};
        parse(doc, included);
        const pugi::xml_node root = doc.document_element();
        const Place rootPlace{included.name, included.line(root.offset_debug())};
        if (std::string(root.name()) != "scene")
            fail(rootPlace.text(), ": <", root.name(), ">: an included file must be a <scene>");
        checkVersion(root, rootPlace);
        including_.push_back(canonical);
        readChildren(root, included, scene);
        including_.pop_back();
    }

    std::map<std::string, std::string> params_;
    std::set<std::string> defined_, used_;
    std::map<std::string, std::shared_ptr<const Object>> ids_;
    std::vector<fs::path> searchPath_;
    std::vector<fs::path> including_;
    fs::path sceneFolder_;
};

}  // namespace

Scene readScene(const std::string& text, const fs::path& file, const Defines& defines) {
    return Reader(defines).read(text, file);
}

}  // namespace strahl::scene_detail::mitsuba
