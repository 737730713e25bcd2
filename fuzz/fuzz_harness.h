#pragma once
// What each fuzz target does with one input, shared by the libFuzzer entry
// points in fuzz/fuzz_*.cpp and the regression test that replays the inputs
// they found (tests/scene/fuzz_regression_test.cpp). Every function either
// returns or throws strahl::Error; anything else (another exception, a crash, a
// leak, undefined behaviour) is a bug. docs/reliability.md, "Fuzzing".
//
// Inputs are anchored in a per-process scratch folder below the temporary
// directory (a name that exists nowhere else), so relative paths in them
// resolve to nothing but what the harness itself writes there.

#include <unistd.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "strahl/core/dual.h"
#include "strahl/core/error.h"
#include "strahl/core/interval.h"
#include "strahl/geometry/formula.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"

namespace strahl::fuzz {

inline std::string_view asText(const uint8_t* data, size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// temp/strahl-fuzz-<pid>, created on first use and removed at exit.
class ScratchFolder {
public:
    ScratchFolder() {
        std::error_code ec;
        path_ = std::filesystem::temp_directory_path(ec);
        if (ec) path_ = "/tmp";
        path_ /= "strahl-fuzz-" + std::to_string(::getpid());
        std::filesystem::create_directories(path_, ec);
    }
    ~ScratchFolder() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline const std::filesystem::path& scratch() {
    static const ScratchFolder folder;
    return folder.path();
}

// Mesh warnings are expected for most inputs: drop them (printing them would
// slow the fuzzer down and bury its report).
inline void quietMeshWarnings() {
    static const bool once = [] {
        setMeshWarningHandler([](const std::string&) {});
        return true;
    }();
    (void)once;
}

// ---- scene JSON --------------------------------------------------------------------

// The input is a scene file's text.
inline void runSceneJson(std::string_view input) {
    const SceneDesc scene = parseSceneText(std::string(input), scratch() / "scene.json");
    (void)scene;
}

// ---- Mitsuba 3 scenes ------------------------------------------------------------

// The input is a Mitsuba 3 scene file's text, imported into a strahl scene
// document and parsed (src/scene/mitsuba_*.cpp). File names it gives resolve
// in the scratch folder, where nothing is.
inline void runMitsubaXml(std::string_view input) {
    const SceneDesc scene =
        SceneDocument::fromText(std::string(input), scratch() / "scene.xml").parse();
    (void)scene;
}

// The input is a pbrt-v4 scene file (its Includes resolve in the scratch folder).
inline void runPbrt(std::string_view input) {
    quietMeshWarnings();
    const SceneDesc scene =
        SceneDocument::fromText(std::string(input), scratch() / "scene.pbrt").parse();
    (void)scene;
}

// ---- meshes ----------------------------------------------------------------------

// The input is a PLY file, ascii or binary.
inline void runPly(std::string_view input) {
    quietMeshWarnings();
    const LoadedMesh mesh = loadPlyFromMemory(input, scratch() / "fuzz.ply");
    (void)mesh;
}

// The input is a .serialized file; its first and its second mesh are read.
inline void runSerialized(std::string_view input) {
    for (uint32_t index : {0u, 1u}) {
        const LoadedMesh mesh = loadSerializedFromMemory(input, scratch() / "fuzz.serialized", index);
        (void)mesh;
    }
}

// The input is an OBJ file, optionally followed by a line "@mtl" and the text of
// a material library: that part is written to <scratch>/m.mtl (which the OBJ
// part names with "mtllib m.mtl"), so one input covers both parsers.
inline constexpr std::string_view kMtlSeparator = "\n@mtl\n";

inline void runObj(std::string_view input) {
    quietMeshWarnings();
    const std::filesystem::path mtl = scratch() / "m.mtl";
    const size_t split = input.find(kMtlSeparator);
    std::string_view obj = input;
    if (split != std::string_view::npos) {
        obj = input.substr(0, split);
        const std::string_view library = input.substr(split + kMtlSeparator.size());
        if (std::FILE* f = std::fopen(mtl.c_str(), "wb")) {
            std::fwrite(library.data(), 1, library.size(), f);
            std::fclose(f);
        }
    } else {
        std::error_code ec;
        std::filesystem::remove(mtl, ec);
    }
    const LoadedMesh mesh = loadObjFromMemory(obj, scratch() / "fuzz.obj");
    (void)mesh;
}

// The input is a .gltf (JSON) or .glb (binary) file; the loader tells them apart
// by the GLB magic, not by the name.
inline void runGltf(std::string_view input) {
    quietMeshWarnings();
    const LoadedMesh mesh = loadGltfFromMemory(input, scratch() / "fuzz.gltf");
    (void)mesh;
}

// ---- formulas ----------------------------------------------------------------------

// The input's first line is a formula in x, y and z; every further line
// "name=value" is a parameter (a value that does not parse is NaN, which the
// compiler must reject). A formula that compiles is evaluated in every
// arithmetic the renderer uses, at a few points, boxes and ray segments.
inline void runFormula(std::string_view input) {
    const size_t eol = input.find('\n');
    const std::string_view text = input.substr(0, eol);
    std::map<std::string, double> parameters;
    for (size_t start = eol; start != std::string_view::npos && start < input.size();) {
        const size_t end = input.find('\n', start + 1);
        const std::string_view line =
            input.substr(start + 1, end == std::string_view::npos ? end : end - start - 1);
        start = end;
        const size_t equals = line.find('=');
        if (equals == std::string_view::npos) continue;
        const std::string_view value = line.substr(equals + 1);
        double number = 0.0;
        const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), number);
        if (ec != std::errc() || next != value.data() + value.size()) number = std::nan("");
        parameters[std::string(line.substr(0, equals))] = number;
    }
    static const std::string kVariables[] = {"x", "y", "z"};
    const Formula f = Formula::compile(text, kVariables, parameters);

    volatile double sink = 0.0;  // keeps the evaluations from being optimised away
    static constexpr std::array<std::array<double, 3>, 5> kPoints = {{
        {0.0, 0.0, 0.0},
        {1.0, -2.0, 0.5},
        {-0.75, 1e-300, 3.25},
        {1e6, -1e-6, 42.0},
        {1e300, -1e300, 5e-324},
    }};
    for (const auto& p : kPoints) {
        sink = sink + f.evaluate<double>(p.data());
        const num::Gradient3 g[3] = {num::Gradient3::variable(p[0], 0),
                                     num::Gradient3::variable(p[1], 1),
                                     num::Gradient3::variable(p[2], 2)};
        const num::Gradient3 gradient = f.evaluate<num::Gradient3>(g);
        sink = sink + gradient.v + gradient.d[0] + gradient.d[1] + gradient.d[2];
    }
    using num::Interval;
    static constexpr std::array<std::array<std::pair<double, double>, 3>, 4> kBoxes = {{
        {{{-1.0, 1.0}, {-1.0, 1.0}, {-1.0, 1.0}}},
        {{{0.5, 2.0}, {-3.0, -0.25}, {0.0, 0.0}}},
        {{{-1e-3, 1e6}, {2.0, 2.0}, {-1e300, 1e300}}},
        {{{-num::kInf, num::kInf}, {0.0, num::kInf}, {-num::kInf, -1.0}}},
    }};
    for (const auto& box : kBoxes) {
        const Interval x[3] = {Interval(box[0].first, box[0].second),
                               Interval(box[1].first, box[1].second),
                               Interval(box[2].first, box[2].second)};
        const Interval range = f.evaluate<Interval>(x);
        sink = sink + range.lo + range.hi;
        // Along a ray through the box: p(t) = o + t d with t in [0, 1].
        const num::RayDual t = num::RayDual::variable(Interval(0.0, 1.0), 0);
        num::RayDual ray[3];
        for (int i = 0; i < 3; ++i) {
            const double o = std::isfinite(x[i].lo) ? x[i].lo : -1.0;
            const double d = std::isfinite(x[i].hi) ? x[i].hi - o : 2.0;
            ray[i] = t * num::RayDual(d) + num::RayDual(o);
        }
        const num::RayDual along = f.evaluate<num::RayDual>(ray);
        sink = sink + along.v.lo + along.v.hi + along.d[0].lo + along.d[0].hi;
    }
}

// Calls run(input) and swallows strahl::Error, the loaders' and parsers' only
// way of rejecting an input; anything else propagates (and crashes the fuzzer).
template <typename Run>
void expectErrorOrSuccess(Run&& run, std::string_view input) {
    try {
        run(input);
    } catch (const Error&) {
    }
}

}  // namespace strahl::fuzz
