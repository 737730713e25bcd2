// Catmull-Clark refinement (catmull_clark.h): the rules of the header, level
// by level, over an edge table rebuilt at every level. Positions and uvs go
// through the same weights (applyRules is templated on the value type).

#include "strahl/geometry/catmull_clark.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include <glm/glm.hpp>

#include "double_box.h"
#include "strahl/core/error.h"

namespace strahl {

namespace {

using geometry_detail::isFiniteD;

constexpr float kInfiniteSharpness = std::numeric_limits<float>::infinity();
// Refined quads beyond this are refused: about 150 bytes each for the
// reference tables, so 2^24 quads are 2.5 GB.
constexpr size_t kMaxRefinedQuads = size_t(1) << 24;

struct Edge {
    uint32_t a = 0, b = 0;        // a < b
    uint32_t faces[2] = {0, 0};
    int faceCount = 0;            // 1: boundary, 2: interior
    float sharpness = 0.0f;       // as given (creases), before the boundary mode
};

// One level of the mesh: polygons at level 0, quads after.
struct Level {
    std::vector<DVec3> p;
    std::vector<DVec2> uv;
    std::vector<uint32_t> faceStart{0};  // faces' first corner; size faces + 1
    std::vector<uint32_t> corners;       // vertex of each face corner
    std::vector<uint32_t> controlFace;   // per face
    std::vector<DVec2> params;           // per corner, level ≥ 1
    std::vector<uint32_t> cornerEdge;    // per corner i: the edge from corner i to i + 1
    std::vector<Edge> edges;
    std::vector<float> vertexSharpness;
    // Per vertex, its edges and faces (CSR).
    std::vector<uint32_t> vertexEdgeStart, vertexEdges, vertexFaceStart, vertexFaces;

    size_t faceCount() const { return faceStart.size() - 1; }
    uint32_t faceSize(size_t f) const { return faceStart[f + 1] - faceStart[f]; }
};

void buildVertexAdjacency(Level& level);

uint64_t edgeKey(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32 | b) : (uint64_t(b) << 32 | a); }

// Builds the edges of `level` from its faces, and the vertex adjacency.
// `directed` catches a directed edge used twice (faces wound inconsistently).
void buildTopology(Level& level, const std::string& name, std::unordered_map<uint64_t, uint32_t>* edgeIndexOut) {
    std::unordered_map<uint64_t, uint32_t> edgeIndex;
    edgeIndex.reserve(level.corners.size());
    level.edges.clear();
    level.cornerEdge.assign(level.corners.size(), 0);
    std::unordered_map<uint64_t, uint32_t> directed;
    const bool checkDirection = edgeIndexOut != nullptr;  // level 0 only: refinement keeps windings
    for (size_t f = 0; f < level.faceCount(); ++f) {
        const uint32_t first = level.faceStart[f], n = level.faceSize(f);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = level.corners[first + i], b = level.corners[first + (i + 1) % n];
            const auto [it, inserted] = edgeIndex.emplace(edgeKey(a, b), uint32_t(level.edges.size()));
            if (inserted) level.edges.push_back(Edge{std::min(a, b), std::max(a, b)});
            Edge& e = level.edges[it->second];
            if (e.faceCount == 2)
                fail(name, ": the edge ", a, "-", b, " is shared by more than two faces (face ", f,
                     "); subdivision needs a manifold surface");
            if (checkDirection && !directed.emplace(uint64_t(a) << 32 | b, uint32_t(f)).second)
                fail(name, ": the edge ", a, "-", b, " is used twice in the same direction (faces ",
                     directed[uint64_t(a) << 32 | b], " and ", f, "): face windings disagree");
            e.faces[e.faceCount++] = uint32_t(f);
            level.cornerEdge[first + i] = it->second;
        }
    }
    if (edgeIndexOut) *edgeIndexOut = std::move(edgeIndex);
    buildVertexAdjacency(level);
}

