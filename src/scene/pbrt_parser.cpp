// The pbrt-v4 scene language (pbrt_parser.h): a tokenizer over the file's
// text and the directives that build the graphics state. The grammar is
// pbrt-v4's file format reference (pbrt.org/fileformat-v4); docs/pbrt.md.

#include "pbrt_parser.h"

#include "strahl/meshio/mapped_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "file_identity.h"
#include "strahl/core/error.h"
#include "strahl/meshio/mesh_file.h"

namespace strahl::scene_detail::pbrt {

const Parameter* ParameterList::find(const std::string& name) const {
    for (const Parameter& p : items)
        if (p.name == name) return &p;
    return nullptr;
}

void ParameterList::addDefaults(const ParameterList& defaults) {
    for (const Parameter& d : defaults.items)
        if (!find(d.name)) items.push_back(d);
}

namespace {

namespace fs = std::filesystem;

// Include nesting deeper than this is an error (a cycle is caught earlier;
// this bounds the stack for pathological chains).
constexpr int kMaxIncludeDepth = 32;

struct Token {
    std::string_view text;  // a quoted string keeps its quotes
    int line = 0;
    bool quoted() const { return !text.empty() && text.front() == '"'; }
    bool is(std::string_view s) const { return !quoted() && text == s; }
};

// Splits one file's text into tokens: bare words and numbers, "strings",
// [ and ]; '#' starts a comment to the end of the line.
class Tokenizer {
public:
    Tokenizer(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

    std::optional<Token> next() {
        if (pending_) {
            std::optional<Token> t = pending_;
            pending_.reset();
            return t;
        }
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_, ++pos_;
            } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
                ++pos_;
            } else if (c == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else {
                break;
            }
        }
        if (pos_ >= text_.size()) return std::nullopt;
        const size_t start = pos_;
        const char c = text_[pos_];
        if (c == '[' || c == ']') {
            ++pos_;
            return Token{text_.substr(start, 1), line_};
        }
        if (c == '"') {
            ++pos_;
            while (pos_ < text_.size() && text_[pos_] != '"') {
                if (text_[pos_] == '\n') fail(file_, ":", line_, ": a string runs past the end of its line");
                if (text_[pos_] == '\\') ++pos_;
                ++pos_;
            }
            if (pos_ >= text_.size()) fail(file_, ":", line_, ": the file ends inside a string");
            ++pos_;
            return Token{text_.substr(start, pos_ - start), line_};
        }
        while (pos_ < text_.size()) {
            const char d = text_[pos_];
            if (d == ' ' || d == '\n' || d == '\t' || d == '\r' || d == '"' || d == '[' || d == ']' ||
                d == '#')
                break;
            ++pos_;
        }
        return Token{text_.substr(start, pos_ - start), line_};
    }

    void putBack(const Token& t) { pending_ = t; }
    const std::string& file() const { return file_; }

private:
    std::string_view text_;
    std::string file_;
    size_t pos_ = 0;
    int line_ = 1;
    std::optional<Token> pending_;
};

// The text of a quoted token, escapes resolved.
std::string unquote(std::string_view quoted) {
    std::string out;
    out.reserve(quoted.size());
    for (size_t i = 1; i + 1 < quoted.size(); ++i) {
        char c = quoted[i];
        if (c == '\\' && i + 2 < quoted.size()) {
            c = quoted[++i];
            if (c == 'n') c = '\n';
            else if (c == 't') c = '\t';
        }
        out += c;
    }
    return out;
}

bool parseNumber(std::string_view text, double& value) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    if (begin != end && *begin == '+') ++begin;  // from_chars takes no '+'
    const auto [ptr, ec] = std::from_chars(begin, end, value);
    return ec == std::errc() && ptr == end;
}

// What each parameter type holds: how many numbers make one value, or that
// it holds strings.
struct TypeInfo {
    const char* name;
    int arity;       // numbers per value; 0 for string-valued types
    const char* canonical;
};

