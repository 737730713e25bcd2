// Instancing through the whole renderer: scenes/regression/instances.json
// (nested groups, a mirrored instance, an implicit surface and a mesh in the
// prototype) renders the same image as the same scene "baked" — every instance
// expanded, here in the test, into top-level copies of its group's shapes with
// the composed transform. Hits inside instances are shaded from object-space
// interactions mapped to world space (normals, and shadow-ray offsets from the
// transformed error bounds), so this checks all of that against shapes that
// never saw an instance.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "strahl/scene/scene_builder.h"
#include "render_helpers.h"
#include "sanitizers/sanitized.h"
#include "test_support.h"

namespace strahl {
namespace {

// Appends the shapes that placing `shapes` at `toWorld` puts in the world.
void expand(const SceneDesc& desc, const std::vector<ShapeDesc>& shapes, const Mat4& toWorld,
            std::vector<ShapeDesc>& out) {
    for (const ShapeDesc& shape : shapes) {
        if (shape.kind == ShapeKind::Instance) {
            expand(desc, desc.groups[shape.group].shapes, toWorld * shape.transform, out);
            continue;
        }
        ShapeDesc copy = shape;
        copy.transform = toWorld * shape.transform;
        out.push_back(std::move(copy));
    }
}

SceneDesc baked(const SceneDesc& desc) {
    SceneDesc flat = desc;
    flat.shapes.clear();
    flat.groups.clear();
    expand(desc, desc.shapes, Mat4(1.0f), flat.shapes);
    return flat;
}

// Fraction of values that differ by more than `tolerance`.
double differingFraction(const std::vector<float>& a, const std::vector<float>& b, float tolerance) {
    EXPECT_EQ(a.size(), b.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        differing += !(std::abs(a[i] - b[i]) <= tolerance);
    return double(differing) / double(a.size());
}

TEST(InstanceRender, InstancedSceneLooksLikeItsBakedCopy) {
    const SceneDesc desc =
        parseSceneFile(test::sourceDir() / "scenes/regression/instances.json");
    const SceneDesc flat = baked(desc);
    ASSERT_EQ(flat.shapes.size(), 1u + 7u * 2u);  // the floor, 7 charms of 2 shapes
    for (const char* integrator : {"direct", "normal", "depth"}) {
        SCOPED_TRACE(integrator);
        const test::Rendered a = test::render(desc, AccelKind::Embree, integrator);
        const test::Rendered b = test::render(flat, AccelKind::Embree, integrator);
        // The two transform the same geometry with different rounding (float
        // instance matrices against double implicit transforms and baked
        // vertices): a ray grazing a silhouette or a shadow edge may go either
        // way, nothing else may differ visibly.
        EXPECT_LE(differingFraction(a.beauty, b.beauty, 2e-3f), 0.002);
        EXPECT_LE(differingFraction(a.normal, b.normal, 2e-3f), 0.002);
    }
}

TEST(InstanceRender, NaiveTracerRendersInstancesLikeEmbree) {
    SceneDesc desc = parseSceneFile(test::sourceDir() / "scenes/regression/instances.json");
    test::shrinkFilmWhenSanitized(desc, 3);  // naive tracer: slow under the sanitizers
    const test::Rendered a = test::render(desc, AccelKind::Embree, "primid");
    const test::Rendered b = test::render(desc, AccelKind::Naive, "primid");
    // primid colours differ per instance: equal images mean equal instance IDs.
    EXPECT_LE(differingFraction(a.beauty, b.beauty, 0.0f), 0.001);
}

}  // namespace
}  // namespace strahl
