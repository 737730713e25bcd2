#include "strahl/integrator/light_bvh.h"

#include <algorithm>
#include <array>

#include "strahl/core/error.h"

namespace strahl {

namespace {

constexpr int kBins = 12;  // split candidates per axis: 11 borders, as in pbrt-v4

float surfaceArea(const Bounds3& b) {
    const Vec3 d = b.diagonal();
    return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The surface area orientation heuristic's cost of one side of a split.
float cost(const LightBounds& b) {
    return b.power > 0.0f ? b.power * orientationMeasure(b) * surfaceArea(b.box) : 0.0f;
}

}  // namespace

LightBvh::LightBvh(std::vector<LightBounds> lights, std::vector<uint32_t> index) {
    if (lights.size() != index.size())
        fail("light BVH: ", lights.size(), " bounds for ", index.size(), " lights");
    if (lights.empty()) return;
    uint32_t most = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (!(lights[i].power > 0.0f)) fail("light BVH: light ", index[i], " has no power");
        most = std::max(most, index[i]);
    }
    leafOf_.assign(size_t(most) + 1, UINT32_MAX);
    nodes_.reserve(2 * lights.size() - 1);
    build(lights, index, 0, lights.size(), UINT32_MAX);
}

// Builds the subtree of lights [begin, end) and returns its root; iterative
// (an explicit stack), so an unbalanced tree cannot overflow the call stack.
uint32_t LightBvh::build(std::vector<LightBounds>& lights, std::vector<uint32_t>& index,
                         size_t begin, size_t end, uint32_t parent) {
    struct Task {
        size_t begin, end;
        uint32_t parent;
        int which;  // which child of the parent this subtree is
    };
    std::vector<Task> stack{{begin, end, parent, 0}};
    const auto root = static_cast<uint32_t>(nodes_.size());
    while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        const auto self = static_cast<uint32_t>(nodes_.size());
        nodes_.emplace_back();
        if (task.parent != UINT32_MAX) nodes_[task.parent].child[task.which] = self;
        nodes_[self].parent = task.parent;
        if (task.end - task.begin == 1) {
            Node& leaf = nodes_[self];
            leaf.leaf = true;
            leaf.bounds = ImportanceBounds(lights[task.begin]);
            leaf.light = index[task.begin];
            leafOf_[leaf.light] = self;
            continue;
        }
        LightBounds all;
        Bounds3 centroids;
        for (size_t i = task.begin; i < task.end; ++i) {
            all = unite(all, lights[i]);
            centroids.expand(lights[i].box.center());
        }
        nodes_[self].bounds = ImportanceBounds(all);

        // The cheapest bin border over the three axes.
        float bestCost = kInfinity;
        int bestAxis = -1, bestBorder = 0;
        const Vec3 extent = centroids.diagonal();
        const float longest =
            std::max({all.box.diagonal().x, all.box.diagonal().y, all.box.diagonal().z});
        const auto binOf = [&](const LightBounds& b, int axis) {
            const float f = (b.box.center()[axis] - centroids.min[axis]) / extent[axis];
            return std::clamp(static_cast<int>(f * kBins), 0, kBins - 1);
        };
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0f)) continue;
            std::array<LightBounds, kBins> bins{};
            for (size_t i = task.begin; i < task.end; ++i) {
                LightBounds& bin = bins[size_t(binOf(lights[i], axis))];
                bin = unite(bin, lights[i]);
            }
            // Long thin nodes are poor bounds: the axis's share of the longest side.
            const float aspect = longest / all.box.diagonal()[axis];
            for (int border = 1; border < kBins; ++border) {
                LightBounds below, above;
                for (int b = 0; b < border; ++b) below = unite(below, bins[size_t(b)]);
                for (int b = border; b < kBins; ++b) above = unite(above, bins[size_t(b)]);
                const float c = aspect * (cost(below) + cost(above));
                if (c < bestCost) {
                    bestCost = c;
                    bestAxis = axis;
                    bestBorder = border;
                }
            }
        }
        size_t middle = task.begin + (task.end - task.begin) / 2;
        if (bestAxis >= 0) {
            // Partition lights and their indices together.
            size_t lo = task.begin;
            for (size_t i = task.begin; i < task.end; ++i)
                if (binOf(lights[i], bestAxis) < bestBorder) {
                    std::swap(lights[i], lights[lo]);
                    std::swap(index[i], index[lo]);
                    ++lo;
                }
            if (lo > task.begin && lo < task.end) middle = lo;
        }
        // Otherwise (every centroid in one place, or a border with nothing on
        // one side) the lights split in two halves as they are.
        stack.push_back({middle, task.end, self, 1});
        stack.push_back({task.begin, middle, self, 0});
    }
    return root;
}

std::pair<float, float> LightBvh::childProbabilities(const Node& node, const Vec3& p, const Vec3& n) const {
    const float left = nodes_[node.child[0]].bounds.importance(p, n);
    const float right = nodes_[node.child[1]].bounds.importance(p, n);
    const float total = left + right;
    if (!(total > 0.0f)) return {0.0f, 0.0f};
    return {left / total, right / total};
}

std::optional<std::pair<uint32_t, float>> LightBvh::choose(float u, const Vec3& p,
                                                           const Vec3& n) const {
    // A light alone is taken without asking whether it reaches p: if it does
    // not, it brings nothing, and the one-light scene pays nothing for the tree.
    if (nodes_.empty()) return std::nullopt;
    float pmf = 1.0f;
    uint32_t at = 0;
    while (!nodes_[at].leaf) {
        const Node& node = nodes_[at];
        const auto [pLeft, pRight] = childProbabilities(node, p, n);
        if (!(pLeft + pRight > 0.0f)) return std::nullopt;
        // Rescale u into the chosen child's share, so one number serves the
        // whole walk; kept below 1 against rounding.
        if (u < pLeft) {
            u = std::min(u / pLeft, 0x1.fffffep-1f);
            pmf *= pLeft;
            at = node.child[0];
        } else {
            u = std::min((u - pLeft) / pRight, 0x1.fffffep-1f);
            pmf *= pRight;
            at = node.child[1];
        }
        if (!(pmf > 0.0f)) return std::nullopt;
    }
    return std::make_pair(nodes_[at].light, pmf);
}

float LightBvh::pmf(uint32_t light, const Vec3& p, const Vec3& n) const {
    if (light >= leafOf_.size() || leafOf_[light] == UINT32_MAX) return 0.0f;
    // The path up to the root, then the same products as choose, in its
    // order (float products depend on it). Trees are rarely deeper than 64;
    // a deeper one takes the heap.
    std::array<uint32_t, 64> small;
    std::vector<uint32_t> large;
    size_t depth = 0;
    for (uint32_t at = leafOf_[light]; at != UINT32_MAX; at = nodes_[at].parent, ++depth) {
        if (depth == small.size()) large.assign(small.begin(), small.end());
        if (depth < small.size())
            small[depth] = at;
        else
            large.push_back(at);
    }
    const uint32_t* path = depth <= small.size() ? small.data() : large.data();
    float pmf = 1.0f;
    for (size_t i = depth - 1; i > 0; --i) {
        const Node& node = nodes_[path[i]];
        const auto [pLeft, pRight] = childProbabilities(node, p, n);
        pmf *= node.child[0] == path[i - 1] ? pLeft : pRight;
    }
    return pmf;
}

}  // namespace strahl