// The edges and faces around every vertex (CSR), from the edges and faces.
void buildVertexAdjacency(Level& level) {
    const size_t nv = level.p.size();
    level.vertexEdgeStart.assign(nv + 1, 0);
    level.vertexFaceStart.assign(nv + 1, 0);
    for (const Edge& e : level.edges) {
        ++level.vertexEdgeStart[e.a + 1];
        ++level.vertexEdgeStart[e.b + 1];
    }
    for (uint32_t v : level.corners) ++level.vertexFaceStart[v + 1];
    std::partial_sum(level.vertexEdgeStart.begin(), level.vertexEdgeStart.end(), level.vertexEdgeStart.begin());
    std::partial_sum(level.vertexFaceStart.begin(), level.vertexFaceStart.end(), level.vertexFaceStart.begin());
    level.vertexEdges.assign(level.vertexEdgeStart.back(), 0);
    level.vertexFaces.assign(level.vertexFaceStart.back(), 0);
    std::vector<uint32_t> fillE(level.vertexEdgeStart.begin(), level.vertexEdgeStart.end() - 1);
    std::vector<uint32_t> fillF(level.vertexFaceStart.begin(), level.vertexFaceStart.end() - 1);
    for (uint32_t e = 0; e < level.edges.size(); ++e) {
        level.vertexEdges[fillE[level.edges[e].a]++] = e;
        level.vertexEdges[fillE[level.edges[e].b]++] = e;
    }
    for (uint32_t f = 0; f < level.faceCount(); ++f)
        for (uint32_t c = level.faceStart[f]; c < level.faceStart[f + 1]; ++c) level.vertexFaces[fillF[level.corners[c]]++] = f;
}

// The next level's edges, known from the parent's without searching: parent
// edge e (a, b) splits into 2e = (a, E_e) and 2e + 1 = (b, E_e); parent
// corner c (of face f, on edge e_c) adds 2·ne + c = (E_c, F_f). Child face c
// is (v, E_c, F, E_prev) with edges: e_c's child at v, c's inner edge,
// prev's inner edge, e_prev's child at v.
void buildChildTopology(const Level& parent, Level& next) {
    const size_t nv = parent.p.size(), ne = parent.edges.size();
    next.edges.assign(2 * ne + parent.corners.size(), Edge{});
    for (size_t e = 0; e < ne; ++e) {
        const Edge& pe = parent.edges[e];
        const uint32_t mid = uint32_t(nv + e);
        next.edges[2 * e].a = pe.a;
        next.edges[2 * e].b = mid;
        next.edges[2 * e + 1].a = pe.b;
        next.edges[2 * e + 1].b = mid;
    }
    next.cornerEdge.assign(next.corners.size(), 0);
    for (uint32_t f = 0; f < parent.faceCount(); ++f) {
        const uint32_t first = parent.faceStart[f], n = parent.faceSize(f);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t c = first + i, prev = first + (i + n - 1) % n;
            const uint32_t v = parent.corners[c];
            Edge& inner = next.edges[2 * ne + c];
            inner.a = uint32_t(nv + parent.cornerEdge[c]);
            inner.b = uint32_t(nv + ne + f);
            const auto childAt = [&](uint32_t e) { return uint32_t(2 * e + (parent.edges[e].a == v ? 0 : 1)); };
            const uint32_t child = c;  // child faces are made one per parent corner, in order
            next.cornerEdge[4 * child + 0] = childAt(parent.cornerEdge[c]);
            next.cornerEdge[4 * child + 1] = uint32_t(2 * ne + c);
            next.cornerEdge[4 * child + 2] = uint32_t(2 * ne + prev);
            next.cornerEdge[4 * child + 3] = childAt(parent.cornerEdge[prev]);
        }
    }
    for (uint32_t f = 0; f < next.faceCount(); ++f)
        for (uint32_t k = 0; k < 4; ++k) {
            Edge& e = next.edges[next.cornerEdge[4 * f + k]];
            e.faces[e.faceCount++] = f;
        }
    buildVertexAdjacency(next);
}

