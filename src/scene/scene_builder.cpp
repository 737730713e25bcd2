#include "strahl/scene/scene_builder.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <sstream>

#include "curve_parser.h"
#include "subdivision_parser.h"
#include "instance_flattening.h"
#include "light_builder.h"
#include "material_builder.h"
#include "scene_files.h"
#include "strahl/core/error.h"
#include "strahl/core/process_memory.h"
#include "strahl/meshio/curve_file.h"
#include "strahl/meshio/mesh_file.h"
#include "strahl/reference/naive_accel.h"

namespace strahl {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// True when some triangle has a non-zero area. A mesh whose triangles are all
// degenerate (collinear or repeated corners) is as invisible as one without
// triangles. The cross product is taken in double so that a tiny but real
// triangle does not underflow to zero; the first such triangle ends the scan.
bool hasTriangleWithArea(const TriangleMesh& mesh) {
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const DVec3 p0(mesh.positions[mesh.indices[3 * t]]);
        const DVec3 p1(mesh.positions[mesh.indices[3 * t + 1]]);
        const DVec3 p2(mesh.positions[mesh.indices[3 * t + 2]]);
        if (glm::cross(p1 - p0, p2 - p0) != DVec3(0.0)) return true;
    }
    return false;
}

std::string shapeSource(const SceneDesc& desc, const ShapeDesc& shape) {
    return concat(desc.file.filename().string(), ": ", shape.where,
                  shape.file.empty() ? std::string() : " (" + shape.file.string() + ")");
}

// A "curves" shape in world space; its strand file, if any, read now.
std::shared_ptr<const UserShape> makeCurveShape(const SceneDesc& desc, const ShapeDesc& shape) {
    try {
        CurveSetDesc curves = shape.curves;
        if (!shape.file.empty()) {
            StrandFile strands = loadStrandFile(shape.file);
            curves.points = std::move(strands.points);
            curves.segments = curveSegmentsOfStrands(strands.strandPoints, curves.basis, curves.name);
        }
        return std::make_shared<CurveSet>(scene_detail::placeCurves(std::move(curves), shape.transform,
                                                                       shape.curveRadiusFollowsTransform));
    } catch (const Error& e) {
        // A strand file's errors name it and the line already.
        fail(desc.file.filename().string(), ": ", shape.where, ": ", e.what());
    }
}

// A mesh whose triangles all take one material slot (an OBJ with a single
// usemtl, say) keeps that slot alone and no per-triangle table: it saves 4
// bytes a triangle, and on large meshes a cache miss at every hit (the
// table's entry is read by every surface interaction). Same materials, same
// image.
void collapseUniformSlots(SceneShape& geometry) {
    std::vector<uint32_t>& slots = geometry.mesh.faceMaterials;
    if (slots.empty()) return;
    const uint32_t slot = slots.front();
    if (slot >= geometry.materialOfSlot.size()) return;  // (loaders give slots of their own materials)
    if (std::any_of(slots.begin(), slots.end(), [slot](uint32_t s) { return s != slot; })) return;
    geometry.materialOfSlot = {geometry.materialOfSlot[slot]};
    slots.clear();
    slots.shrink_to_fit();
}

// Every mesh attribute the shape's materials read must be on its mesh.
void checkMeshAttributes(const SceneDesc& desc, const ShapeDesc& shape, const SceneShape& geometry,
                         const World& world) {
    for (const uint32_t index : geometry.materialOfSlot) {
        Material material = world.materials[index];  // forEachTexture visits mutably
        material.forEachTexture([&](const TextureRef& texture, TextureEncoding) {
            const std::string& name = texture.meshAttribute;
            if (name.empty()) return;
            const auto& attributes = geometry.mesh.attributes;
            if (std::any_of(attributes.begin(), attributes.end(),
                            [&](const MeshAttribute& a) { return a.name == name; }))
                return;
            if (!geometry.isMesh())
                fail(shapeSource(desc, shape), ": material '", material.name,
                     "' reads the mesh attribute '", name, "', but this shape is not a mesh");
            std::string have;
            for (const MeshAttribute& a : attributes) have += (have.empty() ? "" : ", ") + a.name;
            fail(shapeSource(desc, shape), ": material '", material.name, "' reads the mesh attribute '",
                 name, "', which the mesh does not have (",
                 have.empty() ? std::string("it has none") : "it has " + have, ")");
        });
    }
}

