// SceneDocument: the scene file's JSON between reading and parsing, with the
// command line's patches applied (scene_document.h).
//
// A patch walks its pointer's tokens from the root: a missing or null level
// becomes an object, an object member is created when missing, an array
// element must exist (index < size). Anything else (a number on the way, a
// bad index) is the patch's error, named by its origin. The value is JSON,
// or else taken as a string, so `--set /render/integrator=path` needs no
// quotes.

#include "strahl/scene/scene_document.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "json_reader.h"
#include "scene_formats.h"
#include "scene_json.h"
#include "scene_place.h"
#include "strahl/core/error.h"
#include "strahl/core/hash.h"

namespace strahl {

namespace fs = std::filesystem;
using nlohmann::json;

struct SceneDocument::Impl {
    json document;
    fs::path file;
    std::string label;  // how errors name the file: as the user gave it
    std::vector<ScenePatch> patches;
};

namespace {

// The reference tokens of a pointer, first to last (json_pointer keeps them
// but shows only the last).
std::vector<std::string> tokensOf(json::json_pointer pointer) {
    std::vector<std::string> tokens;
    while (!pointer.empty()) {
        tokens.push_back(pointer.back());
        pointer.pop_back();
    }
    std::reverse(tokens.begin(), tokens.end());
    return tokens;
}

// "0", "12": an array index as RFC 6901 writes it (no sign, no leading zero).
std::optional<size_t> arrayIndex(const std::string& token) {
    if (token.empty() || token.size() > 18 || (token.size() > 1 && token[0] == '0')) return {};
    if (!std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return {};
    return std::stoull(token);
}

// RFC 6901 escaping of one token, for messages.
std::string escapeToken(const std::string& token) {
    std::string out;
    for (char c : token) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    return out;
}

bool startsWith(std::string_view text, std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
}

// A patch and an error's place are related when one contains the other.
bool related(const std::string& patched, const std::string& where) {
    return patched == where || startsWith(patched, where + "/") || startsWith(where, patched + "/");
}

}  // namespace

ScenePatch parseSetArgument(std::string_view argument) {
    const std::string origin = "--set " + std::string(argument);
    const size_t equals = argument.find('=');
    if (equals == std::string_view::npos)
        fail(origin, ": expected POINTER=VALUE, such as /render/spp=64");
    ScenePatch patch{std::string(argument.substr(0, equals)), {}, origin};
    if (!startsWith(patch.pointer, "/"))
        fail(origin, ": the pointer must start with '/', such as /render/spp");
    try {
        (void)json::json_pointer(patch.pointer);
    } catch (const json::exception&) {
        fail(origin, ": '", patch.pointer, "' is not a JSON pointer (RFC 6901: /key/key/index)");
    }
    const std::string_view value = argument.substr(equals + 1);
    // JSON if it is JSON, else the text as a string.
    const json parsed = json::parse(value, nullptr, /*allow_exceptions=*/false);
    patch.value = parsed.is_discarded() ? json(std::string(value)).dump() : parsed.dump();
    return patch;
}

SceneDocument::SceneDocument(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SceneDocument::SceneDocument(SceneDocument&&) noexcept = default;
SceneDocument& SceneDocument::operator=(SceneDocument&&) noexcept = default;
SceneDocument::~SceneDocument() = default;

SceneDocument SceneDocument::fromText(const std::string& text, const fs::path& file,
                                      const SceneDefines& defines) {
    auto impl = std::make_unique<Impl>();
    impl->label = file.string();
    impl->document = scene_detail::sceneFormatOf(file).toDocument(text, file, impl->label, defines);
    impl->file = fs::absolute(file).lexically_normal();
    return SceneDocument(std::move(impl));
}

SceneDocument SceneDocument::read(const fs::path& file, const SceneDefines& defines) {
    const std::string label = file.string();
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(std::fopen(file.c_str(), "rb"),
                                                                 &std::fclose);
    if (!stream) fail(label, ": cannot open: ", std::strerror(errno));
    std::string text;
    std::array<char, 1 << 16> buffer;
    size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), stream.get())) > 0)
        text.append(buffer.data(), n);
    if (std::ferror(stream.get())) fail(label, ": cannot read: ", std::strerror(errno));
    return fromText(text, file, defines);
}

std::string SceneDocument::text(int indent) const { return impl_->document.dump(indent) + "\n"; }

