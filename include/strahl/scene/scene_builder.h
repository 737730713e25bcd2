#pragma once
// From SceneDesc to what the renderer reads: meshes loaded (in parallel),
// transformed to world space, validated and padded for Embree; materials
// resolved to one table; lights; the camera; the Embree BVH.

#include <functional>

#include "strahl/camera/camera.h"
#include "strahl/integrator/world.h"
#include "strahl/scene/scene_desc.h"

namespace strahl {

struct BuildOptions {
    int threads = 0;  // 0: all hardware threads
    // Called when the BVH build starts and with its progress fraction.
    std::function<void()> bvhStarted;
    std::function<void(double)> bvhProgress;
};

struct BuildTimings {
    double loadSeconds = 0.0;  // reading and preparing meshes
    double bvhSeconds = 0.0;   // building the acceleration structure
};

// Throws strahl::Error naming the shape (file or JSON pointer) on any failure.
World buildWorld(const SceneDesc& desc, const BuildOptions& options, BuildTimings* timings = nullptr);

// The camera for an image of width x height pixels.
Camera buildCamera(const CameraDesc& desc, int width, int height);

// A short human-readable description, e.g. "perspective eye (0,1,4) fov 45".
std::string describeCamera(const CameraDesc& desc);

}  // namespace strahl