std::shared_ptr<const UserShape> makeImplicitShape(const SceneDesc& desc, const ShapeDesc& shape) {
    try {
        return std::make_shared<ImplicitShape>(shape.implicitSurface, shape.transform,
                                               shape.implicitOptions);
    } catch (const Error& e) {
        fail(shapeSource(desc, shape), ": ", e.what());
    }
}

// The longest object-space edge that spans `pixels` pixels of the camera's
// image at an object-space point: a pixel's footprint grows with the distance
// from the eye (perspective) or is constant (orthographic). Dividing by the
// transform's largest stretch keeps the bound conservative in world space.
std::function<double(const DVec3&)> edgeLengthFromCamera(const SceneDesc& desc,
                                                         const CameraDesc& cameraDesc,
                                                         const Mat4& toWorld, double pixels,
                                                         double extent) {
    const Camera camera = buildCamera(cameraDesc, desc.film.width, desc.film.height);
    const ImageWindow& w = camera.window();
    const double pixelSize = static_cast<double>(w.t - w.b) / desc.film.height;
    const bool perspective = camera.projection() == Projection::Perspective;
    const double perUnitDistance = pixelSize / camera.focalDistance();
    const glm::dmat4 m(toWorld);
    const double stretch = std::max({glm::length(DVec3(m[0])), glm::length(DVec3(m[1])),
                                     glm::length(DVec3(m[2]))});
    const DVec3 eye(camera.frame().e);
    // Never below a millionth of the surface (a point at the eye itself).
    const double floor = 1e-6 * extent;
    return [=](const DVec3& p) {
        const double footprint = perspective
                                     ? perUnitDistance * glm::length(DVec3(m * glm::dvec4(p, 1.0)) - eye)
                                     : pixelSize;
        return std::max(pixels * footprint / stretch, floor);
    };
}

// The triangles of a tessellated parametric shape, in object space, and the
// map from its hits back to the surface.
struct TessellatedShape {
    LoadedMesh mesh;
    std::shared_ptr<const TessellatedSurface> surface;
};

TessellatedShape tessellateShape(const SceneDesc& desc, const CameraDesc& camera,
                                 const ShapeDesc& shape, const ParametricSurfacePtr& surface) {
    const ParametricDesc& p = shape.parametric;
    try {
        const double extent = parametricExtent(*surface);
        ParametricGridOptions grid;
        const bool bounded = p.maxError > 0.0 || p.maxEdgePixels > 0.0;
        grid.maxChordError = p.maxError;
        if (p.maxEdgePixels > 0.0)
            grid.maxEdgeLength =
                edgeLengthFromCamera(desc, camera, shape.transform, p.maxEdgePixels, extent);
        if (p.segmentsU > 0) {
            grid.initialSegmentsU = p.segmentsU;
            grid.initialSegmentsV = p.segmentsV;
        } else if (!bounded) {
            grid.maxChordError = kDefaultRelativeError * extent;
        }
        Tessellation t = tessellateParametric(*surface, buildParametricGrid(*surface, grid), p.normals);
        TessellatedShape out;
        out.mesh.mesh = std::move(t.mesh);
        out.surface =
            std::make_shared<TessellatedSurface>(surface, std::move(t), shape.transform, p.normals, shape.flipNormals);
        return out;
    } catch (const Error& e) {
        fail(shapeSource(desc, shape), ": ", e.what());
    }
}

std::shared_ptr<const UserShape> makeDirectShape(const SceneDesc& desc, const ShapeDesc& shape,
                                                 const ParametricSurfacePtr& surface) {
    try {
        ParametricShapeOptions options = shape.parametric.direct;
        options.flipNormals = shape.flipNormals;
        return std::make_shared<ParametricShape>(surface, shape.transform, options);
    } catch (const Error& e) {
        fail(shapeSource(desc, shape), ": ", e.what());
    }
}

}  // namespace

AccelKind accelFromName(const std::string& name) {
    if (name == "embree") return AccelKind::Embree;
    if (name == "naive") return AccelKind::Naive;
    fail("unknown accelerator '", name, "' (choose embree or naive)");
}

const char* accelName(AccelKind kind) { return kind == AccelKind::Naive ? "naive" : "embree"; }

