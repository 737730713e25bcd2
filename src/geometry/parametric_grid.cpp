#include "strahl/geometry/parametric_grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "strahl/core/error.h"

namespace strahl {

namespace {

// Breakpoint lists are kept in a normalised parameter t ∈ [0, 1], so patches
// whose shared edge runs the other way read the list as 1 − t. Halving dyadic
// values keeps them exact, so 1 − t of a neighbour is bit-identical too.
using Breakpoints = std::vector<double>;

double toDomain(double t, double lo, double hi) { return t == 1.0 ? hi : lo + t * (hi - lo); }

Breakpoints uniform(int segments) {
    Breakpoints b(static_cast<size_t>(segments) + 1);
    for (int i = 0; i <= segments; ++i) b[static_cast<size_t>(i)] = static_cast<double>(i) / segments;
    b.back() = 1.0;
    return b;
}

// Union-find over the (patch, direction) lists, with the parity of each node's
// orientation relative to its root.
class EdgeClasses {
public:
    explicit EdgeClasses(size_t nodes) : parent_(nodes), reversed_(nodes, false) {
        std::iota(parent_.begin(), parent_.end(), size_t(0));
    }
    size_t root(size_t node) {
        bool flip = false;
        return find(node, flip);
    }
    bool reversedToRoot(size_t node) {
        bool flip = false;
        find(node, flip);
        return flip;
    }
    // Joins a and b with `reversed` telling whether they run opposite ways.
    // Returns false if that contradicts an earlier join (the class must then
    // be symmetric to serve both orientations).
    bool join(size_t a, size_t b, bool reversed) {
        bool fa = false, fb = false;
        const size_t ra = find(a, fa), rb = find(b, fb);
        if (ra == rb) return (fa != fb) == reversed;
        parent_[rb] = ra;
        reversed_[rb] = (fa != fb) != reversed;
        return true;
    }

private:
    size_t find(size_t node, bool& flip) {
        flip = false;
        size_t n = node;
        while (parent_[n] != n) {
            flip = flip != reversed_[n];
            n = parent_[n];
        }
        return n;
    }
    std::vector<size_t> parent_;
    std::vector<bool> reversed_;
};

size_t nodeOf(uint32_t patch, int direction) { return 2 * size_t(patch) + size_t(direction); }

struct PatchEdge {
    size_t node;  // the list whose breakpoints lie along this edge
    DVec3 a, m, b;  // start, middle and end point
};

// Links the lists of edges that two patches share. An edge is a boundary
// curve: v = v0 and v = v1 run along u (list U), u = u0 and u = u1 along v.
void matchSharedEdges(const ParametricSurface& surface, double tolerance, EdgeClasses& classes,
                      std::vector<bool>& symmetric) {
    const ParamDomain& d = surface.domain();
    std::vector<PatchEdge> edges;
    const double um = 0.5 * (d.u0 + d.u1), vm = 0.5 * (d.v0 + d.v1);
    for (uint32_t p = 0; p < surface.patchCount(); ++p) {
        for (const double v : {d.v0, d.v1})
            edges.push_back({nodeOf(p, 0), surface.point(p, d.u0, v), surface.point(p, um, v),
                             surface.point(p, d.u1, v)});
        for (const double u : {d.u0, d.u1})
            edges.push_back({nodeOf(p, 1), surface.point(p, u, d.v0), surface.point(p, u, vm),
                             surface.point(p, u, d.v1)});
    }
    auto near = [&](const DVec3& x, const DVec3& y) { return glm::length(x - y) <= tolerance; };
    // A degenerate edge (a pole) is a point: it matches every other pole there
    // and must not join their lists.
    std::erase_if(edges, [&](const PatchEdge& e) { return near(e.a, e.b) && near(e.a, e.m); });
    std::sort(edges.begin(), edges.end(),
              [](const PatchEdge& x, const PatchEdge& y) { return x.m.x < y.m.x; });
    for (size_t i = 0; i < edges.size(); ++i)
        for (size_t j = i + 1; j < edges.size() && edges[j].m.x - edges[i].m.x <= tolerance; ++j) {
            const PatchEdge &e = edges[i], &f = edges[j];
            if (!near(e.m, f.m)) continue;
            const bool same = near(e.a, f.a) && near(e.b, f.b);
            const bool reversed = near(e.a, f.b) && near(e.b, f.a);
            if (!same && !reversed) continue;
            if (!classes.join(e.node, f.node, !same)) symmetric[classes.root(e.node)] = true;
        }
}

}  // namespace

size_t ParametricGrid::cellCount() const {
    size_t n = 0;
    for (const PatchGrid& p : patches) n += p.cellCount();
    return n;
}

ParametricGrid buildParametricGrid(const ParametricSurface& surface,
                                   const ParametricGridOptions& options) {
    if (options.maxSegments < 1) fail("the segment cap must be at least 1");
    for (const int n : {options.initialSegmentsU, options.initialSegmentsV})
        if (n < 1 || n > options.maxSegments)
            fail("segments must lie in [1, ", options.maxSegments, "], got ", n);
    if (!(options.maxChordError >= 0.0) || !std::isfinite(options.maxChordError))
        fail("the chordal error bound must be a finite number >= 0, got ", options.maxChordError);

    const ParamDomain& d = surface.domain();
    const uint32_t patches = surface.patchCount();
    EdgeClasses classes(2 * size_t(patches));
    std::vector<bool> symmetric(2 * size_t(patches), false);
    if (patches > 1) {
        // Shared edges meet to far better than this: their points come from
        // the same control points (or formula), differing by rounding only.
        DVec3 lo(num::kInf), hi(-num::kInf);
        for (uint32_t p = 0; p < patches; ++p)
            for (const double u : {d.u0, d.u1})
                for (const double v : {d.v0, d.v1}) {
                    lo = glm::min(lo, surface.point(p, u, v));
                    hi = glm::max(hi, surface.point(p, u, v));
                }
        matchSharedEdges(surface, 1e-7 * std::max(glm::length(hi - lo), 1e-300), classes, symmetric);
    }
    if (d.twistedU) symmetric[classes.root(nodeOf(0, 1))] = true;

    // One list per class root, started at the largest request of its members.
    std::vector<Breakpoints> lists(2 * size_t(patches));
    std::vector<int> start(2 * size_t(patches), 0);
    for (uint32_t p = 0; p < patches; ++p) {
        start[classes.root(nodeOf(p, 0))] = std::max(start[classes.root(nodeOf(p, 0))], options.initialSegmentsU);
        start[classes.root(nodeOf(p, 1))] = std::max(start[classes.root(nodeOf(p, 1))], options.initialSegmentsV);
    }
    for (size_t n = 0; n < lists.size(); ++n)
        if (start[n] > 0) lists[n] = uniform(start[n]);

    ParametricGrid grid;
    auto listOf = [&](uint32_t p, int direction) {
        const size_t node = nodeOf(p, direction);
        const Breakpoints& b = lists[classes.root(node)];
        const double lo = direction == 0 ? d.u0 : d.v0, hi = direction == 0 ? d.u1 : d.v1;
        std::vector<double> out(b.size());
        const bool flip = classes.reversedToRoot(node);
        for (size_t i = 0; i < b.size(); ++i)
            out[i] = toDomain(flip ? 1.0 - b[b.size() - 1 - i] : b[i], lo, hi);
        return out;
    };

    const bool adaptive = options.maxChordError > 0.0 || static_cast<bool>(options.maxEdgeLength);
    while (adaptive) {
        std::vector<std::vector<char>> split(lists.size());
        for (size_t n = 0; n < lists.size(); ++n)
            if (!lists[n].empty()) split[n].assign(lists[n].size() - 1, 0);
        auto tooLong = [&](const DVec3& a, const DVec3& b, const DVec3& mid) {
            if (options.maxChordError > 0.0 && glm::length(mid - 0.5 * (a + b)) > options.maxChordError)
                return true;
            return options.maxEdgeLength && glm::length(b - a) > options.maxEdgeLength(mid);
        };
        for (uint32_t p = 0; p < patches; ++p) {
            const std::vector<double> us = listOf(p, 0), vs = listOf(p, 1);
            const size_t nu = us.size(), nv = vs.size();
            std::vector<DVec3> pts(nu * nv);
            for (size_t j = 0; j < nv; ++j)
                for (size_t i = 0; i < nu; ++i) pts[j * nu + i] = surface.point(p, us[i], vs[j]);
            std::vector<char> splitU(nu - 1, 0), splitV(nv - 1, 0);
            for (size_t j = 0; j < nv; ++j)
                for (size_t i = 0; i + 1 < nu; ++i)
                    if (!splitU[i] && tooLong(pts[j * nu + i], pts[j * nu + i + 1],
                                              surface.point(p, 0.5 * (us[i] + us[i + 1]), vs[j])))
                        splitU[i] = 1;
            for (size_t j = 0; j + 1 < nv; ++j)
                for (size_t i = 0; i < nu; ++i)
                    if (!splitV[j] && tooLong(pts[j * nu + i], pts[(j + 1) * nu + i],
                                              surface.point(p, us[i], 0.5 * (vs[j] + vs[j + 1]))))
                        splitV[j] = 1;
            // A cell whose edges are fine can still be cut badly across: its
            // triangles' diagonal misses the centre (a saddle). Cells with an
            // edge to split wait for the next round.
            if (options.maxChordError > 0.0)
                for (size_t j = 0; j + 1 < nv; ++j)
                    for (size_t i = 0; i + 1 < nu; ++i) {
                        if (splitU[i] || splitV[j]) continue;
                        const DVec3 centre = surface.point(p, 0.5 * (us[i] + us[i + 1]),
                                                           0.5 * (vs[j] + vs[j + 1]));
                        const DVec3 diagonal1 = 0.5 * (pts[j * nu + i] + pts[(j + 1) * nu + i + 1]);
                        const DVec3 diagonal2 = 0.5 * (pts[j * nu + i + 1] + pts[(j + 1) * nu + i]);
                        const double error = std::min(glm::length(centre - diagonal1),
                                                      glm::length(centre - diagonal2));
                        if (error > options.maxChordError) splitU[i] = splitV[j] = 1;
                    }
            // Hand the flags to the class lists, in the root's orientation.
            for (int direction = 0; direction < 2; ++direction) {
                const size_t node = nodeOf(p, direction);
                const std::vector<char>& flags = direction == 0 ? splitU : splitV;
                std::vector<char>& target = split[classes.root(node)];
                const bool flip = classes.reversedToRoot(node);
                for (size_t k = 0; k < flags.size(); ++k)
                    if (flags[k]) target[flip ? flags.size() - 1 - k : k] = 1;
            }
        }
        bool any = false;
        for (size_t n = 0; n < lists.size(); ++n) {
            if (lists[n].empty()) continue;
            std::vector<char>& flags = split[n];
            if (symmetric[n])
                for (size_t k = 0; k < flags.size(); ++k)
                    flags[k] = flags[k] || flags[flags.size() - 1 - k];
            const size_t wanted = static_cast<size_t>(std::count(flags.begin(), flags.end(), 1));
            if (wanted == 0) continue;
            if (flags.size() + wanted > static_cast<size_t>(options.maxSegments)) {
                grid.capped = true;
                continue;
            }
            Breakpoints refined;
            refined.reserve(lists[n].size() + wanted);
            for (size_t k = 0; k + 1 < lists[n].size(); ++k) {
                refined.push_back(lists[n][k]);
                if (flags[k]) refined.push_back(0.5 * (lists[n][k] + lists[n][k + 1]));
            }
            refined.push_back(1.0);
            lists[n] = std::move(refined);
            any = true;
        }
        if (!any) break;
    }

    grid.patches.resize(patches);
    for (uint32_t p = 0; p < patches; ++p) grid.patches[p] = PatchGrid{listOf(p, 0), listOf(p, 1)};
    return grid;
}

}  // namespace strahl