constexpr TypeInfo kTypes[] = {
    {"integer", 1, "integer"}, {"float", 1, "float"},     {"point2", 2, "point2"},
    {"vector2", 2, "vector2"}, {"point3", 3, "point3"},   {"vector3", 3, "vector3"},
    {"normal3", 3, "normal"},  {"normal", 3, "normal"},   {"point", 3, "point3"},
    {"vector", 3, "vector3"},  {"rgb", 3, "rgb"},         {"color", 3, "rgb"},
    {"spectrum", 2, "spectrum"}, {"blackbody", 1, "blackbody"}, {"bool", 1, "bool"},
    {"string", 0, "string"},   {"texture", 0, "texture"},
};

const TypeInfo* typeInfo(std::string_view name) {
    for (const TypeInfo& t : kTypes)
        if (name == t.name) return &t;
    return nullptr;
}

struct GraphicsState {
    glm::dmat4 ctm[2] = {glm::dmat4(1.0), glm::dmat4(1.0)};  // at the start and end time
    unsigned active = 3;  // bit 0: the start transform, bit 1: the end transform
    bool reverseOrientation = false;
    int material = 0;           // an anonymous Material, or
    std::string namedMaterial;  // the NamedMaterial in effect (resolved at the end)
    int areaLight = -1;
    ParameterList shapeDefaults, lightDefaults, materialDefaults, textureDefaults;
    Place place;  // of the AttributeBegin that pushed the enclosing state
    bool transformOnly = false;  // pushed by TransformBegin
};

class Parser {
public:
    explicit Parser(const fs::path& mainFile) {
        scene_.folder = fs::absolute(mainFile).parent_path();
        Entity diffuse;
        diffuse.directive = "Material";
        diffuse.type = "diffuse";
        diffuse.place = {"(pbrt's default material)", 0};
        scene_.materials.push_back(diffuse);
    }

    void parseFile(std::string_view text, const std::string& label, const fs::path& path, int depth) {
        const fs::path canonical = fileIdentity(path);
        openFiles_.insert(canonical);
        Tokenizer tokens(text, label);
        while (std::optional<Token> t = tokens.next()) directive(tokens, *t, depth);
        openFiles_.erase(canonical);
    }

    Scene finish(const std::string& label) {
        if (!stack_.empty())
            fail(stack_.back().place.text(), ": AttributeBegin without a matching AttributeEnd");
        if (currentObject_) fail(currentObject_->place.text(), ": ObjectBegin without a matching ObjectEnd");
        if (!inWorld_) fail(label, ": the file has no WorldBegin");
        scene_.label = label;
        auto resolve = [&](Shape& s) {
            if (s.materialName.empty()) return;
            const auto found = scene_.namedMaterials.find(s.materialName);
            if (found == scene_.namedMaterials.end())
                fail(namedMaterialPlace_[s.materialName].text(), ": NamedMaterial: no material named \"",
                     s.materialName, "\"");
            s.material = found->second;
        };
        for (Shape& s : scene_.shapes) resolve(s);
        for (auto& [name, object] : scene_.objects)
            for (Shape& s : object.shapes) resolve(s);
        for (const Instance& i : scene_.instances)
            if (!scene_.objects.count(i.object))
                fail(i.place.text(), ": ObjectInstance: no object named \"", i.object, "\"");
        return std::move(scene_);
    }

private:
    Scene scene_;
    GraphicsState state_;
    std::vector<GraphicsState> stack_;
    std::map<std::string, glm::dmat4> coordinateSystems_;
    std::set<fs::path> openFiles_;
    bool inWorld_ = false;
    std::optional<ObjectDefinition> currentObject_;
    std::map<std::string, Place> namedMaterialPlace_;  // where each NamedMaterial name was used

    static Place at(const Tokenizer& tokens, const Token& t) { return {tokens.file(), t.line}; }