namespace {

// One shape to load: where it is described and where its result goes.
struct ShapeJob {
    const ShapeDesc* desc;
    std::vector<SceneShape>* destination;
};

// The shapes to load: the top level's own, then each prototype's, skipping
// instance entries (flattened separately) and groups no instance reaches.
std::vector<ShapeJob> collectShapeJobs(const SceneDesc& desc,
                                       const scene_detail::FlatInstances& flat, World& world) {
    std::vector<ShapeJob> jobs;
    for (const ShapeDesc& shape : desc.shapes) {
        if (shape.kind != ShapeKind::Instance) jobs.push_back({&shape, &world.shapes});
    }
    world.prototypes.resize(flat.prototypeGroups.size());
    for (size_t p = 0; p < flat.prototypeGroups.size(); ++p) {
        const GroupDesc& group = desc.groups[flat.prototypeGroups[p]];
        world.prototypes[p].name = group.name;
        for (const ShapeDesc& shape : group.shapes) {
            if (shape.kind != ShapeKind::Instance)
                jobs.push_back({&shape, &world.prototypes[p].shapes});
        }
    }
    return jobs;
}

void placeInstances(const SceneDesc& desc, const scene_detail::FlatInstances& flat, World& world) {
    world.instances.reserve(flat.instances.size());
    for (const scene_detail::FlatInstance& instance : flat.instances) {
        // Each transform was checked when parsed, but a product of many can
        // still under- or overflow.
        for (const Mat4& m : instance.motion.empty() ? std::vector<Mat4>{instance.objectToWorld} : instance.motion) {
            const float det = glm::determinant(Mat3(m));
            if (!std::isfinite(det) || det == 0.0f)
                fail(desc.file.filename().string(), ": an instance of group '",
                     desc.groups[flat.prototypeGroups[instance.prototype]].name,
                     "' has a singular or non-finite composed transform");
        }
        if (instance.motion.empty())
            world.instances.emplace_back(instance.prototype, instance.objectToWorld);
        else
            world.instances.emplace_back(instance.prototype, instance.motion);
    }
}

}  // namespace

