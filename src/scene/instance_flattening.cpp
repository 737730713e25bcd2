#include "instance_flattening.h"

#include <algorithm>
#include <limits>

#include "strahl/core/error.h"

namespace strahl::scene_detail {

namespace {

constexpr uint32_t kNoPrototype = std::numeric_limits<uint32_t>::max();

bool hasOwnShapes(const GroupDesc& group) {
    return std::any_of(group.shapes.begin(), group.shapes.end(),
                       [](const ShapeDesc& s) { return s.kind != ShapeKind::Instance; });
}

class Flattener {
public:
    explicit Flattener(const SceneDesc& desc)
        : desc_(desc),
          prototypeOf_(desc.groups.size(), kNoPrototype),
          counts_(desc.groups.size(), kUncounted) {
        for (const GroupDesc& group : desc.groups) ownShapes_.push_back(hasOwnShapes(group));
    }

    FlatInstances run() {
        // Count first, so an explosive nesting is rejected before anything is
        // allocated for it.
        uint64_t total = 0;
        for (const ShapeDesc& shape : desc_.shapes) {
            if (shape.kind == ShapeKind::Instance) total = cappedSum(total, count(shape));
        }
        if (total > kMaxInstances)
            fail(desc_.file.filename().string(), ": the groups place more than ", kMaxInstances,
                 " instances (the limit, 2^24)");
        result_.instances.reserve(total);
        for (const ShapeDesc& shape : desc_.shapes) {
            if (shape.kind == ShapeKind::Instance) placeShape(shape, {Mat4(1.0f)});
        }
        return std::move(result_);
    }

private:
    static constexpr uint64_t kUncounted = std::numeric_limits<uint64_t>::max();

    // Sums saturate just above the limit: the exact figure does not matter
    // once it is too many, and nested groups can multiply past 2^64.
    static uint64_t cappedSum(uint64_t a, uint64_t b) { return std::min(a + b, kMaxInstances + 1); }
    static uint64_t cappedProduct(uint64_t a, uint64_t b) {
        // Both factors are at most kMaxInstances + 1 (2^24 + 1): no overflow.
        return std::min(a * b, kMaxInstances + 1);
    }

    // Instances one instance shape (an array: once per placement) expands to.
    uint64_t count(const ShapeDesc& shape) {
        const uint64_t copies = shape.placements.empty() ? 1 : shape.placements.size();
        return cappedProduct(std::min<uint64_t>(copies, kMaxInstances + 1), count(shape.group));
    }

    // Instances one placement of `group` expands to (memoised).
    uint64_t count(size_t group) {
        if (counts_[group] != kUncounted) return counts_[group];
        uint64_t n = ownShapes_[group] ? 1 : 0;
        for (const ShapeDesc& shape : desc_.groups[group].shapes) {
            if (shape.kind == ShapeKind::Instance) n = cappedSum(n, count(shape));
        }
        return counts_[group] = n;
    }

    // An instance shape in a space that `toWorld` maps to the world: one
    // matrix, or the keyframes of a moving instance above it. A product of
    // linearly interpolated keyframes with fixed matrices is the linear
    // interpolation of the products, so one moving instance on a path stays
    // exact; two would not be (their product is quadratic in time).
    void placeShape(const ShapeDesc& shape, const std::vector<Mat4>& toWorld) {
        std::vector<Mat4> arrayToWorld;
        if (!shape.motion.empty()) {
            if (toWorld.size() > 1)
                fail(desc_.file.filename().string(), ": ", shape.where,
                     ": a moving instance inside a moving instance (give the motion to one of them)");
            for (const Mat4& key : shape.motion) arrayToWorld.push_back(toWorld[0] * key);
        } else {
            for (const Mat4& key : toWorld) arrayToWorld.push_back(key * shape.transform);
        }
        if (shape.placements.empty()) {
            place(shape.group, arrayToWorld);
            return;
        }
        std::vector<Mat4> placed(arrayToWorld.size());
        for (const Mat4& placement : shape.placements) {
            for (size_t k = 0; k < arrayToWorld.size(); ++k) placed[k] = arrayToWorld[k] * placement;
            place(shape.group, placed);
        }
    }

    void place(size_t group, const std::vector<Mat4>& toWorld) {
        if (ownShapes_[group]) {
            FlatInstance instance{prototype(group), toWorld[0], {}};
            if (toWorld.size() > 1) instance.motion = toWorld;
            result_.instances.push_back(std::move(instance));
        }
        for (const ShapeDesc& shape : desc_.groups[group].shapes) {
            if (shape.kind == ShapeKind::Instance) placeShape(shape, toWorld);
        }
    }

    uint32_t prototype(size_t group) {
        if (prototypeOf_[group] == kNoPrototype) {
            prototypeOf_[group] = static_cast<uint32_t>(result_.prototypeGroups.size());
            result_.prototypeGroups.push_back(group);
        }
        return prototypeOf_[group];
    }

    const SceneDesc& desc_;
    std::vector<bool> ownShapes_;  // per group: holds shapes besides instances
    std::vector<uint32_t> prototypeOf_;
    std::vector<uint64_t> counts_;
    FlatInstances result_;
};

}  // namespace

FlatInstances flattenInstances(const SceneDesc& desc) { return Flattener(desc).run(); }

}  // namespace strahl::scene_detail