    [[noreturn]] static void error(const Tokenizer& tokens, const Token& t, const std::string& what) {
        fail(tokens.file(), ":", t.line, ": ", what);
    }

    static Token need(Tokenizer& tokens, const Token& after, const char* what) {
        std::optional<Token> t = tokens.next();
        if (!t) error(tokens, after, std::string("the file ends where ") + what + " should follow " +
                                         std::string(after.text));
        return *t;
    }

    static std::string needString(Tokenizer& tokens, const Token& directive) {
        const Token t = need(tokens, directive, "a quoted string");
        if (!t.quoted())
            error(tokens, t, std::string(directive.text) + ": expected a quoted string, got '" +
                                 std::string(t.text) + "'");
        return unquote(t.text);
    }

    static double needNumber(Tokenizer& tokens, const Token& directive) {
        const Token t = need(tokens, directive, "a number");
        double v = 0.0;
        if (t.quoted() || !parseNumber(t.text, v))
            error(tokens, t, std::string(directive.text) + ": expected a number, got '" +
                                 std::string(t.text) + "'");
        if (!std::isfinite(v)) error(tokens, t, std::string(directive.text) + ": the number is not finite");
        return v;
    }

    // n numbers, bracketed or not (Transform [ ... ] and LookAt ...).
    static std::vector<double> needNumbers(Tokenizer& tokens, const Token& directive, size_t n) {
        std::vector<double> v;
        const Token first = need(tokens, directive, "numbers");
        const bool bracketed = first.is("[");
        if (!bracketed) tokens.putBack(first);
        for (size_t i = 0; i < n; ++i) v.push_back(needNumber(tokens, directive));
        if (bracketed) {
            const Token close = need(tokens, directive, "]");
            if (!close.is("]"))
                error(tokens, close, std::string(directive.text) + ": expected ']' after " +
                                         std::to_string(n) + " numbers");
        }
        return v;
    }

    ParameterList parameters(Tokenizer& tokens, const Token& directive) {
        ParameterList list;
        std::set<std::string> names;
        while (std::optional<Token> t = tokens.next()) {
            if (!t->quoted()) {
                tokens.putBack(*t);
                break;
            }
            const std::string decl = unquote(t->text);
            std::istringstream words(decl);
            std::string type, name, extra;
            words >> type >> name >> extra;
            if (name.empty() || !extra.empty())
                error(tokens, *t, std::string(directive.text) + ": expected a parameter declaration \"type name\", got \"" + decl + "\"");
            const TypeInfo* info = typeInfo(type);
            if (!info) error(tokens, *t, "\"" + decl + "\": unknown parameter type '" + type + "'");
            if (!names.insert(name).second) error(tokens, *t, "parameter '" + name + "' is given twice");
            Parameter p;
            p.type = info->canonical;
            p.name = name;
            p.place = at(tokens, *t);
            values(tokens, *t, *info, p);
            list.items.push_back(std::move(p));
        }
        return list;
    }

    static void value(Tokenizer& tokens, const Token& decl, const Token& v, const TypeInfo& info, Parameter& p) {
        // Numbers, the common case, first and without building any message.
        if (info.arity != 0 && !v.quoted() && std::string_view(info.name) != "bool") {
            double x = 0.0;
            if (parseNumber(v.text, x) && std::isfinite(x) &&
                (std::string_view(info.name) != "integer" || x == std::floor(x))) {
                p.numbers.push_back(x);
                return;
            }
        }
        const std::string what = "\"" + unquote(decl.text) + "\"";
        if (info.arity == 0 || (std::string_view(info.name) == "spectrum" && v.quoted())) {
            if (!v.quoted()) error(tokens, v, what + ": expected a quoted string, got '" + std::string(v.text) + "'");
            p.strings.push_back(unquote(v.text));
            return;
        }
        if (std::string_view(info.name) == "bool") {
            const std::string s = v.quoted() ? unquote(v.text) : std::string(v.text);
            if (s == "true") p.numbers.push_back(1.0);
            else if (s == "false") p.numbers.push_back(0.0);
            else error(tokens, v, what + ": expected true or false, got '" + s + "'");
            return;
        }
        double x = 0.0;
        if (v.quoted() || !parseNumber(v.text, x))
            error(tokens, v, what + ": expected a number, got '" + std::string(v.text) + "'");
        if (!std::isfinite(x)) error(tokens, v, what + ": the number is not finite");
        if (std::string_view(info.name) == "integer" && x != std::floor(x))
            error(tokens, v, what + ": expected an integer, got '" + std::string(v.text) + "'");
        p.numbers.push_back(x);
    }