BuiltScene buildScene(const SceneDesc& desc, const BuildOptions& options, BuildTimings* timings) {
    const auto loadStart = Clock::now();
    BuiltScene built;
    World& world = built.world;
    world.background = desc.background;

    // Material table: 0 is the built-in default, then the scene's own, then the
    // materials of mesh files, named "<shape>/<material>".
    std::map<std::string, uint32_t> byName;
    Material grey;
    grey.name = "default";
    world.materials.push_back(grey);
    byName["default"] = 0;
    for (const MaterialDesc& m : desc.materials) {
        byName[m.name] = static_cast<uint32_t>(world.materials.size());
        world.materials.push_back(scene_detail::buildMaterial(m, desc, world));
    }

    const scene_detail::FlatInstances flat = scene_detail::flattenInstances(desc);
    const std::vector<ShapeJob> jobs = collectShapeJobs(desc, flat, world);

    // Every file once, in parallel; then the camera they may give.
    std::vector<const ShapeDesc*> shapes;
    for (const ShapeJob& job : jobs) shapes.push_back(job.desc);
    scene_detail::SceneFiles files = scene_detail::readSceneFiles(desc, shapes, options.threads);
    built.camera = scene_detail::resolveCamera(desc, files.cameras);

    // Prepare every shape in parallel; the first error (in job order) wins so
    // the message does not depend on thread timing.
    std::vector<LoadedMesh> loaded(jobs.size());
    std::vector<std::shared_ptr<const UserShape>> userShapes(jobs.size());
    std::vector<std::shared_ptr<const TessellatedSurface>> tessellated(jobs.size());
    std::vector<std::exception_ptr> errors(jobs.size());
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t(0), jobs.size(), [&](size_t i) {
            const ShapeDesc& shape = *jobs[i].desc;
            try {
                if (shape.kind == ShapeKind::Implicit) {
                    userShapes[i] = makeImplicitShape(desc, shape);
                    return;
                }
                if (shape.kind == ShapeKind::Curves) {
                    userShapes[i] = makeCurveShape(desc, shape);
                    return;
                }
                if (shape.kind == ShapeKind::Subdivision) {
                    scene_detail::SubdivisionBudget budget;
                    budget.memoryLimitBytes = options.memoryLimitBytes;
                    if (shape.subdivision.maxEdgePixels > 0.0)
                        // The cage is placed in world space before refining:
                        // the camera's bound at world points.
                        budget.maxEdgeLength = edgeLengthFromCamera(desc, built.camera, Mat4(1.0f),
                                                                    shape.subdivision.maxEdgePixels, 0.0);
                    userShapes[i] = scene_detail::makeSubdivisionSurface(shape, shapeSource(desc, shape), budget);
                    return;
                }
                LoadedMesh mesh;
                if (shape.kind == ShapeKind::Parametric) {
                    const ParametricDesc& p = shape.parametric;
                    const ParametricSurfacePtr surface =
                        p.file ? scene_detail::surfaceFromFile(desc, *p.file, std::move(files.shapes[i]))
                               : p.surface;
                    if (p.mode == ParametricMode::Direct) {
                        userShapes[i] = makeDirectShape(desc, shape, surface);
                        return;
                    }
                    TessellatedShape t = tessellateShape(desc, built.camera, shape, surface);
                    mesh = std::move(t.mesh);
                    tessellated[i] = std::move(t.surface);
                } else if (shape.file.empty()) {
                    mesh = LoadedMesh{shape.inlineMesh, {}};
                } else {
                    mesh = std::move(files.shapes[i].mesh);
                }
                mesh.mesh.transform(shape.transform);
                mesh.mesh.validate(shapeSource(desc, shape));
                if (shape.fileNormals == ShapeDesc::FileNormals::Flat) {
                    mesh.mesh.normals.clear();
                } else if (shape.fileNormals == ShapeDesc::FileNormals::Smooth &&
                           mesh.mesh.normals.empty()) {
                    mesh.mesh.computeVertexNormals();  // in world space: after the transform
                }
                if (shape.flipNormals) mesh.mesh.flipOrientation();
                if (mesh.mesh.triangleCount() == 0)
                    fail(shapeSource(desc, shape), ": the mesh has no triangles");
                if (!hasTriangleWithArea(mesh.mesh))
                    fail(shapeSource(desc, shape), ": all ", mesh.mesh.triangleCount(),
                         " triangles of the mesh are degenerate (zero area)");
                loaded[i] = std::move(mesh);
            } catch (...) {
                errors[i] = std::current_exception();
            }
        });
    });
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);

    for (size_t i = 0; i < jobs.size(); ++i) {
        const ShapeDesc& shape = *jobs[i].desc;
        SceneShape geometry;
        geometry.name = shape.name;
        geometry.user = std::move(userShapes[i]);
        geometry.tessellated = std::move(tessellated[i]);
        geometry.mesh = std::move(loaded[i].mesh);
        geometry.mesh.reservePadding();
        if (!shape.material.empty()) {
            // One material for the whole shape overrides the file's own.
            const auto found = byName.find(shape.material);
            if (found == byName.end())
                fail(shapeSource(desc, shape), ": unknown material '", shape.material, "'");
            geometry.mesh.faceMaterials.clear();
            geometry.materialOfSlot = {found->second};
        } else if (loaded[i].materials.empty()) {
            geometry.mesh.faceMaterials.clear();
            geometry.materialOfSlot = {0};
        } else {
            for (const MeshMaterial& m : loaded[i].materials) {
                geometry.materialOfSlot.push_back(static_cast<uint32_t>(world.materials.size()));
                // Its errors (an unreadable texture) name the material; add the scene file.
                try {
                    world.materials.push_back(
                        scene_detail::buildMeshMaterial(m, shape.name + "/" + m.name, world));
                } catch (const Error& e) {
                    fail(desc.file.filename().string(), ": ", e.what());
                }
            }
            collapseUniformSlots(geometry);
        }
        checkMeshAttributes(desc, shape, geometry, world);
        jobs[i].destination->push_back(std::move(geometry));
    }
    placeInstances(desc, flat, world);

    for (const LightDesc& l : desc.lights) world.lights.push_back(scene_detail::buildLight(l, desc, world));
    if (timings) timings->loadSeconds = secondsSince(loadStart);
    const size_t loadedBytes = residentBytes();
    if (options.memoryLimitBytes != 0 && loadedBytes > options.memoryLimitBytes)
        fail(desc.file.string(), ": loading the scene took ", formatBytes(loadedBytes),
             " of memory, more than the memory limit of ", formatBytes(options.memoryLimitBytes));

    const auto bvhStart = Clock::now();
    if (options.bvhStarted) options.bvhStarted();
    world.prepareCutouts();
    const AccelScene refs = world.accelScene();
    if (options.accel == AccelKind::Naive) {
        world.accel = buildNaiveAccel(refs);
    } else {
        AccelBuildOptions accelOptions;
        accelOptions.threads = options.threads;
        accelOptions.progress = options.bvhProgress;
        accelOptions.quality = options.bvhQuality;
        accelOptions.compact = useCompactBvh(options, world.triangleCount());
        accelOptions.quads = options.quads;
        accelOptions.memoryLimitBytes = options.memoryLimitBytes;
        accelOptions.memoryBaselineBytes = loadedBytes;
        try {
            world.accel = buildEmbreeAccel(refs, accelOptions);
        } catch (const Error& e) {
            fail(desc.file.string(), ": ", e.what());  // a memory limit, say: name the scene
        }
    }
    if (timings) timings->bvhSeconds = secondsSince(bvhStart);
    world.lightSelection = desc.render.lightSelection;
    world.prepareLights();
    return built;
}

