#pragma once
// The built-in implicit surfaces, each f < 0 inside, in object space (place
// them with a shape's transform). Parameters are checked: a non-finite or
// out-of-range value throws strahl::Error naming the parameter (the scene
// builder adds the shape). docs/implicit-surfaces.md gives every formula.

#include <vector>

#include "strahl/geometry/implicit_surface.h"

namespace strahl {

// f = x² + y² + z² − r², with a closed-form, cancellation-free ray intersection.
ImplicitSurfacePtr makeImplicitSphere(double radius);

// f = xx·x² + yy·y² + zz·z² + xy·xy + yz·yz + xz·xz + x·x + y·y + z·z + c: any
// quadric (ellipsoid, cylinder, cone, paraboloid, hyperboloid, plane). Closed
// form; most quadrics are unbounded, so bounds() is empty and a shape needs a box.
struct QuadricCoefficients {
    double xx = 0, yy = 0, zz = 0, xy = 0, yz = 0, xz = 0, x = 0, y = 0, z = 0, c = 0;
};
ImplicitSurfacePtr makeImplicitQuadric(const QuadricCoefficients& q);

// f = (x² + y² + z² + R² − r²)² − 4R²(x² + y²): the torus around the z axis
// with major radius R (centre to tube centre) and minor radius r (tube).
ImplicitSurfacePtr makeImplicitTorus(double majorRadius, double minorRadius);

// Barr's superellipsoid: f = (|x/a|^(2/e2) + |y/b|^(2/e2))^(e2/e1) + |z/c|^(2/e1) − 1.
// e1 shapes the north–south profile, e2 the east–west one: 1,1 is an ellipsoid,
// towards 0 a box, 2 an octahedron.
ImplicitSurfacePtr makeSuperellipsoid(const DVec3& radii, double e1, double e2);

// Blobby / metaball surface with the compact "soft object" kernel of Wyvill et
// al. (1986): f = threshold − Σ strength·(1 − ‖x − c‖²/R²)³ over the balls
// ‖x − c‖ < R. Finite support keeps the surface bounded and cells cullable.
struct Blob {
    DVec3 center{0.0};
    double radius = 1.0;
    double strength = 1.0;
};
ImplicitSurfacePtr makeBlobs(std::vector<Blob> blobs, double threshold);

// Triply periodic minimal-surface approximations, with k = 2π/period:
//   gyroid    sin kx cos ky + sin ky cos kz + sin kz cos kx
//   schwarz_p cos kx + cos ky + cos kz
//   schwarz_d sin kx sin ky sin kz + sin kx cos ky cos kz + cos kx sin ky cos kz
//             + cos kx cos ky sin kz
//   neovius   3(cos kx + cos ky + cos kz) + 4 cos kx cos ky cos kz
// minus `level`. With thickness > 0 the surface is the solid sheet
// |g| − thickness = 0 instead of the level set. Unbounded: a shape needs a box.
enum class PeriodicSurface { Gyroid, SchwarzP, SchwarzD, Neovius };
ImplicitSurfacePtr makePeriodicSurface(PeriodicSurface kind, double period, double level,
                                       double thickness);

}  // namespace strahl