    static void values(Tokenizer& tokens, const Token& decl, const TypeInfo& info, Parameter& p) {
        const Token first = need(tokens, decl, "a value");
        if (first.is("[")) {
            for (;;) {
                const Token v = need(tokens, decl, "]");
                if (v.is("]")) break;
                value(tokens, decl, v, info, p);
            }
        } else {
            value(tokens, decl, first, info, p);
        }
        const std::string what = "\"" + unquote(decl.text) + "\"";
        if (p.numbers.empty() && p.strings.empty()) error(tokens, decl, what + ": no value");
        if (!p.numbers.empty() && !p.strings.empty())
            error(tokens, decl, what + ": numbers and strings mixed");
        if (p.type == "spectrum" && !p.strings.empty() && p.strings.size() != 1)
            error(tokens, decl, what + ": one spectrum name or file");
        else if (p.type == "blackbody" && p.numbers.size() != 1)
            error(tokens, decl, what + ": one temperature in kelvin (pbrt-v4 takes no scale here; use \"float scale\")");
        else if (!p.numbers.empty() && info.arity > 1 && p.numbers.size() % static_cast<size_t>(info.arity) != 0)
            error(tokens, decl, what + ": " + std::to_string(p.numbers.size()) + " numbers is not a multiple of " +
                                    std::to_string(info.arity));
    }

    // --- transforms ----------------------------------------------------
    void apply(const glm::dmat4& m) {
        for (int i = 0; i < 2; ++i)
            if (state_.active & (1u << i)) state_.ctm[i] = state_.ctm[i] * m;
    }
    void set(const glm::dmat4& m) {
        for (int i = 0; i < 2; ++i)
            if (state_.active & (1u << i)) state_.ctm[i] = m;
    }

    // The CTM where something is placed that cannot move (the camera, a
    // light, a shape inside ObjectBegin): an animated one is an error.
    glm::dmat4 placement(const Tokenizer& tokens, const Token& t, const char* what) const {
        if (state_.ctm[0] != state_.ctm[1])
            error(tokens, t, std::string(t.text) + ": the start and end transforms differ (ActiveTransform): " + what +
                                 " cannot move in strahl (shapes and object instances can)");
        return state_.ctm[0];
    }
    // The CTM where a shape or an instance is placed, and its end transform
    // when it is animated (motion blur).
    glm::dmat4 movingPlacement(std::optional<glm::dmat4>& end) const {
        if (state_.ctm[0] != state_.ctm[1]) end = state_.ctm[1];
        return state_.ctm[0];
    }

    void requireWorld(const Tokenizer& tokens, const Token& t, bool inside) const {
        if (inWorld_ != inside)
            error(tokens, t, std::string(t.text) + (inside ? " must come after WorldBegin" : " must come before WorldBegin"));
    }

    Entity entity(Tokenizer& tokens, const Token& t) {
        Entity e;
        e.directive = std::string(t.text);
        e.type = needString(tokens, t);
        e.place = at(tokens, t);
        e.params = parameters(tokens, t);
        return e;
    }