// The sharpness the rules see: boundary edges are infinitely sharp, and so
// is every edge when every vertex is pinned.
float effectiveEdgeSharpness(const Edge& e, SubdivisionBoundary mode) {
    if (e.faceCount < 2 || mode == SubdivisionBoundary::PinAll) return kInfiniteSharpness;
    return e.sharpness;
}

struct VertexRule {
    enum Kind { Smooth, Crease, Corner } kind = Smooth;
    uint32_t creaseEnds[2] = {0, 0};
    uint32_t creaseEdges[2] = {0, 0};
    float blend = 1.0f;  // weight of the sharp rule against the smooth one
    // A crease vertex without a vertex sharpness: the sharpness of its two
    // crease edges' children here follows Chaikin's rule.
    bool chaikin = false;
};

// Which rule vertex v follows at this level (the header's table).
VertexRule vertexRule(const Level& level, uint32_t v, SubdivisionBoundary mode) {
    int sharpCount = 0;
    bool boundary = false;
    double sharpSum = 0.0;
    VertexRule rule;
    const uint32_t valence = level.vertexEdgeStart[v + 1] - level.vertexEdgeStart[v];
    for (uint32_t k = level.vertexEdgeStart[v]; k < level.vertexEdgeStart[v + 1]; ++k) {
        const Edge& e = level.edges[level.vertexEdges[k]];
        boundary |= e.faceCount < 2;
        const float s = effectiveEdgeSharpness(e, mode);
        if (s > 0.0f) {
            if (sharpCount < 2) {
                rule.creaseEnds[sharpCount] = e.a == v ? e.b : e.a;
                rule.creaseEdges[sharpCount] = level.vertexEdges[k];
            }
            ++sharpCount;
            sharpSum += double(s);
        }
    }
    float vertexSharpness = level.vertexSharpness[v];
    if (mode == SubdivisionBoundary::PinAll ||
        (boundary && (mode == SubdivisionBoundary::PinBoundary ||
                      (mode == SubdivisionBoundary::PinCorners && valence == 2))))
        vertexSharpness = kInfiniteSharpness;
    const float edgeMean = sharpCount > 0 ? float(sharpSum / sharpCount) : 0.0f;
    if (vertexSharpness > 0.0f) {
        rule.kind = VertexRule::Corner;
        rule.blend = std::min(1.0f, vertexSharpness);
    } else if (sharpCount > 2) {
        rule.kind = VertexRule::Corner;  // not blended (Embree, DeRose et al.)
    } else if (sharpCount == 2) {
        rule.kind = VertexRule::Crease;
        rule.blend = std::min(1.0f, edgeMean);
        rule.chaikin = true;
    }
    return rule;
}