namespace {

// The keys whose string values are file names (docs/scene-format.md).
bool namesFiles(const std::string& key) {
    return key == "file" || key == "texture" || key == "image" || key == "gltf" ||
           key == "outputs";
}

void rebase(json& value, const fs::path& from, const fs::path& to, bool isFile) {
    if (value.is_string() && isFile) {
        const fs::path name = value.get<std::string>();
        if (name.is_relative())
            value = (from / name).lexically_normal().lexically_relative(to).string();
    } else if (value.is_array()) {
        for (json& element : value) rebase(element, from, to, isFile);
    } else if (value.is_object()) {
        for (auto& [key, member] : value.items()) rebase(member, from, to, namesFiles(key));
    }
}

}  // namespace

std::string SceneDocument::textFor(const fs::path& destination) const {
    const fs::path from = impl_->file.parent_path();
    const fs::path to = fs::absolute(destination).lexically_normal().parent_path();
    if (from == to) return text();
    json copy = impl_->document;
    rebase(copy, from, to, false);
    return copy.dump(2) + "\n";
}

void SceneDocument::apply(const ScenePatch& patch) {
    json::json_pointer pointer;
    try {
        pointer = json::json_pointer(patch.pointer);
    } catch (const json::exception&) {
        fail(patch.origin, ": '", patch.pointer, "' is not a JSON pointer (RFC 6901: /key/key/index)");
    }
    json value;
    try {
        value = json::parse(patch.value);
    } catch (const json::exception&) {
        fail(patch.origin, ": the value is not JSON: ", patch.value);
    }
    json* node = &impl_->document;
    std::string at;
    for (const std::string& token : tokensOf(pointer)) {
        if (node->is_null()) *node = json::object();
        if (node->is_object()) {
            node = &(*node)[token];
        } else if (node->is_array()) {
            const std::optional<size_t> index = arrayIndex(token);
            if (!index || *index >= node->size())
                fail(impl_->label, ": ", at.empty() ? "the document" : at, " is an array of ",
                     node->size(), " values; '", token, "' is not an index in it (",
                     patch.origin, ")");
            node = &(*node)[*index];
        } else {
            fail(impl_->label, ": ", at.empty() ? "the document" : at, " is a ",
                 node->type_name(), ", not an object (", patch.origin, ")");
        }
        at += '/';  // two appends: GCC 12 warns falsely (-Wrestrict) on "/" + string
        at += escapeToken(token);
    }
    if (at.empty()) fail(patch.origin, ": cannot replace the whole document");
    *node = std::move(value);
    impl_->patches.push_back(patch);
}

const std::vector<ScenePatch>& SceneDocument::patches() const { return impl_->patches; }

const fs::path& SceneDocument::file() const { return impl_->file; }

SceneDesc SceneDocument::parse() const {
    std::vector<std::pair<std::string, std::string>> patches;
    for (const ScenePatch& p : impl_->patches) patches.emplace_back(p.pointer, p.origin);
    try {
        SceneDesc desc = scene_detail::parseSceneJson(impl_->document, impl_->file, impl_->label);
        desc.patches = std::move(patches);
        return desc;
    } catch (const scene_detail::JsonError& e) {
        // Patches at the error's place, inside it or above it are what the
        // user may have to change.
        const std::string origins = scene_detail::patchOrigins(patches, e.pointer());
        if (origins.empty()) throw;
        fail(e.what(), " (set by ", origins, ")");
    }
}

std::string scene_detail::patchOrigins(
    const std::vector<std::pair<std::string, std::string>>& patches, const std::string& pointer) {
    std::string origins;
    for (const auto& [patched, origin] : patches)
        if (!pointer.empty() && related(patched, pointer))
            origins += (origins.empty() ? "" : ", ") + origin;
    return origins;
}

void scene_detail::failAt(const SceneDesc& desc, const ScenePlace& at, const std::string& message) {
    const std::string text =
        concat(at.label, ": ", at.pointer.empty() ? "top level" : at.pointer, ": ", message);
    const std::string origins = patchOrigins(desc.patches, at.pointer);
    if (origins.empty()) throw Error(text);
    fail(text, " (set by ", origins, ")");
}

uint64_t SceneDocument::hash(std::initializer_list<std::string_view> without) const {
    json copy = impl_->document;
    for (std::string_view p : without) {
        const json::json_pointer pointer{std::string(p)};
        if (!copy.contains(pointer)) continue;
        json& parent = copy[pointer.parent_pointer()];
        if (parent.is_object()) parent.erase(pointer.back());
    }
    return fnv1a(copy.dump());
}

SceneDesc parseSceneText(const std::string& text, const fs::path& file) {
    return SceneDocument::fromText(text, file).parse();
}

SceneDesc parseSceneFile(const fs::path& file) {
    return SceneDocument::read(file).parse();
}

}  // namespace strahl