bool useCompactBvh(const BuildOptions& options, size_t storedTriangles) {
    if (options.compact) return *options.compact;
    return storedTriangles > kCompactBvhAboveTriangles || options.memoryLimitBytes != 0;
}

World buildWorld(const SceneDesc& desc, const BuildOptions& options, BuildTimings* timings) {
    return std::move(buildScene(desc, options, timings).world);
}

Camera buildCamera(const CameraDesc& desc, int width, int height) {
    if (desc.gltf)
        fail(desc.gltf->fileAt.label, ": ", desc.gltf->fileAt.pointer,
             ": the camera is read from the glTF file when the scene is built (buildScene)");
    const CameraFrame frame = desc.back ? CameraFrame::fromBackUp(desc.eye, *desc.back, desc.up)
                                        : CameraFrame::lookAt(desc.eye, desc.lookAt.value_or(Vec3(0.0f)),
                                                              desc.up);
    ImageWindow window;
    if (desc.window) {
        window = *desc.window;
    } else if (desc.projection == Projection::Perspective) {
        const float fovDegrees = desc.fovYDegrees.value_or(45.0f);
        window = Camera::windowFromFov(glm::radians(fovDegrees), desc.focalDistance, width, height);
    }
    Camera camera(frame, desc.projection, window, desc.focalDistance, width, height,
                  ThinLens{desc.apertureRadius, desc.focusDistance});
    camera.setShutter(desc.shutter);
    return camera;
}

PixelFilter buildPixelFilter(const FilmDesc& film) {
    return PixelFilter::fromName(film.filter, film.filterRadius);
}

IntegratorOptions buildIntegratorOptions(const SceneDesc& desc, const Camera& camera) {
    IntegratorOptions options;
    options.maxDepth = desc.render.maxDepth;
    options.russianRoulette = desc.render.russianRoulette;
    options.russianRouletteDepth = desc.render.russianRouletteDepth;
    options.russianRouletteThreshold = desc.render.russianRouletteThreshold;
    options.clampDirect = desc.render.clampDirect;
    options.clampIndirect = desc.render.clampIndirect;
    options.filterGlossy = desc.render.filterGlossy;
    options.aoDistance = desc.render.aoDistance;
    options.aoSamples = desc.render.aoSamples;
    options.hideEmitters = desc.render.hideEmitters;
    // One pixel's extent on the image plane: a width for orthographic rays,
    // an angle (extent / focal distance) for perspective ones.
    const ImageWindow& w = camera.window();
    const float pixel = std::abs(w.t - w.b) / static_cast<float>(camera.height());
    if (camera.projection() == Projection::Orthographic)
        options.coneWidth = pixel;
    else
        options.coneAngle = pixel / camera.focalDistance();
    return options;
}

std::string describeCamera(const CameraDesc& desc) {
    std::ostringstream out;
    out << (desc.projection == Projection::Perspective ? "perspective" : "orthographic") << " eye ("
        << desc.eye.x << "," << desc.eye.y << "," << desc.eye.z << ")";
    if (desc.back)
        out << " back (" << desc.back->x << "," << desc.back->y << "," << desc.back->z << ")";
    else if (desc.lookAt)
        out << " look_at (" << desc.lookAt->x << "," << desc.lookAt->y << "," << desc.lookAt->z << ")";
    out << " d " << desc.focalDistance;
    if (desc.window)
        out << " window [" << desc.window->l << "," << desc.window->r << "," << desc.window->b << ","
            << desc.window->t << "]";
    else if (desc.projection == Projection::Perspective)
        out << " fov " << desc.fovYDegrees.value_or(45.0f);
    return out.str();
}

}  // namespace strahl