// The next level's values of one attribute (positions or uvs), in the new
// vertex order: vertex points, then edge points, then face points.
template <class T>
std::vector<T> applyRules(const Level& level, const std::vector<T>& x, const std::vector<VertexRule>& rules,
                          SubdivisionBoundary mode) {
    const size_t nv = level.p.size(), ne = level.edges.size(), nf = level.faceCount();
    std::vector<T> out(nv + ne + nf);
    for (size_t f = 0; f < nf; ++f) {
        T sum(0.0);
        for (uint32_t c = level.faceStart[f]; c < level.faceStart[f + 1]; ++c) sum += x[level.corners[c]];
        out[nv + ne + f] = sum / double(level.faceSize(f));
    }
    for (size_t e = 0; e < ne; ++e) {
        const Edge& edge = level.edges[e];
        const T mid = 0.5 * (x[edge.a] + x[edge.b]);
        const float s = effectiveEdgeSharpness(edge, mode);
        if (s >= 1.0f) {
            out[nv + e] = mid;
            continue;
        }
        const T smooth = 0.25 * (x[edge.a] + x[edge.b] + out[nv + ne + edge.faces[0]] + out[nv + ne + edge.faces[1]]);
        out[nv + e] = s > 0.0f ? smooth + double(s) * (mid - smooth) : smooth;
    }
    for (uint32_t v = 0; v < nv; ++v) {
        const uint32_t valence = level.vertexEdgeStart[v + 1] - level.vertexEdgeStart[v];
        const uint32_t faces = level.vertexFaceStart[v + 1] - level.vertexFaceStart[v];
        if (valence == 0) {  // used only by holes
            out[v] = x[v];
            continue;
        }
        const VertexRule& rule = rules[v];
        T smooth = x[v];
        if (rule.kind == VertexRule::Smooth || rule.blend < 1.0f) {
            T q(0.0), r(0.0);
            for (uint32_t k = level.vertexFaceStart[v]; k < level.vertexFaceStart[v + 1]; ++k)
                q += out[nv + ne + level.vertexFaces[k]];
            for (uint32_t k = level.vertexEdgeStart[v]; k < level.vertexEdgeStart[v + 1]; ++k) {
                const Edge& e = level.edges[level.vertexEdges[k]];
                r += 0.5 * (x[e.a] + x[e.b]);
            }
            const double n = double(valence);
            smooth = faces > 0 ? (q / double(faces) + 2.0 * (r / n) + (n - 3.0) * x[v]) / n : x[v];
        }
        T sharp = x[v];
        if (rule.kind == VertexRule::Crease)
            sharp = (6.0 * x[v] + x[rule.creaseEnds[0]] + x[rule.creaseEnds[1]]) / 8.0;
        out[v] = rule.kind == VertexRule::Smooth ? smooth : smooth + double(rule.blend) * (sharp - smooth);
    }
    return out;
}

float childSharpness(float s) { return s > 1.0f ? s - 1.0f : 0.0f; }  // inf − 1 = inf

Level refine(const Level& level, SubdivisionBoundary mode, bool firstLevel, const std::string& name) {
    const size_t nv = level.p.size(), ne = level.edges.size(), nf = level.faceCount();
    std::vector<VertexRule> rules(nv);
    for (uint32_t v = 0; v < nv; ++v) rules[v] = vertexRule(level, v, mode);

    Level next;
    next.p = applyRules(level, level.p, rules, mode);
    if (!level.uv.empty()) next.uv = applyRules(level, level.uv, rules, mode);
    next.corners.reserve(4 * level.corners.size());
    next.params.reserve(4 * level.corners.size());
    next.faceStart.reserve(level.corners.size() + 1);
    static const DVec2 kUnit[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t first = level.faceStart[f], n = level.faceSize(f);
        DVec2 centre(0.0);
        if (!firstLevel)
            for (uint32_t i = 0; i < n; ++i) centre += level.params[first + i] / double(n);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t prev = (i + n - 1) % n;
            next.corners.insert(next.corners.end(), {level.corners[first + i], uint32_t(nv + level.cornerEdge[first + i]),
                                                     uint32_t(nv + ne + f), uint32_t(nv + level.cornerEdge[first + prev])});
            if (firstLevel && n != 4) {
                // Sub-quad i of a non-quad face, in Embree's encoding.
                const DVec2 base(2.0 * double(i % 4) + 0.5, 2.0 * double(i / 4) + 0.5);
                for (const DVec2& unit : kUnit) next.params.push_back(base + unit);
            } else {
                const auto param = [&](uint32_t k) { return firstLevel ? kUnit[k] : level.params[first + k]; };
                const DVec2 p = param(i), pNext = param((i + 1) % n), pPrev = param(prev);
                const DVec2 c = firstLevel ? DVec2(0.5) : centre;
                next.params.insert(next.params.end(), {p, 0.5 * (p + pNext), c, 0.5 * (p + pPrev)});
            }
            next.controlFace.push_back(level.controlFace[f]);
            next.faceStart.push_back(uint32_t(next.corners.size()));
        }
    }
    if (next.corners.size() / 4 > kMaxRefinedQuads)
        fail(name, ": ", next.corners.size() / 4, " refined quads at this level is too many (at most ",
             kMaxRefinedQuads, "); choose fewer levels");
    buildChildTopology(level, next);
    // Child edges of a parent edge inherit its sharpness minus one — at a
    // crease vertex by Chaikin's rule, (3 s + s_other)/4 − 1 with s_other the
    // vertex's other crease edge; the edges inside a face (edge point to face
    // point) are smooth.
    for (Edge& e : next.edges) {
        if (!(e.a < nv && e.b >= nv && e.b < nv + ne)) continue;
        const auto parent = uint32_t(e.b - nv);
        const float s = level.edges[parent].sharpness;
        e.sharpness = childSharpness(s);
        const VertexRule& rule = rules[e.a];
        if (rule.chaikin && s > 0.0f && (rule.creaseEdges[0] == parent || rule.creaseEdges[1] == parent)) {
            const uint32_t other = rule.creaseEdges[0] == parent ? rule.creaseEdges[1] : rule.creaseEdges[0];
            e.sharpness = childSharpness(0.25f * (3.0f * s + level.edges[other].sharpness));
        }
    }
    next.vertexSharpness.assign(next.p.size(), 0.0f);
    for (uint32_t v = 0; v < nv; ++v) next.vertexSharpness[v] = childSharpness(level.vertexSharpness[v]);
    return next;
}

