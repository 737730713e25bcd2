// `strahl info`: counts, bounds, memory and the camera of a scene, after
// loading it and building the BVH (docs/cli.md#strahl-info).

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"
#include <algorithm>

#include "scene_loading.h"
#include "strahl/core/process_memory.h"

namespace strahl::app {

namespace {

// "compact" or "not compact", and "(auto)" when no flag chose it; whether
// paired triangles are traced as quads.
std::string bvhLayoutName(const BuildOptions& build, const World& world) {
    const bool compact = useCompactBvh(build, world.triangleCount());
    return std::string(compact ? "compact" : "not compact") + (build.compact ? "" : " (auto)") +
           (build.quads == QuadPolicy::Never    ? ", triangles only"
            : build.quads == QuadPolicy::Always ? ", quads where triangles pair"
                                                : ", quads for large paired meshes (auto)");
}

// One line per shape: its index (the geomID within its list), name and size.
void printShapes(const std::vector<SceneShape>& shapes, const char* indent) {
    for (size_t i = 0; i < shapes.size(); ++i) {
        const SceneShape& shape = shapes[i];
        if (shape.user) {
            std::printf("%s[%zu] %-24s %10u %-9s %s\n", indent, i, shape.name.c_str(),
                        shape.user->primitiveCount(), shape.user->primitiveNoun(),
                        shape.user->describe().c_str());
            continue;
        }
        const TriangleMesh& m = shape.mesh;
        std::printf("%s[%zu] %-24s %10zu triangles %10zu vertices%s%s%s%s\n", indent, i,
                    shape.name.c_str(), m.triangleCount(), m.vertexCount(),
                    m.normals.empty() ? "" : " normals", m.uvs.empty() ? "" : " uvs",
                    m.deforms() ? concat(" deforming over ", m.keyframeCount(), " keyframes").c_str() : "",
                    shape.tessellated
                        ? (" tessellated " + shape.tessellated->surface().describe() +
                           (shape.tessellated->normals() == ParametricNormals::Exact ? ", exact normals"
                                                                                      : ", interpolated normals"))
                              .c_str()
                        : "");
    }
}

}  // namespace

int runInfo(const Options& o) {
    const auto started = std::chrono::steady_clock::now();
    const SceneDesc desc = patchedScene(o).parse();
    const double sceneSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    BuildTimings timings;
    const BuildOptions build = buildOptions(o);
    const BuiltScene scene = buildScene(desc, build, &timings);
    timings.loadSeconds += sceneSeconds;  // reading the scene file is part of the load
    const World& world = scene.world;
    const Bounds3 b = world.bounds();
    std::printf("scene      %s\n", desc.file.string().c_str());
    std::printf("shapes     %zu\n", world.shapes.size());
    printShapes(world.shapes, "  ");
    if (!world.prototypes.empty()) {
        std::vector<size_t> placements(world.prototypes.size(), 0);
        for (const SceneInstance& instance : world.instances) ++placements[instance.prototype];
        const auto moving = std::count_if(world.instances.begin(), world.instances.end(),
                                          [](const SceneInstance& i) { return i.moves(); });
        std::printf("groups     %zu, %zu instances%s\n", world.prototypes.size(), world.instances.size(),
                    moving ? concat(" (", moving, " moving: motion blur over the shutter)").c_str() : "");
        for (size_t p = 0; p < world.prototypes.size(); ++p) {
            std::printf("  group '%s', placed %zu times\n", world.prototypes[p].name.c_str(),
                        placements[p]);
            printShapes(world.prototypes[p].shapes, "    ");
        }
    }
    std::printf("triangles  %zu", world.triangleCount());
    if (!world.instances.empty())
        std::printf(" stored, %zu instanced", world.instancedTriangleCount());
    std::printf("\n");
    std::printf("user prims %zu\n", world.userPrimitiveCount());
    std::printf("materials  %zu\n", world.materials.size());
    // Every light the integrators sample: the scene's lights, one triangle
    // light per emissive triangle, and the background's sky.
    size_t areaLights = 0;
    for (const Light& light : world.lightSet.lights())
        if (std::holds_alternative<TriangleLight>(light.kind)) ++areaLights;
    const size_t sky = world.lightSet.lights().size() - world.lights.size() - areaLights;
    std::printf("lights     %zu (%zu from the scene file, %zu emissive triangles, %zu background sky)\n",
                world.lightSet.lights().size(), world.lights.size(), areaLights, sky);
    std::printf("bounds     (%g, %g, %g) - (%g, %g, %g)\n", b.min.x, b.min.y, b.min.z, b.max.x,
                b.max.y, b.max.z);
    std::printf("memory     shapes %s, bvh %s (%s, %s%s), peak resident %s\n",
                formatBytes(world.shapeMemoryBytes()).c_str(),
                formatBytes(world.accel->memoryBytes()).c_str(), o.bvhQuality.c_str(),
                bvhLayoutName(build, world).c_str(),
                world.triangleCount()
                    ? (", " +
                       formatBytes((world.shapeMemoryBytes() + world.accel->memoryBytes()) /
                                   world.triangleCount()) +
                       " per stored triangle with its mesh data")
                          .c_str()
                    : "",
                formatBytes(peakResidentBytes()).c_str());
    std::printf("camera     %s\n", describeCamera(scene.camera).c_str());
    std::printf("film       %dx%d, %d spp, integrator %s\n", desc.film.width, desc.film.height,
                desc.render.spp, desc.render.integrator.c_str());
    std::printf("timing     load %.2f s, bvh %.2f s\n", timings.loadSeconds, timings.bvhSeconds);
    std::printf("embree     %s, packets of %d\n", embreeVersion(), resolvePacketWidth(PacketMode::Auto, *world.accel));
    return 0;
}

}  // namespace strahl::app
