#pragma once
// The scene file as a JSON document, between reading and parsing: where
// command-line overrides apply, as JSON-pointer assignments ("scene patches",
// `strahl render --set /render/spp=64`), and what a render's fingerprint
// hashes, so that every setting the document holds is part of it without a
// hand-kept list. A scene file in another renderer's format becomes such a
// document through its importer (src/scene/scene_formats.h), chosen by the
// file's extension; strahl's JSON is the default.
//
// parseSceneFile(file) is SceneDocument::read(file).parse().

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/scene/scene_desc.h"

namespace strahl {

// One assignment to the document: `value` (JSON text) at `pointer` (RFC 6901,
// "/render/spp"; missing objects on the way are created).
struct ScenePatch {
    std::string pointer;
    std::string value;
    std::string origin;  // what the user typed, for messages: "--spp 64"
};

// "--set POINTER=VALUE": VALUE is JSON (64, true, [1, 2], {"type": "box"},
// "text"), or else a plain string (`--set /render/integrator=path`). Throws
// strahl::Error "--set ARG: ..." for an argument without '=' or whose pointer
// is not an RFC 6901 JSON pointer ("/key/key/index").
ScenePatch parseSetArgument(std::string_view argument);

// -D name=value: values for the parameters of scene formats that have them
// (a Mitsuba scene's <default>s); strahl JSON has none and refuses them.
using SceneDefines = std::map<std::string, std::string>;

class SceneDocument {
public:
    // Throws strahl::Error "<file>: cannot open: ..." or
    // "<file>:LINE:COLUMN: syntax error: ..." (or the importer's error for
    // another format: "<file>:LINE: ...").
    static SceneDocument read(const std::filesystem::path& file, const SceneDefines& defines = {});
    // The same from text; `file` names it in errors, anchors relative paths
    // and, by its extension, picks the format.
    static SceneDocument fromText(const std::string& text, const std::filesystem::path& file,
                                  const SceneDefines& defines = {});

    SceneDocument(SceneDocument&&) noexcept;
    SceneDocument& operator=(SceneDocument&&) noexcept;
    ~SceneDocument();

    // Assigns the patch's value. Throws "<file>: <place> is a number, not an
    // object (<origin>)" when the pointer runs through a value that is not an
    // object (or an array, with an index in range), "<origin>: ..." for a
    // malformed pointer or value; nothing is changed then.
    void apply(const ScenePatch& patch);
    // The patches applied so far, in order.
    const std::vector<ScenePatch>& patches() const;

    // The SceneDesc of the document as patched. An error at a place a patch
    // wrote (or inside or above it) names the patches: "... (set by --spp 0)".
    SceneDesc parse() const;

    // 64-bit FNV-1a of the document in canonical form (keys sorted, no
    // comments or spacing), leaving out the values at `without` (pointers
    // that need not exist).
    uint64_t hash(std::initializer_list<std::string_view> without = {}) const;

    const std::filesystem::path& file() const;
    // The document as strahl JSON text, indented by `indent` spaces (what
    // `strahl convert` writes).
    std::string text(int indent = 2) const;
    // text() for a file written at `destination`: relative file names (of
    // meshes, images, textures, patch files, outputs) rewritten relative to
    // the destination's folder instead of the scene file's.
    std::string textFor(const std::filesystem::path& destination) const;

private:
    struct Impl;
    explicit SceneDocument(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace strahl