// Moves every vertex of the last level to its limit position (or uv).
template <class T>
std::vector<T> limitOf(const Level& level, const std::vector<T>& x, const std::vector<VertexRule>& rules) {
    std::vector<T> out(x.size());
    for (uint32_t v = 0; v < x.size(); ++v) {
        const uint32_t valence = level.vertexEdgeStart[v + 1] - level.vertexEdgeStart[v];
        const VertexRule& rule = rules[v];
        if (valence == 0 || rule.kind == VertexRule::Corner) {
            out[v] = x[v];
        } else if (rule.kind == VertexRule::Crease) {
            out[v] = (4.0 * x[v] + x[rule.creaseEnds[0]] + x[rule.creaseEnds[1]]) / 6.0;
        } else {
            // Smooth: every face is a quad here; its corner opposite v is the
            // diagonal neighbour.
            T edgeSum(0.0), diagonalSum(0.0);
            for (uint32_t k = level.vertexEdgeStart[v]; k < level.vertexEdgeStart[v + 1]; ++k) {
                const Edge& e = level.edges[level.vertexEdges[k]];
                edgeSum += x[e.a == v ? e.b : e.a];
            }
            for (uint32_t k = level.vertexFaceStart[v]; k < level.vertexFaceStart[v + 1]; ++k) {
                const uint32_t f = level.vertexFaces[k], first = level.faceStart[f];
                for (uint32_t i = 0; i < 4; ++i)
                    if (level.corners[first + i] == v) diagonalSum += x[level.corners[first + (i + 2) % 4]];
            }
            const double n = double(valence);
            out[v] = (n * n * x[v] + 4.0 * edgeSum + diagonalSum) / (n * (n + 5.0));
        }
    }
    return out;
}

