#pragma once
// The light BVH: many-light sampling by estimated contribution at the
// shading point (Conty Estevez and Kulla 2018, as pbrt-v4 and Cycles do;
// docs/lights.md, "Choosing a light").
//
// A binary tree over the finite lights with power (light_bounds.h), one light
// per leaf. To choose a light for a receiver at p with normal n, the walk
// starts at the root and at each node goes to a child with probability in
// proportion to the child's importance(p, n), using the same uniform number
// rescaled; the light's probability is the product of the choices. pmf()
// walks the same path down from the root (each leaf knows its ancestors), so
// it returns exactly the probability choose() gives, bit for bit: what the
// MIS weights of emitters hit by BSDF sampling need.
//
// The tree is built top-down by the surface area orientation heuristic (the
// same paper, eq. 2): each node splits along one of the 3 axes at one of 12
// bin borders, where power x orientation measure x surface area, summed over
// both sides, is smallest (times the box's aspect along the axis, so long
// thin nodes are avoided). Sequential, so the same lights give the same tree.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "strahl/integrator/light_bounds.h"

namespace strahl {

class LightBvh {
public:
    LightBvh() = default;
    // lights[i] are the bounds of light index[i] (the light set's index).
    LightBvh(std::vector<LightBounds> lights, std::vector<uint32_t> index);

    bool empty() const { return nodes_.empty(); }
    size_t nodeCount() const { return nodes_.size(); }

    // A light for a receiver at p with unit normal n (0: none) and its
    // probability; none if no light of the tree can reach p.
    std::optional<std::pair<uint32_t, float>> choose(float u, const Vec3& p, const Vec3& n) const;
    // The probability that choose picks light `light` (a light-set index)
    // at p, n; 0 for a light the tree does not hold.
    float pmf(uint32_t light, const Vec3& p, const Vec3& n) const;

private:
    struct Node {
        ImportanceBounds bounds;  // what the walk evaluates
        uint32_t child[2] = {0, 0};  // interior nodes
        uint32_t light = 0;          // leaves: the light-set index
        uint32_t parent = UINT32_MAX;
        bool leaf = false;
    };

    uint32_t build(std::vector<LightBounds>& lights, std::vector<uint32_t>& index, size_t begin,
                   size_t end, uint32_t parent);
    // The probabilities of going from `node` to its children at p, n; both 0
    // if neither child can reach p.
    std::pair<float, float> childProbabilities(const Node& node, const Vec3& p, const Vec3& n) const;

    std::vector<Node> nodes_;       // nodes_[0] is the root
    std::vector<uint32_t> leafOf_;  // light-set index -> leaf node (UINT32_MAX: not held)
};

}  // namespace strahl
