#pragma once
// Internal to the scene module: nested groups to one level of instances.
//
// Embree (as packaged, RTC_MAX_INSTANCE_LEVEL_COUNT == 1) and the naive tracer
// instance one level deep, so a group that places other groups is flattened:
// an instance of group A at transform M places A's own shapes (if any) at M,
// and each instance of B inside A at M * T_B, recursively. Only groups that
// some top-level instance reaches become prototypes, each stored once however
// many paths reach it.

#include <cstdint>
#include <vector>

#include "strahl/core/math.h"
#include "strahl/scene/scene_desc.h"

namespace strahl::scene_detail {

// At most this many instances after flattening: each costs about 400 bytes
// (its three matrices here, Embree's instance geometry and its BVH leaf), so
// 2^24 instances are some 6 GiB. A scene that needs more should instance fewer,
// bigger groups.
inline constexpr uint64_t kMaxInstances = uint64_t(1) << 24;

struct FlatInstance {
    uint32_t prototype = 0;  // index into FlatInstances::prototypeGroups
    Mat4 objectToWorld{1.0f};  // a moving instance's first keyframe
    std::vector<Mat4> motion;  // empty at rest, else its keyframes (core/motion.h)
};

struct FlatInstances {
    std::vector<size_t> prototypeGroups;  // the group each prototype is made of
    std::vector<FlatInstance> instances;  // in scene order, depth first
};

// Throws strahl::Error naming the scene file if there would be more than
// kMaxInstances instances, or if a moving instance is placed by a moving
// instance. Expects groups already checked acyclic and at most
// kMaxGroupNesting deep (the parser does).
FlatInstances flattenInstances(const SceneDesc& desc);

}  // namespace strahl::scene_detail