Level levelZero(const SubdivisionCage& cage, const std::string& name) {
    if (cage.faceSizes.empty()) fail(name, ": no faces");
    if (cage.positions.empty()) fail(name, ": no positions");
    for (size_t i = 0; i < cage.positions.size(); ++i)
        if (!isFiniteD(cage.positions[i])) fail(name, ": position ", i, " is not finite");
    if (!cage.uvs.empty() && cage.uvs.size() != cage.positions.size())
        fail(name, ": ", cage.uvs.size(), " uvs for ", cage.positions.size(), " positions (one per position)");
    for (size_t i = 0; i < cage.uvs.size(); ++i)
        if (!std::isfinite(cage.uvs[i].x) || !std::isfinite(cage.uvs[i].y)) fail(name, ": uv ", i, " is not finite");
    size_t total = 0;
    for (size_t f = 0; f < cage.faceSizes.size(); ++f) {
        if (cage.faceSizes[f] < 3 || cage.faceSizes[f] > uint32_t(kMaxFaceSize))
            fail(name, ": face ", f, " has ", cage.faceSizes[f], " vertices (3 to ", kMaxFaceSize, ")");
        total += cage.faceSizes[f];
    }
    if (total != cage.indices.size())
        fail(name, ": the faces need ", total, " indices, ", cage.indices.size(), " are given");
    std::vector<bool> hole(cage.faceSizes.size(), false);
    for (uint32_t h : cage.holes) {
        if (h >= cage.faceSizes.size()) fail(name, ": hole ", h, " is not a face (", cage.faceSizes.size(), " faces)");
        hole[h] = true;
    }
    Level level;
    level.p = cage.positions;
    level.uv = cage.uvs;
    size_t first = 0;
    for (uint32_t f = 0; f < cage.faceSizes.size(); ++f) {
        const uint32_t n = cage.faceSizes[f];
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t v = cage.indices[first + i];
            if (v >= cage.positions.size())
                fail(name, ": face ", f, " uses vertex ", v, ", but there are ", cage.positions.size());
            for (uint32_t j = 0; j < i; ++j)
                if (cage.indices[first + j] == v) fail(name, ": face ", f, " uses vertex ", v, " twice");
        }
        if (!hole[f]) {
            level.corners.insert(level.corners.end(), cage.indices.begin() + first, cage.indices.begin() + first + n);
            level.controlFace.push_back(f);
            level.faceStart.push_back(uint32_t(level.corners.size()));
        }
        first += n;
    }
    if (level.controlFace.empty()) fail(name, ": every face is a hole");
    std::unordered_map<uint64_t, uint32_t> edgeIndex;
    buildTopology(level, name, &edgeIndex);
    if (cage.creaseEdges.size() != 2 * cage.creaseWeights.size())
        fail(name, ": ", cage.creaseEdges.size(), " crease indices for ", cage.creaseWeights.size(),
             " weights (two vertices per weight)");
    for (size_t k = 0; k < cage.creaseWeights.size(); ++k) {
        const float w = cage.creaseWeights[k];
        const uint32_t a = cage.creaseEdges[2 * k], b = cage.creaseEdges[2 * k + 1];
        if (!(w >= 0.0f)) fail(name, ": crease ", k, " has weight ", w, " (need ≥ 0)");
        const auto it = edgeIndex.find(edgeKey(a, b));
        if (it == edgeIndex.end()) fail(name, ": crease ", k, " (", a, "-", b, ") is not an edge of the mesh");
        level.edges[it->second].sharpness = w;
    }
    if (cage.cornerVertices.size() != cage.cornerWeights.size())
        fail(name, ": ", cage.cornerVertices.size(), " corner vertices for ", cage.cornerWeights.size(), " weights");
    level.vertexSharpness.assign(level.p.size(), 0.0f);
    for (size_t k = 0; k < cage.cornerVertices.size(); ++k) {
        const uint32_t v = cage.cornerVertices[k];
        const float w = cage.cornerWeights[k];
        if (v >= level.p.size()) fail(name, ": corner ", k, " names vertex ", v, ", but there are ", level.p.size());
        if (!(w >= 0.0f)) fail(name, ": corner ", k, " has weight ", w, " (need ≥ 0)");
        level.vertexSharpness[v] = w;
    }
    return level;
}

