#pragma once
// SceneDesc: the scene file as plain data. Parsing reads the scene file and
// nothing else: the files it names (meshes, a glTF file's cameras, Bézier
// patch files, height images, textures, environment images) are only checked
// to exist, and are read when the world is built (scene_builder.h), once per
// file. Every element remembers where it came from (a JSON pointer such as
// "/shapes/2") so that later stages can name the place in their errors.
// The file format is documented key by key in docs/scene-format.md.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "strahl/camera/camera.h"
#include "strahl/core/math.h"
#include "strahl/core/pixel_rect.h"
#include "strahl/film/film.h"
#include "strahl/geometry/catmull_clark.h"
#include "strahl/geometry/curve_set.h"
#include "strahl/geometry/formula.h"
#include "strahl/geometry/implicit_shape.h"
#include "strahl/geometry/parametric_shape.h"
#include "strahl/geometry/parametric_tessellation.h"
#include "strahl/geometry/triangle_mesh.h"
#include "strahl/integrator/light.h"
#include "strahl/material/material.h"

namespace strahl {

// A value of the scene document, for errors found when the file it names is
// read: "<label>: <pointer>: <message>", as the parser words its own errors.
struct ScenePlace {
    std::string label;    // the scene file as the user gave it
    std::string pointer;  // e.g. "/camera/gltf"
};

// A camera a glTF file places ("camera": {"gltf": FILE, "gltf_camera": ...}):
// its frame and projection are read from the file when the world is built
// (buildScene resolves it); the lens keys are the scene file's.
struct GltfCameraChoice {
    std::filesystem::path file;  // resolved; checked to exist
    // By name, or by index among the placed cameras (default 0); an index
    // that is negative or past 2^64 is kept as written, to be refused with
    // the count of cameras when the file is read.
    bool byName = false;
    std::string name;
    std::optional<uint64_t> index = 0;
    std::string indexText = "0";   // the index as written, for messages
    ScenePlace fileAt, cameraAt;  // "/camera/gltf", "/camera/gltf_camera"
};

struct CameraDesc {
    Projection projection = Projection::Perspective;
    Vec3 eye{0.0f, 0.0f, 5.0f};
    std::optional<Vec3> lookAt;  // exactly one of lookAt / back; default look_at (0,0,0)
    std::optional<Vec3> back;
    Vec3 up{0.0f, 1.0f, 0.0f};
    float focalDistance = 1.0f;
    std::optional<float> fovYDegrees;  // perspective only; exclusive with window
    std::optional<ImageWindow> window;  // default: fov 45 deg (persp.), [-1,1]^2 (ortho.)
    float apertureRadius = 0.0f;         // thin lens; 0: pinhole
    std::optional<float> focusDistance;  // default: the focal distance
    Shutter shutter;                     // "shutter": [open, close] in frame time
    // Set: the frame and projection above are still to be read from a glTF
    // file (buildScene fills them and clears this).
    std::optional<GltfCameraChoice> gltf;
};

// Image size limits, for the scene file and the command line alike: each side
// at most 32768 pixels and at most 2^28 pixels in all (16384^2, about 9 GiB of
// film buffers with every AOV).
inline constexpr int kMaxFilmSide = 32768;
inline constexpr long long kMaxFilmPixels = 1LL << 28;

struct FilmDesc {
    int width = 640;
    int height = 480;
    std::vector<std::filesystem::path> outputs;  // resolved against the scene folder
    std::vector<AovKind> aovs;
    bool exrFloat = false;
    std::string filter = "box";           // PixelFilter::names()
    std::optional<float> filterRadius;    // default: the filter's own
    // The pixels to render (as --crop, which overrides it); the whole film without.
    std::optional<PixelRect> crop;
};

struct RenderDesc {
    std::string integrator = "direct";  // integratorNames(): eyelight ... direct, ao, path
    int spp = 1;
    uint64_t seed = 0;
    int maxDepth = 8;            // path
    bool russianRoulette = true; // path
    // path: roulette from this bounce on, for paths whose throughput fell below
    // the threshold. Chosen by bench_roulette: the most efficient setting that
    // never loses against no roulette (bench/RESULTS.md, "Russian roulette").
    int russianRouletteDepth = 1;
    float russianRouletteThreshold = 0.5f;
    LightSelection lightSelection = LightSelection::Auto;  // path: next-event estimation
    // path: Cycles-style sample clamping, biased and off (0) by default: the
    // light of one sample after one reflection (direct) or more (indirect) is
    // scaled down so its largest channel is at most this.
    float clampDirect = 0.0f;
    float clampIndirect = 0.0f;
    // path: Cycles' "filter glossy", biased and off (0) by default: after rough
    // bounces, glossy and specular lobes are roughened (path_integrator.cpp).
    float filterGlossy = 0.0f;
    float aoDistance = 0.0f;     // ao (0: a quarter of the scene diagonal)
    int aoSamples = 1;           // ao
    bool hideEmitters = false;   // direct, path: emitters and the sky unseen by camera rays
    // Keep the even and odd samples' halves and write the NFOR-denoised beauty
    // as the main image (docs/denoising.md); ray tracing, at least 2 spp.
    bool denoise = false;
    // Adaptive sampling (render/adaptive_sampling.h, docs/adaptive.md): a
    // pixel stops once its noise and its neighbours' is below the threshold,
    // after at least min_samples samples; spp is then the most any pixel takes.
    float adaptiveThreshold = 0.0f;  // 0: off
    int adaptiveMinSamples = 16;
};

struct MaterialDesc {
    std::string name;
    Material material;  // kind and parameters; texture files named, handles not yet bound
    std::string where;
};

enum class ShapeKind { Mesh, Implicit, Parametric, Curves, Subdivision, Instance };

enum class ParametricMode { Tessellated, Direct };

// A parametric surface whose data is a file, read when the world is built:
// Bézier patches (.bpt; `reverse` swaps u and v in every patch) or a height
// image (`size` in x and y, `height` of a value of 1).
struct ParametricFile {
    enum class Kind { BezierPatches, HeightImage };
    Kind kind = Kind::BezierPatches;
    std::filesystem::path file;  // resolved
    bool reverse = false;
    Vec2 size{1.0f};
    double height = 1.0;
    ScenePlace at;  // "/shapes/0/surface/file" or ".../image"
};

// A parametric shape: its surface (built at parse time, so a bad formula is
// reported with its place; from `file` when the world is built) and how it is
// rendered.
struct ParametricDesc {
    ParametricSurfacePtr surface;    // null while `file` is to be read
    std::optional<ParametricFile> file;
    ParametricMode mode = ParametricMode::Tessellated;
    // Tessellated: uniform segments per patch and direction (the start of the
    // refinement when a bound is also given), and the adaptive bounds: chordal
    // error in object-space units, edge length in pixels from the camera.
    // Neither bound nor segments: maxError = kDefaultRelativeError × extent.
    int segmentsU = 0, segmentsV = 0;
    double maxError = 0.0;
    double maxEdgePixels = 0.0;
    ParametricNormals normals = ParametricNormals::Exact;
    // Direct: the sub-patch and Newton settings.
    ParametricShapeOptions direct;
};
// 5e-4 of the surface's extent is below half a pixel for a surface that fills
// a 1000-pixel-wide image.
inline constexpr double kDefaultRelativeError = 5e-4;

// A subdivision surface's displacement: h = scale × (the formula of x, y, z,
// u, v at the limit point, object space) or scale × (the image's value at the
// cage's uv), plus offset; along the unit normal, in object units.
struct DisplacementDesc {
    std::shared_ptr<const Formula> formula;  // null: an image
    std::filesystem::path image;             // resolved; read when the world is built
    double scale = 1.0;
    double offset = 0.0;
    std::string text;  // for messages and `strahl info`
};

// A "subdivision" shape: its control cage in object space (inline, or read
// from an OBJ file when the world is built), levels and displacement.
struct SubdivisionShapeDesc {
    SubdivisionCage cage;         // empty positions while `file` is to be read
    std::filesystem::path file;   // resolved OBJ cage, or empty
    int levels = 3;
    // When > 0, instead of `levels`: the fewest levels (1 … 8) that make
    // every refined cage edge at most this many pixels of the scene's camera,
    // capped so the refined surface fits the memory limit.
    double maxEdgePixels = 0.0;
    std::optional<DisplacementDesc> displacement;
};

struct ShapeDesc {
    ShapeKind kind = ShapeKind::Mesh;
    std::string name;                // optional label, defaults to the JSON pointer
    size_t group = 0;                // kind == Instance: index into SceneDesc::groups
    std::filesystem::path file;      // mesh file (resolved), empty for inline meshes
    // A file mesh's shading normals: the file's (flat where it has none),
    // none (flat), or the file's and else computed (smooth).
    enum class FileNormals { AsGiven, Flat, Smooth };
    FileNormals fileNormals = FileNormals::AsGiven;
    bool flipNormals = false;  // mesh, parametric: turn the front (winding and normals) around
    uint32_t shapeIndex = 0;   // mesh file: which mesh of a multi-mesh file (.serialized)
    TriangleMesh inlineMesh;         // used when file is empty
    ImplicitSurfacePtr implicitSurface;    // kind == Implicit: f, compiled at parse time
    ImplicitShapeOptions implicitOptions;  // its box, cells and tolerance
    ParametricDesc parametric;             // kind == Parametric
    // kind == Curves: type, basis and (inline) points and segments in object
    // space; with `file` (a strand file) the points are read when the world
    // is built.
    CurveSetDesc curves;
    bool curveRadiusFollowsTransform = true;  // "transform_radius"
    SubdivisionShapeDesc subdivision;         // kind == Subdivision
    Mat4 transform{1.0f};            // object to world (in a group: to the group's space)
    // kind == Instance: an instance array when not empty — the group placed
    // once per matrix, at transform · placement (group space to the array's,
    // then the array's to its parent's). From "placements" or "scatter".
    std::vector<Mat4> placements;
    // kind == Instance: when not empty, the instance moves — keyframes (at
    // least two) equally spaced over frame time [0, 1], each in place of
    // `transform` (core/motion.h). From "motion".
    std::vector<Mat4> motion;
    std::string material;            // empty: the file's own materials, else "default"
    std::string where;               // JSON pointer, e.g. "/shapes/0"
};

// A named group of shapes, stored once and placed by "instance" shapes (which
// may themselves be in groups: groups nest, without cycles).
struct GroupDesc {
    std::string name;
    std::vector<ShapeDesc> shapes;
    std::string where;  // JSON pointer, e.g. "/groups/0"
};

// Groups nest at most this deep (a chain longer than this is an error), which
// bounds the recursion of everything that walks them.
inline constexpr int kMaxGroupNesting = 64;

// A light of the scene file: its kind and parameters (strahl/integrator/light.h);
// an environment's image is named here and read when the world is built.
struct LightDesc {
    Light light;
    std::string where;
};

struct SceneDesc {
    std::filesystem::path file;  // the scene file itself (absolute)
    CameraDesc camera;
    FilmDesc film;
    RenderDesc render;
    Color background{0.0f};  // radiance of rays that escape
    std::vector<MaterialDesc> materials;
    std::vector<GroupDesc> groups;
    std::vector<ShapeDesc> shapes;
    std::vector<LightDesc> lights;
    // The patches applied to the document (pointer, origin such as "--spp 4"),
    // so errors found after parsing name them as the parser's errors do.
    std::vector<std::pair<std::string, std::string>> patches;
};

// Parse a scene file (SceneDocument::read(file).parse(), scene_document.h).
// Throws strahl::Error:
//   "scene.json:12:5: syntax error: ..." for malformed JSON,
//   "scene.json: /shapes/1: unknown key 'colour' (allowed: ...)" for bad content.
SceneDesc parseSceneFile(const std::filesystem::path& file);

// The same from text; `file` names it in errors and anchors relative paths.
SceneDesc parseSceneText(const std::string& text, const std::filesystem::path& file);

}  // namespace strahl