    void include(Tokenizer& tokens, const Token& t, int depth) {
        const std::string name = needString(tokens, t);
        if (depth + 1 > kMaxIncludeDepth) error(tokens, t, "Include: nested deeper than 32 files");
        const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : scene_.folder / name;
        if (openFiles_.count(fileIdentity(path)))
            error(tokens, t, std::string(t.text) + " \"" + name + "\": the file includes itself (a cycle)");
        std::error_code ec;
        if (!fs::is_regular_file(path, ec))
            error(tokens, t, std::string(t.text) + " \"" + name + "\": cannot open " + path.string() + " (" +
                                 (ec && ec != std::errc::no_such_file_or_directory ? ec.message()
                                  : fs::exists(path, ec)                           ? "not a regular file"
                                                                                   : "no such file") +
                                 ")");
        if (name.size() > 3 && name.substr(name.size() - 3) == ".gz")
            error(tokens, t, std::string(t.text) + " \"" + name + "\": compressed scene files are not supported");
        // Tokenized in place from a memory map: an included geometry file of
        // gigabytes is never copied.
        std::optional<meshio::MappedFile> mapped;
        try {
            mapped.emplace(path);
        } catch (const Error& e) {
            error(tokens, t, std::string(t.text) + " \"" + name + "\": " + e.what());
        }
        parseFile(mapped->bytes(), name, path, depth + 1);
    }