// Union-find over quad corners: corners of one vertex on two quads that
// share a smooth edge at that vertex get one normal.
struct Groups {
    std::vector<uint32_t> parent;
    explicit Groups(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

uint32_t cornerOf(const Level& level, uint32_t face, uint32_t vertex) {
    const uint32_t first = level.faceStart[face];
    for (uint32_t i = 0; i < 4; ++i)
        if (level.corners[first + i] == vertex) return first + i;
    return first;  // unreachable: the edge's faces hold both its ends
}

}  // namespace

const char* subdivisionBoundaryName(SubdivisionBoundary mode) {
    switch (mode) {
        case SubdivisionBoundary::Smooth: return "smooth";
        case SubdivisionBoundary::PinCorners: return "pin_corners";
        case SubdivisionBoundary::PinBoundary: return "pin_boundary";
        case SubdivisionBoundary::PinAll: return "pin_all";
    }
    return "smooth";
}

SubdivisionBoundary subdivisionBoundaryFromName(const std::string& name) {
    for (SubdivisionBoundary m : {SubdivisionBoundary::Smooth, SubdivisionBoundary::PinCorners,
                                  SubdivisionBoundary::PinBoundary, SubdivisionBoundary::PinAll})
        if (name == subdivisionBoundaryName(m)) return m;
    fail("unknown boundary mode '", name, "' (choose smooth, pin_corners, pin_boundary or pin_all)");
}

RefinedSurface refineCatmullClark(const SubdivisionCage& cage, int levels, const std::string& name) {
    if (levels < 1 || levels > kMaxSubdivisionLevels)
        fail(name, ": ", levels, " subdivision levels (1 to ", kMaxSubdivisionLevels, ")");
    Level level = levelZero(cage, name);
    // Pinned everywhere, every control edge is a kink between bilinear
    // patches: sharp for the rules already (effectiveEdgeSharpness), and
    // so for the normals too.
    if (cage.boundary == SubdivisionBoundary::PinAll)
        for (Edge& e : level.edges) e.sharpness = kInfiniteSharpness;
    for (int l = 0; l < levels; ++l) level = refine(level, cage.boundary, l == 0, name);

    std::vector<VertexRule> rules(level.p.size());
    for (uint32_t v = 0; v < level.p.size(); ++v) rules[v] = vertexRule(level, v, cage.boundary);
    RefinedSurface out;
    out.levels = levels;
    out.positions = limitOf(level, level.p, rules);
    if (!level.uv.empty()) out.uvs = limitOf(level, level.uv, rules);
    const size_t quads = level.faceCount();
    out.quads.resize(quads);
    out.quadParams.resize(quads);
    out.quadFace = level.controlFace;
    for (size_t q = 0; q < quads; ++q)
        for (int i = 0; i < 4; ++i) {
            out.quads[q][i] = level.corners[4 * q + i];
            out.quadParams[q][i] = level.params[4 * q + i];
        }
    Groups groups(level.corners.size());
    for (const Edge& e : level.edges) {
        if (e.faceCount < 2 || e.sharpness > 0.0f) continue;
        for (uint32_t v : {e.a, e.b}) groups.unite(cornerOf(level, e.faces[0], v), cornerOf(level, e.faces[1], v));
    }
    // Number the groups in order of their first corner.
    std::vector<uint32_t> groupOfRoot(level.corners.size(), UINT32_MAX);
    out.cornerGroup.resize(quads);
    uint32_t groupCount = 0;
    for (size_t c = 0; c < level.corners.size(); ++c) {
        uint32_t& id = groupOfRoot[groups.find(uint32_t(c))];
        if (id == UINT32_MAX) id = groupCount++;
        out.cornerGroup[c / 4][c % 4] = id;
    }
    out.groupCount = groupCount;
    return out;
}

std::vector<std::array<DVec3, 4>> cornerNormals(const RefinedSurface& surface, const std::vector<DVec3>& positions) {
    std::vector<DVec3> sum(surface.groupCount, DVec3(0.0));
    for (size_t q = 0; q < surface.quads.size(); ++q) {
        const auto& v = surface.quads[q];
        // The quad's area-weighted normal: half the cross product of its diagonals.
        const DVec3 n = glm::cross(positions[v[2]] - positions[v[0]], positions[v[3]] - positions[v[1]]);
        for (int i = 0; i < 4; ++i) sum[surface.cornerGroup[q][i]] += n;
    }
    std::vector<std::array<DVec3, 4>> out(surface.quads.size());
    for (size_t q = 0; q < surface.quads.size(); ++q)
        for (int i = 0; i < 4; ++i) {
            const DVec3 n = sum[surface.cornerGroup[q][i]];
            const double len = glm::length(n);
            out[q][i] = len > 0.0 ? n / len : DVec3(0.0, 0.0, 1.0);
        }
    return out;
}

}  // namespace strahl
