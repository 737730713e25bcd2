// The scene: the node graph checked (a forest), the default scene's nodes with
// their world transforms, and the cameras those nodes place.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_reader.h"

namespace strahl::meshio::gltf {

// All nodes, in the scene or not: children exist, no node has two parents,
// and no node is its own ancestor.
void GltfReader::checkNodeGraph() const {
    const size_t count = model_.nodes.size();
    constexpr size_t kNoParent = std::numeric_limits<size_t>::max();
    std::vector<size_t> parent(count, kNoParent);
    for (size_t i = 0; i < count; ++i) {
        const std::vector<int>& children = model_.nodes[i].children;
        for (size_t k = 0; k < children.size(); ++k) {
            const int c = children[k];
            const std::string place = concat("nodes[", i, "].children[", k, "]: ");
            if (c < 0 || size_t(c) >= count)
                error(place, "node ", c, " does not exist (", count, " nodes)");
            if (size_t(c) == i)
                error(place, "node ", c, " is its own ancestor (cyclic node hierarchy)");
            if (parent[size_t(c)] != kNoParent)
                error(place, "node ", c, " already is a child of node ", parent[size_t(c)],
                      " (a node has at most one parent)");
            parent[size_t(c)] = i;
        }
    }
    // With one parent each, a cycle is a parent chain that comes back to a
    // node of the same walk; every node is walked over once.
    enum class State : uint8_t { Unknown, OnWalk, Rooted };
    std::vector<State> state(count, State::Unknown);
    std::vector<size_t> walk;
    for (size_t i = 0; i < count; ++i) {
        walk.clear();
        size_t x = i;
        while (x != kNoParent && state[x] == State::Unknown) {
            state[x] = State::OnWalk;
            walk.push_back(x);
            x = parent[x];
        }
        if (x != kNoParent && state[x] == State::OnWalk)
            error("nodes[", x, "]: node ", x, " is its own ancestor (cyclic node hierarchy)");
        for (size_t w : walk) state[w] = State::Rooted;
    }
}

// Local transform of node `index`: its matrix, or T * R * S.
glm::dmat4 GltfReader::localTransform(size_t index) const {
    const tinygltf::Node& n = model_.nodes[index];
    const std::string place = concat("nodes[", index, "]");
    const auto check = [&](const std::vector<double>& v, std::initializer_list<size_t> sizes,
                           const char* what) {
        if (std::find(sizes.begin(), sizes.end(), v.size()) == sizes.end())
            error(place, what, " has ", v.size(), " numbers");
        for (double x : v) {
            if (!std::isfinite(x)) error(place, what, " is not finite");
        }
    };
    check(n.matrix, {0, 16}, ".matrix");
    check(n.translation, {0, 3}, ".translation");
    check(n.rotation, {0, 4}, ".rotation");
    check(n.scale, {0, 3}, ".scale");
    if (!n.matrix.empty()) return glm::make_mat4(n.matrix.data());  // column-major, as glm
    glm::dmat4 m(1.0);
    if (!n.translation.empty()) m = glm::translate(m, glm::make_vec3(n.translation.data()));
    if (!n.rotation.empty()) {
        // glTF stores (x, y, z, w); glm's constructor takes w first.
        glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
        const double length = glm::length(q);
        if (!(length > 0.0)) error(place, ".rotation is the zero quaternion");
        m *= glm::mat4_cast(q / length);
    }
    if (!n.scale.empty()) m = glm::scale(m, glm::make_vec3(n.scale.data()));
    return m;
}

// Every node of the scene with its world transform, parents before
// children. Cycles and nodes with two parents are errors: a hierarchy must
// be a forest, and a cycle would never end.
GltfReader::SceneNodes GltfReader::sceneNodes() const {
    std::vector<int> roots;
    std::string rootsPlace = "root nodes";
    if (!model_.scenes.empty()) {
        const int scene = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (size_t(scene) >= model_.scenes.size())
            fail(name_, ": scene ", scene, " does not exist (", model_.scenes.size(), " scenes)");
        roots = model_.scenes[size_t(scene)].nodes;
        rootsPlace = concat("scenes[", scene, "].nodes");
    } else {
        // No scene at all: every node that is no node's child.
        std::vector<bool> child(model_.nodes.size(), false);
        for (const tinygltf::Node& n : model_.nodes) {
            for (int c : n.children) {
                if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
            }
        }
        for (size_t i = 0; i < child.size(); ++i) {
            if (!child[i]) roots.push_back(int(i));
        }
    }

    enum class State : uint8_t { Unvisited, Open, Done };
    std::vector<State> state(model_.nodes.size(), State::Unvisited);
    std::vector<std::pair<size_t, glm::dmat4>> instances;
    struct Frame {
        size_t node;
        glm::dmat4 world;
        size_t nextChild;
    };
    std::vector<Frame> stack;  // explicit: a deep hierarchy must not overflow the call stack
    const auto enter = [&](int node, const glm::dmat4& parent, const std::string& place) {
        if (node < 0 || size_t(node) >= model_.nodes.size())
            error(place, "node ", node, " does not exist (", model_.nodes.size(), " nodes)");
        const size_t n = size_t(node);
        if (state[n] == State::Open)
            error(place, "node ", node, " is its own ancestor (cyclic node hierarchy)");
        if (state[n] == State::Done)
            error(place, "node ", node,
                  " appears twice in the hierarchy (a node has at most"
                  " one parent)");
        state[n] = State::Open;
        const glm::dmat4 world = parent * localTransform(n);
        const int mesh = model_.nodes[n].mesh;
        if (mesh >= 0) {
            if (size_t(mesh) >= model_.meshes.size())
                error(concat("nodes[", n, "]"), ": mesh ", mesh, " does not exist (",
                      model_.meshes.size(), " meshes)");
        }
        instances.emplace_back(n, world);
        stack.push_back({n, world, 0});
    };
    for (size_t r = 0; r < roots.size(); ++r) {
        enter(roots[r], glm::dmat4(1.0), concat(rootsPlace, '[', r, "]: "));
        while (!stack.empty()) {
            Frame& top = stack.back();
            const std::vector<int>& children = model_.nodes[top.node].children;
            if (top.nextChild == children.size()) {
                state[top.node] = State::Done;
                stack.pop_back();
                continue;
            }
            const size_t k = top.nextChild++;
            const glm::dmat4 world = top.world;  // `top` dangles once enter() pushes
            enter(children[k], world, concat("nodes[", top.node, "].children[", k, "]: "));
        }
    }
    return instances;
}

// The camera of each node in `nodes` that has one, in that order.
std::vector<GltfCamera> GltfReader::placeCameras(const SceneNodes& nodes) const {
    std::vector<GltfCamera> cameras;
    for (const auto& [node, world] : nodes) {
        const tinygltf::Node& n = model_.nodes[node];
        if (n.camera < 0) continue;
        const std::string place = concat("nodes[", node, "]");
        if (size_t(n.camera) >= model_.cameras.size())
            error(place, ": camera ", n.camera, " does not exist (", model_.cameras.size(),
                  " cameras)");
        cameras.push_back(convertCamera(size_t(n.camera), n, world, cameras.size()));
    }
    return cameras;
}

GltfCamera GltfReader::convertCamera(size_t index, const tinygltf::Node& node,
                                     const glm::dmat4& world, size_t placed) const {
    const tinygltf::Camera& c = model_.cameras[index];
    const std::string place = concat("cameras[", index, "]: ");
    GltfCamera out;
    out.name = !c.name.empty()      ? c.name
               : !node.name.empty() ? node.name
                                    : concat("camera ", placed);
    const glm::dvec3 back = glm::dvec3(world * glm::dvec4(0, 0, 1, 0));
    const glm::dvec3 up = glm::dvec3(world * glm::dvec4(0, 1, 0, 0));
    const glm::dvec3 eye = glm::dvec3(world * glm::dvec4(0, 0, 0, 1));
    // A scale of (nearly) zero or a shear that folds +y onto +z leaves no frame.
    const double backLength = glm::length(back), upLength = glm::length(up);
    if (!(backLength > 1e-12 && upLength > 1e-12) ||
        glm::length(glm::cross(back / backLength, up / upLength)) < 1e-6 ||
        !std::isfinite(eye.x + eye.y + eye.z))
        error(place, "the transform of the node placing it leaves no camera frame");
    out.eye = Vec3(eye);
    out.back = Vec3(back / backLength);
    out.up = Vec3(up / upLength);
    if (c.type == "perspective") {
        const double yfov = c.perspective.yfov;
        if (!(yfov > 0.0 && yfov < glm::pi<double>()))
            error(place, "perspective.yfov ", yfov, " is not in (0, pi)");
        out.yfovDegrees = float(glm::degrees(yfov));
    } else if (c.type == "orthographic") {
        out.orthographic = true;
        out.xmag = float(std::abs(c.orthographic.xmag));
        out.ymag = float(std::abs(c.orthographic.ymag));
        if (!(out.xmag > 0.0f && out.ymag > 0.0f && std::isfinite(out.xmag) &&
              std::isfinite(out.ymag)))
            error(place, "orthographic.xmag and ymag must not be zero");
    } else {
        error(place, "type '", c.type, "' is neither perspective nor orthographic");
    }
    return out;
}

}  // namespace strahl::meshio::gltf
