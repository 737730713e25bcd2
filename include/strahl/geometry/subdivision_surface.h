#pragma once
// SubdivisionSurface: a Catmull-Clark surface (creases, corners, holes,
// boundary modes), optionally displaced along its normal. Embree traces it
// natively (RTC_GEOMETRY_TYPE_SUBDIVISION, accel/), tessellating every face
// at 2^levels segments per edge; this class's own intersect() is the
// reference the naive tracer uses: the limit surface refined `levels` times
// (catmull_clark.h) — the same points in the same parameters — split into
// triangles. docs/geometry.md, "Subdivision surfaces", has the math.
//
// One primitive per control face (holes included: they are never hit). Hit
// records: u, v = the face's own parameters (Embree's convention, see
// catmull_clark.h), Ng = the geometric normal of the tessellated surface.
// Shading interpolates the refined surface: smooth normals (kinked at sharp
// creases), the cage's uvs subdivided with the surface, or (u, v) without.
//
// Displacement: h(p, n, uv) moves every refined point p of the limit surface
// by h·n along its unit normal n (the mean over the quads around it, so the
// surface stays closed at creases); the shading normals are those of the
// displaced surface. Embree evaluates its own limit surface at the same
// parameters and adds the same offset (displacementAt), so both tracers see
// one displaced surface.

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "strahl/geometry/catmull_clark.h"
#include "strahl/geometry/user_shape.h"

namespace strahl {

// Height along the unit normal at limit point p with normal n and uv (the
// cage's uvs, or the face's parameters without them), in object units.
using DisplacementFunction = std::function<double(const DVec3& p, const DVec3& n, const DVec2& uv)>;

struct SubdivisionDesc {
    std::string name;
    SubdivisionCage cage;
    int levels = 3;  // 1 … 8: each face edge becomes 2^levels segments
    DisplacementFunction displacement;  // null: none
    std::string displacementText;       // for describe(): what the displacement is
    std::string levelsText;             // for describe(): how the levels were chosen, if not given
};

class SubdivisionSurface final : public UserShape {
public:
    // Refines the cage; throws strahl::Error naming desc.name for bad input
    // (refineCatmullClark lists it) or a displacement that is not finite.
    explicit SubdivisionSurface(SubdivisionDesc desc);

    uint32_t primitiveCount() const override { return uint32_t(desc_.cage.faceSizes.size()); }
    Bounds3 primitiveBounds(uint32_t face) const override;
    bool intersect(const Ray& ray, uint32_t face, Hit& hit) const noexcept override;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const override;
    std::string describe() const override;
    const char* primitiveNoun() const override { return "faces"; }
    size_t memoryBytes() const override;
    const SubdivisionSurface* asSubdivision() const override { return this; }

    const SubdivisionDesc& desc() const { return desc_; }
    const SubdivisionCage& cage() const { return desc_.cage; }
    int tessellationRate() const { return 1 << desc_.levels; }
    size_t refinedQuadCount() const { return refined_.quads.size(); }
    bool displaced() const { return !offsets_.empty(); }
    // The displacement offset at face parameters (u, v): exact at the refined
    // points, bilinear between them. Zero without displacement.
    DVec3 displacementAt(uint32_t face, float u, float v) const noexcept;
    // The refined (displaced) surface point at face parameters (u, v), the
    // same interpolation: for tests.
    DVec3 pointAt(uint32_t face, float u, float v) const noexcept;

private:
    // Which refined quad holds (u, v) of `face` and the bilinear weights of its
    // corners there; false for a hole.
    bool locate(uint32_t face, double u, double v, uint32_t& quad, std::array<double, 4>& weights,
                std::array<double, 4>* dWeightsDu = nullptr, std::array<double, 4>* dWeightsDv = nullptr) const noexcept;

    // Corner `corner` of refined quad `quad` in face parameters.
    DVec2 cornerParam(uint32_t face, uint32_t quad, int corner) const noexcept;

    SubdivisionDesc desc_;
    RefinedSurface refined_;  // its quads, control faces and uvs (the rest moved into the tables)
    std::vector<DVec3> points_;                        // refined positions, displaced
    std::vector<DVec3> offsets_;                       // displacement per refined vertex (empty: none)
    std::vector<std::array<Vec3, 4>> normals_;         // per quad corner, unit
    std::vector<uint32_t> faceFirstQuad_;              // per control face (size faces + 1)
    std::vector<uint32_t> faceCellStart_;              // per control face: first cell in cells_
    std::vector<uint32_t> cells_;                      // cell → quad, per face, row by row per sub-face
    std::vector<Bounds3> faceBounds_;
    std::vector<uint8_t> firstCorner_;                 // per quad: its corner at the cell's (0, 0)
    std::vector<uint32_t> quadCell_;                   // per quad: its cell within its face
};

}  // namespace strahl
