#pragma once
// From SceneDesc to what the renderer reads: every file the scene names read
// once, in parallel (meshes, a glTF file's cameras, Bézier patch files, height
// images); meshes transformed to world space, validated and padded for Embree;
// implicit surfaces placed and cut into cells; parametric surfaces tessellated
// or prepared for direct intersection; materials resolved to one table;
// lights; the camera; the accelerator (Embree's BVH, or the naive reference
// loop).

#include <functional>
#include <optional>

#include "strahl/camera/camera.h"
#include "strahl/core/filter.h"
#include "strahl/integrator/integrator.h"
#include "strahl/integrator/world.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {

enum class AccelKind { Embree, Naive };

struct BuildOptions {
    int threads = 0;  // 0: all hardware threads
    AccelKind accel = AccelKind::Embree;
    BvhQuality bvhQuality = BvhQuality::Medium;  // Embree only
    // Embree's compact BVH: on 10^7 triangles it halves the peak memory and
    // builds 1.8x faster, for rays 10-15% slower (docs/memory.md). Unset: the
    // choice of useCompactBvh below.
    std::optional<bool> compact;
    // Meshes of paired triangles traced as Embree quads (AccelBuildOptions::quads).
    QuadPolicy quads = QuadPolicy::Auto;
    // When not 0: resident memory allowed after loading, and for the process
    // while Embree builds (its memory monitor; see AccelBuildOptions). Going
    // past it is a strahl::Error, not a kill by the kernel.
    size_t memoryLimitBytes = 0;
    // Called when the BVH build starts and with its progress fraction.
    std::function<void()> bvhStarted;
    std::function<void(double)> bvhProgress;
};

// Compact mode is worth its slower rays only where memory and build time
// matter: above this many stored triangles (the extra 32 bytes per triangle of
// the full layout, docs/memory.md, stay below 128 MiB and its extra build time
// below about 0.6 s), or when a memory limit is set. Below it the full layout
// renders 10-15 % faster (bench/RESULTS.md, "Peers: Embree's tutorials").
inline constexpr size_t kCompactBvhAboveTriangles = size_t(1) << 22;

// The BVH layout of a build: `options.compact` when set, else compact for
// scenes of more than kCompactBvhAboveTriangles stored triangles or with a
// memory limit.
bool useCompactBvh(const BuildOptions& options, size_t storedTriangles);

struct BuildTimings {
    double loadSeconds = 0.0;  // reading and preparing meshes (callers add reading the scene file)
    double bvhSeconds = 0.0;   // building the acceleration structure (0 for naive)
};

// The world and the camera as the files made them (a glTF camera resolved).
struct BuiltScene {
    World world;
    CameraDesc camera;
};

// Throws strahl::Error naming the shape (file or JSON pointer) on any failure.
BuiltScene buildScene(const SceneDesc& desc, const BuildOptions& options,
                      BuildTimings* timings = nullptr);
// buildScene's world alone, for scenes whose camera is not needed or not from
// a file.
World buildWorld(const SceneDesc& desc, const BuildOptions& options, BuildTimings* timings = nullptr);

// "embree" or "naive"; throws strahl::Error listing the choices otherwise.
AccelKind accelFromName(const std::string& name);
const char* accelName(AccelKind kind);

// The camera for an image of width x height pixels. A camera still to be read
// from a glTF file is an error: take BuiltScene::camera.
Camera buildCamera(const CameraDesc& desc, int width, int height);

// The film's pixel filter.
PixelFilter buildPixelFilter(const FilmDesc& film);

// The integrator settings of the scene's render block, with the ray cone of
// the camera's pixels (texture filtering).
IntegratorOptions buildIntegratorOptions(const SceneDesc& desc, const Camera& camera);

// A short human-readable description, e.g. "perspective eye (0,1,4) fov 45".
std::string describeCamera(const CameraDesc& desc);

}  // namespace strahl
