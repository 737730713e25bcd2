// QuadFaces: pairing consecutive triangles into Embree quads, and hits on those
// quads back to triangles (quad_faces.h has the geometry).

#include "strahl/accel/quad_faces.h"

#include <array>

namespace strahl {

namespace {

using Tri = std::array<uint32_t, 3>;

Tri triangle(const TriangleMesh& mesh, size_t t) {
    const uint32_t* i = &mesh.indices[3 * t];
    return {i[0], i[1], i[2]};
}

Tri rotated(const Tri& t, unsigned r) { return {t[r % 3], t[(r + 1) % 3], t[(r + 2) % 3]}; }

// If `first` and `second` share an edge that runs x→y in first and y→x in
// second, the rotations that make them (a, b, c) and (a, c, d) — first's edge
// x→y is then c→a, second's y→x is a→c.
bool sharedEdge(const Tri& first, const Tri& second, uint8_t& firstRotation, uint8_t& secondRotation) {
    for (unsigned i = 0; i < 3; ++i)
        for (unsigned j = 0; j < 3; ++j)
            if (first[i] == second[(j + 1) % 3] && first[(i + 1) % 3] == second[j]) {
                firstRotation = static_cast<uint8_t>((i + 1) % 3);
                secondRotation = static_cast<uint8_t>(j);
                return true;
            }
    return false;
}

// Weights w on a triangle rotated left by r, as the (second, third) corner
// weights of the triangle as stored: rotated corner i is stored corner r + i.
void unrotate(const float w[3], unsigned r, float& u, float& v) {
    float stored[3];
    for (unsigned i = 0; i < 3; ++i) stored[(r + i) % 3] = w[i];
    u = stored[1];
    v = stored[2];
}

}  // namespace

QuadFaces pairTriangles(const TriangleMesh& mesh) {
    QuadFaces quads;
    const size_t n = mesh.triangleCount();
    quads.corners.reserve(4 * ((n + 1) / 2));
    quads.faces.reserve((n + 1) / 2);
    bool plainPairs = n % 2 == 0;  // face k == triangles 2k, 2k + 1, unrotated
    for (size_t t = 0; t < n;) {
        QuadFace face;
        face.firstTriangle = static_cast<uint32_t>(t);
        const Tri first = triangle(mesh, t);
        if (t + 1 < n && sharedEdge(first, triangle(mesh, t + 1), face.firstRotation, face.secondRotation)) {
            face.pair = true;
            const Tri abc = rotated(first, face.firstRotation);
            const Tri acd = rotated(triangle(mesh, t + 1), face.secondRotation);
            quads.corners.insert(quads.corners.end(), {acd[2], abc[0], abc[1], abc[2]});  // (d, a, b, c)
            plainPairs = plainPairs && face.firstRotation == 0 && face.secondRotation == 0;
            quads.pairedTriangles += 2;
            t += 2;
        } else {
            quads.corners.insert(quads.corners.end(), {first[0], first[1], first[2], first[2]});
            plainPairs = false;
            t += 1;
        }
        quads.faces.push_back(face);
    }
    quads.faceCount = quads.faces.size();
    if (plainPairs) quads.faces = {};  // (and its memory)
    quads.corners.shrink_to_fit();
    quads.faces.shrink_to_fit();
    return quads;
}

void toTriangleHit(const QuadFaces& quads, uint32_t& prim, float& u, float& v) {
    const QuadFace face = quads.faces.empty() ? QuadFace{2 * prim, 0, 0, true} : quads.faces[prim];
    if (!face.pair) {  // (a, b, c, c): only its first half, (a, b, c), has area
        prim = face.firstTriangle;
        return;
    }
    if (u + v < 1.0f) {
        // First half (q0, q1, q3) = (d, a, c) with weights (1 - u - v, u, v):
        // on (a, c, d), the second triangle rotated, (u, v, 1 - u - v). (On
        // the diagonal, u + v = 1, the first triangle of the pair is named,
        // as a loop over the triangles in order finds it first.)
        const float w[3] = {u, v, 1.0f - u - v};
        prim = face.firstTriangle + 1;
        unrotate(w, face.secondRotation, u, v);
    } else {
        // Second half (q2, q3, q1) = (b, c, a) at its own (1 - u, 1 - v), so
        // weights (u + v - 1, 1 - u, 1 - v): on (a, b, c), (1 - v, u + v - 1, 1 - u).
        const float w[3] = {1.0f - v, u + v - 1.0f, 1.0f - u};
        prim = face.firstTriangle;
        unrotate(w, face.firstRotation, u, v);
    }
}

}  // namespace strahl
