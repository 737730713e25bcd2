#pragma once
// ParametricGrid: where a parametric surface is cut — for each patch, the
// sorted parameter values (breakpoints) in u and in v of a tensor grid over its
// domain. The tessellator puts a vertex at every grid point; the direct mode
// makes every grid cell one user primitive (a sub-patch).
//
// The grid is adaptive but never has T-junctions:
//  * within a patch it is a tensor grid, so a breakpoint cuts the whole patch;
//  * patches that share an edge (the Bézier patches of the teapot) share the
//    breakpoint list of that edge's direction, found by matching edge end and
//    mid points, with the direction reversed where the neighbours run opposite
//    ways (an edge class; lists are refined per class, so one patch's need
//    splits its neighbours too);
//  * a twisted seam (Möbius: f(u1, v) = f(u0, v0 + v1 − v)) keeps its v list
//    symmetric, so the two sides of the seam meet vertex to vertex.
//
// Refinement: start from `initialSegments` uniform intervals and halve every
// interval that some row (or column) of the patch says is too coarse, until
// none is or `maxSegments` is reached. An interval is too coarse when, on any
// grid line across it,
//   chordal error   ‖f(mid) − (f(a) + f(b))/2‖ > maxChordError, or
//   edge length     ‖f(b) − f(a)‖ > maxEdgeLength(f(mid))
// and a cell whose edges pass is split both ways when its centre is farther
// than maxChordError from the midpoints of both its diagonals (a saddle that
// the edges alone miss: the triangles' shared diagonal is the chord there). The
// midpoint deviation is the chordal error of a smooth curve to first order
// (it is exactly the maximum for a parabola).

#include <cstdint>
#include <functional>
#include <vector>

#include "strahl/geometry/parametric_surface.h"

namespace strahl {

struct ParametricGridOptions {
    // Per patch and direction: uniform start (and the whole grid if neither
    // bound below is set).
    int initialSegmentsU = 8;
    int initialSegmentsV = 8;
    // Adaptive bounds in object-space length; 0 (or an empty function) turns
    // a criterion off.
    double maxChordError = 0.0;
    std::function<double(const DVec3&)> maxEdgeLength;
    // Hard cap per patch and direction, so a surface that never converges
    // (a cusp, a discontinuous formula) cannot exhaust memory.
    int maxSegments = 4096;
};

struct PatchGrid {
    std::vector<double> u, v;  // sorted breakpoints, first = domain start, last = domain end

    size_t cellCount() const { return (u.size() - 1) * (v.size() - 1); }
};

struct ParametricGrid {
    std::vector<PatchGrid> patches;  // one per surface patch

    size_t cellCount() const;
    // Whether some direction stopped at maxSegments before meeting the bounds.
    bool capped = false;
};

// Throws strahl::Error for options out of range (segments < 1 or above the cap).
ParametricGrid buildParametricGrid(const ParametricSurface& surface,
                                   const ParametricGridOptions& options);

}  // namespace strahl
