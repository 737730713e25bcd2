// Loop subdivision (loop_subdivision.h): the rules of the header, level by
// level, over an edge table built from the triangles.

#include "strahl/geometry/loop_subdivision.h"

#include <cmath>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "strahl/core/error.h"

namespace strahl {

namespace {

using DVec3 = glm::dvec3;

// What the rules need to know about one surface: per vertex the sum and the
// number of its neighbours and its neighbours along the boundary; per edge
// its opposite vertices.
struct Adjacency {
    struct Edge {
        uint32_t a, b;            // a < b
        uint32_t opposite[2];     // the third vertex of each adjacent triangle
        int triangles = 0;        // 1: boundary, 2: interior
    };
    std::vector<Edge> edges;
    std::unordered_map<uint64_t, uint32_t> edgeIndex;  // (a << 32 | b) -> index in edges
    std::vector<DVec3> neighbourSum;
    std::vector<int> valence;
    std::vector<std::vector<uint32_t>> boundaryNeighbours;

    static uint64_t key(uint32_t a, uint32_t b) {
        return a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a);
    }

    Adjacency(const std::vector<DVec3>& p, const std::vector<uint32_t>& indices, const std::string& source) {
        for (size_t t = 0; t < indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3], c = indices[t + (k + 2) % 3];
                if (a == b) fail(source, ": triangle ", t / 3, " repeats vertex ", a, " (degenerate)");
                const auto [it, added] = edgeIndex.try_emplace(key(a, b), uint32_t(edges.size()));
                if (added) edges.push_back({std::min(a, b), std::max(a, b), {c, c}, 0});
                Edge& e = edges[it->second];
                if (e.triangles == 2)
                    fail(source, ": the edge between vertices ", e.a, " and ", e.b,
                         " belongs to more than two triangles: Loop subdivision needs a manifold surface");
                e.opposite[e.triangles++] = c;
            }
        neighbourSum.assign(p.size(), DVec3(0.0));
        valence.assign(p.size(), 0);
        boundaryNeighbours.assign(p.size(), {});
        for (const Edge& e : edges) {
            neighbourSum[e.a] += p[e.b];
            neighbourSum[e.b] += p[e.a];
            ++valence[e.a];
            ++valence[e.b];
            if (e.triangles == 1) {
                boundaryNeighbours[e.a].push_back(e.b);
                boundaryNeighbours[e.b].push_back(e.a);
            }
        }
    }

    uint32_t edge(uint32_t a, uint32_t b) const { return edgeIndex.at(key(a, b)); }
};

// Warren's weight of a valence-n interior vertex's neighbours.
double beta(int n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n); }

// Where vertex v moves: by the one-level rule, or to its limit.
DVec3 moved(const std::vector<DVec3>& p, const Adjacency& adj, size_t v, bool limit) {
    const int n = adj.valence[v];
    const std::vector<uint32_t>& boundary = adj.boundaryNeighbours[v];
    if (n == 0) return p[v];  // a vertex no triangle uses
    if (!boundary.empty()) {
        if (boundary.size() != 2) return p[v];  // a corner where boundaries meet: fixed
        const DVec3 ends = p[boundary[0]] + p[boundary[1]];
        return limit ? 0.6 * p[v] + 0.2 * ends : 0.75 * p[v] + 0.125 * ends;
    }
    const double b = beta(n);
    const double w = limit ? 1.0 / (n + 3.0 / (8.0 * b)) : b;
    return (1.0 - n * w) * p[v] + w * adj.neighbourSum[v];
}

}  // namespace

TriangleMesh loopSubdivide(const TriangleMesh& control, int levels, const std::string& source) {
    if (levels < 0 || levels > kMaxLoopLevels)
        fail(source, ": ", levels, " subdivision levels (0 ... ", kMaxLoopLevels, ")");
    // 2^28 triangles: about 8 GiB with their vertices and the BVH, beyond any
    // machine strahl is meant for; a larger result is a mistake, not a scene.
    const double triangles = static_cast<double>(control.triangleCount()) * std::pow(4.0, levels);
    if (triangles > static_cast<double>(size_t(1) << 28))
        fail(source, ": ", levels, " levels would make ", triangles, " triangles (at most 2^28)");
    std::vector<DVec3> p(control.positions.begin(), control.positions.end());
    std::vector<uint32_t> indices = control.indices;
    for (int level = 0; level < levels; ++level) {
        const Adjacency adj(p, indices, source);
        std::vector<DVec3> next(p.size() + adj.edges.size());
        for (size_t v = 0; v < p.size(); ++v) next[v] = moved(p, adj, v, false);
        for (size_t i = 0; i < adj.edges.size(); ++i) {
            const Adjacency::Edge& e = adj.edges[i];
            next[p.size() + i] = e.triangles == 2 ? 0.375 * (p[e.a] + p[e.b]) +
                                                        0.125 * (p[e.opposite[0]] + p[e.opposite[1]])
                                                  : 0.5 * (p[e.a] + p[e.b]);
        }
        std::vector<uint32_t> finer;
        finer.reserve(indices.size() * 4);
        const uint32_t base = static_cast<uint32_t>(p.size());
        for (size_t t = 0; t < indices.size(); t += 3) {
            const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
            const uint32_t ab = base + adj.edge(a, b), bc = base + adj.edge(b, c), ca = base + adj.edge(c, a);
            for (uint32_t k : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) finer.push_back(k);
        }
        p = std::move(next);
        indices = std::move(finer);
    }
    const Adjacency adj(p, indices, source);
    TriangleMesh out;
    out.positions.reserve(p.size() + 1);  // Embree's spare element (triangle_mesh.h)
    for (size_t v = 0; v < p.size(); ++v) out.positions.push_back(Vec3(moved(p, adj, v, true)));
    out.indices = std::move(indices);
    out.validate(source);
    out.computeVertexNormals();
    return out;
}

}  // namespace strahl