    void directive(Tokenizer& tokens, const Token& t, int depth) {
        if (t.quoted() || t.is("[") || t.is("]"))
            error(tokens, t, "expected a directive, got " + std::string(t.text));
        const std::string_view d = t.text;
        if (d == "Include") {
            include(tokens, t, depth);
        } else if (d == "Import") {
            // Imported files see the graphics state but do not change it.
            requireWorld(tokens, t, true);
            const GraphicsState saved = state_;
            const size_t depthBefore = stack_.size();
            include(tokens, t, depth);
            if (stack_.size() != depthBefore) error(tokens, t, "Import: the imported file leaves an AttributeBegin open");
            state_ = saved;
        } else if (d == "Identity") {
            set(glm::dmat4(1.0));
        } else if (d == "Translate") {
            const std::vector<double> v = needNumbers(tokens, t, 3);
            apply(glm::translate(glm::dmat4(1.0), glm::dvec3(v[0], v[1], v[2])));
        } else if (d == "Scale") {
            const std::vector<double> v = needNumbers(tokens, t, 3);
            apply(glm::scale(glm::dmat4(1.0), glm::dvec3(v[0], v[1], v[2])));
        } else if (d == "Rotate") {
            const std::vector<double> v = needNumbers(tokens, t, 4);
            const glm::dvec3 axis(v[1], v[2], v[3]);
            if (!(glm::length(axis) > 0.0)) error(tokens, t, "Rotate: the axis is zero");
            apply(glm::rotate(glm::dmat4(1.0), glm::radians(v[0]), glm::normalize(axis)));
        } else if (d == "LookAt") {
            const std::vector<double> v = needNumbers(tokens, t, 9);
            apply(lookAt(tokens, t, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}));
        } else if (d == "Transform" || d == "ConcatTransform") {
            const std::vector<double> v = needNumbers(tokens, t, 16);
            // The 16 numbers are the matrix column by column (pbrt transposes
            // the row-major list it reads).
            const glm::dmat4 m = glm::make_mat4(v.data());
            if (d == "Transform") set(m);
            else apply(m);
        } else if (d == "CoordinateSystem") {
            coordinateSystems_[needString(tokens, t)] = state_.ctm[0];
        } else if (d == "CoordSysTransform") {
            const std::string name = needString(tokens, t);
            const auto found = coordinateSystems_.find(name);
            if (found == coordinateSystems_.end())
                error(tokens, t, "CoordSysTransform: no coordinate system named \"" + name + "\"");
            set(found->second);
        } else if (d == "ReverseOrientation") {
            state_.reverseOrientation = !state_.reverseOrientation;
        } else if (d == "ActiveTransform") {
            const Token which = need(tokens, t, "StartTime, EndTime or All");
            if (which.is("StartTime")) state_.active = 1;
            else if (which.is("EndTime")) state_.active = 2;
            else if (which.is("All")) state_.active = 3;
            else error(tokens, which, "ActiveTransform: expected StartTime, EndTime or All");
        } else if (d == "TransformTimes") {
            const double start = needNumber(tokens, t), end = needNumber(tokens, t);
            if (!(start <= end)) error(tokens, t, "TransformTimes: the start time must not come after the end time");
            scene_.transformStart = start;
            scene_.transformEnd = end;
        } else if (d == "AttributeBegin" || d == "TransformBegin") {
            GraphicsState saved = state_;
            saved.place = at(tokens, t);
            saved.transformOnly = d == "TransformBegin";
            stack_.push_back(saved);
        } else if (d == "AttributeEnd" || d == "TransformEnd") {
            if (stack_.empty() || stack_.back().transformOnly != (d == "TransformEnd"))
                error(tokens, t, std::string(d) + " without a matching " +
                                     (d == "AttributeEnd" ? "AttributeBegin" : "TransformBegin"));
            if (stack_.back().transformOnly) {
                state_.ctm[0] = stack_.back().ctm[0];
                state_.ctm[1] = stack_.back().ctm[1];
                state_.active = stack_.back().active;
            } else {
                state_ = stack_.back();
            }
            stack_.pop_back();
        } else if (d == "Attribute") {
            const std::string target = needString(tokens, t);
            ParameterList list = parameters(tokens, t);
            ParameterList* into = target == "shape"      ? &state_.shapeDefaults
                                  : target == "light"    ? &state_.lightDefaults
                                  : target == "material" ? &state_.materialDefaults
                                  : target == "texture"  ? &state_.textureDefaults
                                                         : nullptr;
            if (!into) {
                if (target == "medium") error(tokens, t, "Attribute \"medium\": participating media are not supported");
                error(tokens, t, "Attribute: unknown target \"" + target + "\" (shape, light, material, medium, texture)");
            }
            for (Parameter& p : list.items) {
                std::erase_if(into->items, [&](const Parameter& q) { return q.name == p.name; });
                into->items.push_back(std::move(p));
            }
        } else if (d == "Option") {
            const Token decl = need(tokens, t, "an option");
            tokens.putBack(decl);
            const ParameterList list = parameters(tokens, t);
            // Options choose how pbrt runs (threads, seeds, GPU, ...), not what
            // the scene looks like, except these:
            for (const Parameter& p : list.items)
                if (p.name == "disablepixeljitter" || p.name == "disablewavelengthjitter" ||
                    p.name == "forcediffuse" || p.name == "displacementedgescale" || p.name == "wavefront")
                    error(tokens, t, "Option \"" + p.name + "\" is not supported");
        } else if (d == "ColorSpace") {
            const std::string name = needString(tokens, t);
            if (name != "srgb") error(tokens, t, "ColorSpace \"" + name + "\": strahl renders in sRGB (Rec. 709) only");
        } else if (d == "Camera") {
            requireWorld(tokens, t, false);
            Entity e = entity(tokens, t);
            scene_.cameraFromWorld = placement(tokens, t, "the camera");
            coordinateSystems_["camera"] = glm::inverse(scene_.cameraFromWorld);
            scene_.camera = std::move(e);
        } else if (d == "Film" || d == "Sampler" || d == "Integrator" || d == "PixelFilter" || d == "Accelerator") {
            requireWorld(tokens, t, false);
            Entity e = entity(tokens, t);
            if (d == "Film") scene_.film = std::move(e);
            else if (d == "Sampler") scene_.sampler = std::move(e);
            else if (d == "Integrator") scene_.integrator = std::move(e);
            else if (d == "PixelFilter") scene_.filter = std::move(e);
            // Accelerator: how pbrt builds its BVH, not what it shows.
        } else if (d == "MakeNamedMedium") {
            error(tokens, t, "MakeNamedMedium: participating media are not supported");
        } else if (d == "MediumInterface") {
            const std::string inside = needString(tokens, t);
            const Token next = need(tokens, t, "a string");
            std::string outside = inside;
            if (next.quoted()) outside = unquote(next.text);
            else tokens.putBack(next);
            if (!inside.empty() || !outside.empty())
                error(tokens, t, "MediumInterface: participating media are not supported");
        } else if (d == "WorldBegin") {
            requireWorld(tokens, t, false);
            inWorld_ = true;
            state_.ctm[0] = state_.ctm[1] = glm::dmat4(1.0);
            state_.active = 3;
            coordinateSystems_["world"] = glm::dmat4(1.0);
        } else if (d == "WorldEnd") {
            // pbrt-v3's end of the world block; pbrt-v4 files have none.
        } else if (d == "Material") {
            requireWorld(tokens, t, true);
            Entity e = entity(tokens, t);
            e.params.addDefaults(state_.materialDefaults);
            scene_.materials.push_back(std::move(e));
            state_.material = static_cast<int>(scene_.materials.size()) - 1;
            state_.namedMaterial.clear();
        } else if (d == "MakeNamedMaterial") {
            requireWorld(tokens, t, true);
            Entity e;
            e.directive = "MakeNamedMaterial";
            const std::string name = needString(tokens, t);
            e.place = at(tokens, t);
            e.params = parameters(tokens, t);
            e.params.addDefaults(state_.materialDefaults);
            const Parameter* type = e.params.find("type");
            if (!type || type->type != "string")
                error(tokens, t, "MakeNamedMaterial \"" + name + "\": needs \"string type\"");
            type->used = true;
            e.type = type->strings[0];
            if (scene_.namedMaterials.count(name))
                error(tokens, t, "MakeNamedMaterial: a material named \"" + name + "\" is already defined");
            scene_.materials.push_back(std::move(e));
            scene_.namedMaterials[name] = static_cast<int>(scene_.materials.size()) - 1;
        } else if (d == "NamedMaterial") {
            requireWorld(tokens, t, true);
            // May name a material made later in the file (pbrt resolves the
            // names when the file is read).
            state_.namedMaterial = needString(tokens, t);
            namedMaterialPlace_[state_.namedMaterial] = at(tokens, t);
        } else if (d == "Texture") {
            requireWorld(tokens, t, true);
            Texture tex;
            tex.name = needString(tokens, t);
            tex.valueType = needString(tokens, t);
            if (tex.valueType == "color") tex.valueType = "spectrum";
            if (tex.valueType != "float" && tex.valueType != "spectrum")
                error(tokens, t, "Texture \"" + tex.name + "\": the value type must be \"float\" or \"spectrum\", got \"" +
                                     tex.valueType + "\"");
            tex.entity = entity(tokens, t);
            tex.entity.params.addDefaults(state_.textureDefaults);
            // Only 3D texture mappings read the CTM; the mapping refuses them.
            auto& into = tex.valueType == "float" ? scene_.floatTextures : scene_.spectrumTextures;
            into[tex.name] = std::move(tex);
        } else if (d == "LightSource") {
            requireWorld(tokens, t, true);
            Light light;
            light.entity = entity(tokens, t);
            light.entity.params.addDefaults(state_.lightDefaults);
            light.toWorld = placement(tokens, t, "a light");
            scene_.lights.push_back(std::move(light));
        } else if (d == "AreaLightSource") {
            requireWorld(tokens, t, true);
            Entity e = entity(tokens, t);
            e.params.addDefaults(state_.lightDefaults);
            scene_.areaLights.push_back(std::move(e));
            state_.areaLight = static_cast<int>(scene_.areaLights.size()) - 1;
        } else if (d == "Shape") {
            requireWorld(tokens, t, true);
            Shape s;
            s.entity = entity(tokens, t);
            s.entity.params.addDefaults(state_.shapeDefaults);
            s.toWorld = currentObject_ ? placement(tokens, t, "a shape inside ObjectBegin") : movingPlacement(s.toWorldEnd);
            s.reverseOrientation = state_.reverseOrientation;
            s.material = state_.material;
            s.materialName = state_.namedMaterial;
            s.areaLight = state_.areaLight;
            if (currentObject_) {
                // pbrt-v4 ignores area lights in object definitions: the
                // shape is placed, and does not emit.
                if (s.areaLight >= 0) {
                    meshio::reportWarning(s.entity.place.text() + ": " + s.entity.element() +
                                          ": an area light inside ObjectBegin is ignored (as pbrt-v4 ignores it)");
                    s.areaLight = -1;
                }
                currentObject_->shapes.push_back(std::move(s));
            } else {
                scene_.shapes.push_back(std::move(s));
            }
        } else if (d == "ObjectBegin") {
            requireWorld(tokens, t, true);
            if (currentObject_) error(tokens, t, "ObjectBegin inside ObjectBegin \"" + currentObject_->name + "\"");
            const std::string name = needString(tokens, t);
            if (scene_.objects.count(name)) error(tokens, t, "ObjectBegin: an object named \"" + name + "\" is already defined");
            GraphicsState saved = state_;
            saved.place = at(tokens, t);
            stack_.push_back(saved);
            currentObject_ = ObjectDefinition{name, {}, at(tokens, t)};
        } else if (d == "ObjectEnd") {
            if (!currentObject_) error(tokens, t, "ObjectEnd without ObjectBegin");
            if (stack_.empty() || stack_.back().transformOnly)
                error(tokens, t, "ObjectEnd: an AttributeBegin or TransformBegin inside the object is not closed");
            state_ = stack_.back();
            stack_.pop_back();
            std::string name = currentObject_->name;
            scene_.objects[name] = std::move(*currentObject_);
            currentObject_.reset();
        } else if (d == "ObjectInstance") {
            requireWorld(tokens, t, true);
            if (currentObject_) error(tokens, t, "ObjectInstance inside ObjectBegin: instances cannot be nested (as in pbrt-v4)");
            const std::string name = needString(tokens, t);
            Instance instance{name, glm::dmat4(1.0), at(tokens, t), std::nullopt};
            instance.toWorld = movingPlacement(instance.toWorldEnd);
            scene_.instances.push_back(std::move(instance));
        } else {
            error(tokens, t, "unknown directive '" + std::string(d) + "'");
        }
    }

    // pbrt's LookAt: the camera-from-world transform of a camera at `eye`
    // looking at `look`, its +z along the view, +y up and +x = up × dir.
    static glm::dmat4 lookAt(const Tokenizer& tokens, const Token& t, glm::dvec3 eye, glm::dvec3 look,
                             glm::dvec3 up) {
        const glm::dvec3 dir = look - eye;
        if (!(glm::length(dir) > 0.0)) error(tokens, t, "LookAt: the eye and the point looked at coincide");
        const glm::dvec3 z = glm::normalize(dir);
        if (!(glm::length(up) > 0.0)) error(tokens, t, "LookAt: the up vector is zero");
        const glm::dvec3 c = glm::cross(glm::normalize(up), z);
        if (!(glm::length(c) > 1e-9)) error(tokens, t, "LookAt: the up vector and the viewing direction are parallel");
        const glm::dvec3 x = glm::normalize(c);
        const glm::dvec3 y = glm::cross(z, x);
        const glm::dmat4 worldFromCamera(glm::dvec4(x, 0), glm::dvec4(y, 0), glm::dvec4(z, 0), glm::dvec4(eye, 1));
        return glm::inverse(worldFromCamera);
    }
};

}  // namespace

Scene readScene(const std::string& text, const fs::path& file, const std::string& label) {
    Parser parser(file);
    parser.parseFile(text, label, file, 0);
    return parser.finish(label);
}

}  // namespace strahl::scene_detail::pbrt
