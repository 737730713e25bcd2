// The Mitsuba 3 importer (src/scene/mitsuba_*.cpp, docs/mitsuba.md): the XML
// language (defaults and -D, $ substitution, includes, ids and refs,
// transforms in order), the plugin mappings whose numbers are easy to get
// wrong (max_depth, fov_axis, Mitsuba's default lens), and one clear error,
// with file and line, for what is malformed or not supported.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "strahl/integrator/environment_light.h"
#include "strahl/integrator/surface_hit.h"
#include "strahl/integrator/world.h"
#include "strahl/integrator/projector_light.h"
#include "strahl/integrator/spot_light.h"
#include "strahl/material/conductor.h"
#include "strahl/material/dielectric.h"
#include "strahl/material/diffuse.h"
#include "strahl/material/plastic.h"
#include "strahl/material/thin_dielectric.h"
#include "strahl/scene/scene_builder.h"
#include "strahl/scene/scene_desc.h"
#include "strahl/scene/scene_document.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

// A scene around `body`: a perspective sensor (fov 90 along x, 64 x 32
// pixels, 16 spp by default), a path integrator and a rectangle.
std::string xmlScene(const std::string& body,
                     const std::string& integrator = R"(<integrator type="path"/>)") {
    return R"(<scene version="3.0.0">
  <default name="spp" value="16"/>
  )" + integrator + R"(
  <sensor type="perspective">
    <float name="fov" value="90"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="32"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
  </sensor>
  <shape type="rectangle"/>
  )" + body + "\n</scene>\n";
}

SceneDesc parse(const std::string& text, const SceneDefines& defines = {},
                const fs::path& file = "scene.xml") {
    return SceneDocument::fromText(text, file, defines).parse();
}

std::string xmlError(const std::string& text, const SceneDefines& defines = {}) {
    return test::errorMessage([&] { parse(text, defines); });
}

TEST(MitsubaImport, DefaultsAreSubstitutedAndMinusDOverridesThem) {
    EXPECT_EQ(parse(xmlScene("")).render.spp, 16);
    EXPECT_EQ(parse(xmlScene(""), {{"spp", "4"}}).render.spp, 4);
    EXPECT_THAT(xmlError(xmlScene(""), {{"sp", "4"}}),
                HasSubstr("scene.xml: -D sp: the scene has no <default name=\"sp\"> and no $sp"));
    EXPECT_THAT(xmlError(xmlScene(R"(<emitter type="point"><rgb name="intensity" value="$power"/></emitter>)")),
                HasSubstr("scene.xml:11: $power: no <default> or -D gives it a value"));
}

TEST(MitsubaImport, TheSensorBecomesTheCameraWithAVerticalFov) {
    const SceneDesc d = parse(xmlScene(""));
    EXPECT_EQ(d.film.width, 64);
    EXPECT_EQ(d.film.height, 32);
    EXPECT_EQ(d.camera.eye, Vec3(0, 0, 5));
    ASSERT_TRUE(d.camera.back.has_value());
    EXPECT_NEAR(d.camera.back->z, 1.0f, 1e-6f);  // looking down -z
    // 90 degrees along x on a 2:1 film: tan(fov_y / 2) = tan(45°) / 2.
    EXPECT_NEAR(*d.camera.fovYDegrees, 2.0 * std::atan(0.5) * 180.0 / M_PI, 1e-4);
    EXPECT_EQ(d.film.filter, "gaussian");  // hdrfilm's default filter
    EXPECT_FLOAT_EQ(*d.film.filterRadius, 2.0f);
}

TEST(MitsubaImport, WithoutAFovTheSensorHasMitsubasFiftyMillimetreLens) {
    std::string text = xmlScene("");
    text.replace(text.find(R"(<float name="fov" value="90"/>)"), 30, "");
    // 50 mm on 36 x 24 mm film along the diagonal: 46.793°; on a 2:1 film
    // the vertical half-angle's tangent is tan(23.40°) / sqrt(5).
    const double ty = std::tan(46.7930 / 2 * M_PI / 180) / std::sqrt(5.0);
    EXPECT_NEAR(*parse(text).camera.fovYDegrees, 2 * std::atan(ty) * 180 / M_PI, 1e-3);
}

TEST(MitsubaImport, AThinLensSensorKeepsItsLens) {
    std::string text = xmlScene("");
    text.replace(text.find(R"(<sensor type="perspective">)"), 27,
                 R"(<sensor type="thinlens"><float name="aperture_radius" value="0.1"/>)");
    const SceneDesc lens = parse(text);
    EXPECT_FLOAT_EQ(lens.camera.apertureRadius, 0.1f);
    EXPECT_FALSE(lens.camera.focusDistance.has_value());  // strahl's default: the focal distance
    text.replace(text.find("<float name=\"aperture_radius\""), 0,
                 R"(<float name="focus_distance" value="4"/>)");
    EXPECT_FLOAT_EQ(*parse(text).camera.focusDistance, 4.0f);
    EXPECT_THAT(xmlError(xmlScene(R"()").replace(xmlScene("").find("<float name=\"fov\""), 0,
                                                 R"(<float name="aperture_radius" value="0.1"/>)")),
                HasSubstr("aperture_radius and focus_distance belong to a thinlens sensor"));
}

TEST(MitsubaImport, MaxDepthCountsVerticesInMitsubaAndBouncesInStrahl) {
    const auto depth = [](const std::string& value) {
        return parse(xmlScene("", R"(<integrator type="path"><integer name="max_depth" value=")" +
                                      value + R"("/></integrator>)"))
            .render.maxDepth;
    };
    EXPECT_EQ(depth("1"), 0);   // emitters seen directly
    EXPECT_EQ(depth("2"), 1);   // and direct light
    EXPECT_EQ(depth("-1"), 1024);  // unlimited: strahl's most
    EXPECT_THAT(xmlError(xmlScene("", R"(<integrator type="path"><integer name="max_depth" value="0"/></integrator>)")),
                HasSubstr("max_depth must be -1 or at least 1"));
    const SceneDesc wrapped = parse(xmlScene("", R"(<integrator type="moment"><integrator type="direct"/></integrator>)"));
    EXPECT_EQ(wrapped.render.integrator, "direct");
}

TEST(MitsubaImport, RrDepthIsTheBounceRouletteStartsAfter) {
    const auto rrDepth = [](const std::string& integrator) {
        return parse(xmlScene("", integrator)).render.russianRouletteDepth;
    };
    EXPECT_EQ(rrDepth(R"(<integrator type="path"/>)"), 5);  // Mitsuba's default
    EXPECT_EQ(rrDepth(R"(<integrator type="path"><integer name="rr_depth" value="2"/></integrator>)"), 2);
    EXPECT_EQ(rrDepth(R"(<integrator type="path"><integer name="rr_depth" value="0"/></integrator>)"), 1);
}

// The material kind K of the cube's BSDF `bsdf` (the second material: the
// rectangle's default comes first).
template <typename K>
K cubeMaterial(const std::string& bsdf) {
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube">)" + bsdf + "</shape>"));
    const K* kind = d.materials.size() == 2 ? std::get_if<K>(&d.materials[1].material.kind) : nullptr;
    if (!kind) {
        ADD_FAILURE() << "not the expected material kind: " << bsdf;
        return K{};
    }
    return *kind;
}

TEST(MitsubaImport, ConductorsTakeMitsubasNamedMaterialsAndItsMicrofacetModel) {
    // Default material "none": the lossless mirror eta 0, k 1.
    const auto mirror = cubeMaterial<ConductorMaterial>(R"(<bsdf type="conductor"/>)");
    EXPECT_EQ(mirror.eta, Color(0.0f));
    EXPECT_EQ(mirror.k, Color(1.0f));
    EXPECT_EQ(mirror.roughnessU.value, 0.0f);
    // Aluminium as Mitsuba's RGB variants convert its measured spectra.
    const auto al = cubeMaterial<ConductorMaterial>(R"(<bsdf type="roughconductor">
        <string name="material" value="Al"/><string name="distribution" value="ggx"/>
        <float name="alpha_u" value="0.25"/><float name="alpha_v" value="0.04"/></bsdf>)");
    EXPECT_NEAR(al.eta.r, 1.6575f, 1e-4f);
    EXPECT_NEAR(al.k.b, 4.837f, 1e-4f);
    EXPECT_FLOAT_EQ(al.roughnessU.value, 0.5f);  // roughness = sqrt(alpha)
    EXPECT_FLOAT_EQ(al.roughnessV.value, 0.2f);
    EXPECT_EQ(al.microfacets.type, MicrofacetType::Ggx);
    EXPECT_EQ(al.microfacets.masking, MicrofacetMasking::Separable);
    // Mitsuba's defaults: Beckmann, alpha 0.1; eta and k given directly.
    const auto given = cubeMaterial<ConductorMaterial>(R"(<bsdf type="roughconductor">
        <spectrum name="eta" value="0.789"/><spectrum name="k" value="6.15"/></bsdf>)");
    EXPECT_EQ(given.eta, Color(0.789f));
    EXPECT_EQ(given.microfacets.type, MicrofacetType::Beckmann);
    EXPECT_NEAR(given.roughnessU.value, std::sqrt(0.1f), 1e-6f);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="conductor"><string name="material" value="K"/></bsdf></shape>)")),
                HasSubstr("scene.xml:11: <bsdf type=\"conductor\">: the conductor material 'K' is not available"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="roughconductor"><float name="alpha_u" value="0.2"/></bsdf></shape>)")),
                HasSubstr("give either alpha or both alpha_u and alpha_v"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="conductor"><rgb name="specular_reflectance" value="0.5"/></bsdf></shape>)")),
                HasSubstr("'specular_reflectance' other than 1 is not supported"));
}

TEST(MitsubaImport, DielectricsAndPlasticsTakeTheRatioOfNamedIors) {
    const auto diamond = cubeMaterial<DielectricMaterial>(R"(<bsdf type="dielectric">
        <string name="int_ior" value="diamond"/><string name="ext_ior" value="air"/></bsdf>)");
    EXPECT_FLOAT_EQ(diamond.ior, float(2.419 / 1.000277));
    EXPECT_EQ(diamond.roughness.value, 0.0f);
    const auto glass = cubeMaterial<DielectricMaterial>(R"(<bsdf type="roughdielectric">
        <float name="alpha" value="0.04"/></bsdf>)");
    EXPECT_FLOAT_EQ(glass.ior, float(1.5046 / 1.000277));  // bk7 in air
    EXPECT_FLOAT_EQ(glass.roughness.value, 0.2f);
    EXPECT_EQ(glass.microfacets.type, MicrofacetType::Beckmann);
    const auto plastic = cubeMaterial<PlasticMaterial>(R"(<bsdf type="plastic">
        <rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/><float name="int_ior" value="1.9"/></bsdf>)");
    EXPECT_EQ(plastic.color.value, Color(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(plastic.ior, float(1.9 / 1.000277));
    EXPECT_FALSE(plastic.nonlinear);  // Mitsuba's default
    EXPECT_EQ(plastic.roughCoat, nullptr);
    const auto rough = cubeMaterial<PlasticMaterial>(R"(<bsdf type="roughplastic">
        <string name="distribution" value="ggx"/><boolean name="nonlinear" value="true"/></bsdf>)");
    EXPECT_FLOAT_EQ(rough.ior, float(1.49 / 1.000277));  // polypropylene
    EXPECT_TRUE(rough.nonlinear);
    EXPECT_TRUE(rough.microfacetCoat);
    ASSERT_NE(rough.roughCoat, nullptr);  // tabulated for alpha 0.1
    EXPECT_FLOAT_EQ(rough.roughCoat->eta(), rough.ior);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="dielectric"><string name="int_ior" value="unobtainium"/></bsdf></shape>)")),
                HasSubstr("unknown int_ior 'unobtainium' (known: vacuum, helium"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="dielectric"><string name="int_ior" value="air"/><string name="ext_ior" value="water"/></bsdf></shape>)")),
                HasSubstr("strahl's interfaces need a relative index in [1.0001, 4]"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="roughdielectric"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf></shape>)")),
                HasSubstr("an anisotropic roughness (alpha_u, alpha_v) is only supported on conductors"));
}

TEST(MitsubaImport, AThinDielectricIsAThinSheetOfTheRatioOfIors) {
    const auto sheet = cubeMaterial<ThinDielectricMaterial>(R"(<bsdf type="thindielectric">
        <string name="int_ior" value="pyrex"/></bsdf>)");
    EXPECT_FLOAT_EQ(sheet.ior, float(1.470 / 1.000277));
}

TEST(MitsubaImport, AMaskIsTheOpacityOfItsNestedBsdf) {
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><bsdf type="mask">
        <float name="opacity" value="0.25"/>
        <bsdf type="twosided"><bsdf type="roughconductor"/></bsdf></bsdf></shape>)"));
    ASSERT_EQ(d.materials.size(), 2u);
    EXPECT_NE(std::get_if<ConductorMaterial>(&d.materials[1].material.kind), nullptr);
    EXPECT_EQ(d.materials[1].material.opacity.value, 0.25f);
    // Mitsuba's default opacity is 0.5.
    const SceneDesc half = parse(xmlScene(R"(<shape type="cube"><bsdf type="mask"><bsdf type="diffuse"/></bsdf></shape>)"));
    EXPECT_EQ(half.materials[1].material.opacity.value, 0.5f);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="mask"><rgb name="opacity" value="0.1, 0.2, 0.3"/><bsdf type="diffuse"/></bsdf></shape>)")),
                HasSubstr("'opacity' must be one number or a texture"));
}

TEST(MitsubaImport, ABlendbsdfIsABlendOfItsTwoBsdfsWeightedByANumberOrAMeshAttribute) {
    const auto blend = cubeMaterial<BlendMaterial>(R"(<bsdf type="blendbsdf">
        <float name="weight" value="0.3"/>
        <bsdf type="diffuse"/><bsdf type="twosided"><bsdf type="roughconductor"/></bsdf></bsdf>)");
    EXPECT_EQ(blend.weight.value, 0.3f);
    EXPECT_TRUE(std::holds_alternative<DiffuseMaterial>(blend.parts[0]->kind));
    EXPECT_TRUE(std::holds_alternative<ConductorMaterial>(blend.parts[1]->kind));
    const auto attributed = cubeMaterial<BlendMaterial>(R"(<bsdf type="blendbsdf">
        <texture type="mesh_attribute" name="weight"><string name="name" value="face_weight"/></texture>
        <bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>)");
    EXPECT_EQ(attributed.weight.texture.meshAttribute, "face_weight");
    const auto coloured = cubeMaterial<DiffuseMaterial>(R"(<bsdf type="diffuse">
        <texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/>
        <float name="scale" value="0.5"/></texture></bsdf>)");
    EXPECT_EQ(coloured.color.texture.meshAttribute, "vertex_color");
    EXPECT_EQ(coloured.color.value, Color(0.5f));

    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="blendbsdf"><float name="weight" value="0.5"/><bsdf type="diffuse"/></bsdf></shape>)")),
                HasSubstr(R"(<bsdf type="blendbsdf">: needs two nested <bsdf>s)"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="blendbsdf"><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf></shape>)")),
                HasSubstr(R"(<bsdf type="blendbsdf">: needs a weight)"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="blendbsdf"><float name="weight" value="0.5"/>
        <bsdf type="diffuse"/><bsdf type="mask"><bsdf type="diffuse"/></bsdf></bsdf></shape>)")),
                HasSubstr(R"(<bsdf type="mask">: a normalmap, bumpmap, mask or null BSDF inside a blendbsdf is not supported)"));
}

TEST(MitsubaImport, PrincipledBsdfsKeepTheirParametersUnderStrahlsNames) {
    const auto solid = cubeMaterial<PrincipledMaterial>(R"(<bsdf type="principled">
        <rgb name="base_color" value="0.2, 0.8, 0.1"/><float name="roughness" value="0.15"/>
        <float name="spec_trans" value="0.3"/><float name="specular" value="0.7"/>
        <texture name="metallic" type="checkerboard"><float name="color0" value="0.7"/>
        <float name="color1" value="0.1"/></texture></bsdf>)");
    EXPECT_EQ(solid.color.value, Color(0.2f, 0.8f, 0.1f));
    EXPECT_EQ(solid.roughness.value, 0.15f);
    EXPECT_EQ(solid.transmission.value, 0.3f);
    EXPECT_NEAR(solid.eta, PrincipledMaterial::etaOfSpecular(0.7f), 1e-6f);
    EXPECT_FALSE(solid.thin);
    // Mitsuba reads a checkerboard as a number with its colours exchanged.
    ASSERT_TRUE(solid.metallic.checkerboard.has_value());
    EXPECT_EQ(solid.metallic.checkerboard->color0, Color(0.1f));
    EXPECT_EQ(solid.metallic.checkerboard->color1, Color(0.7f));

    const auto thin = cubeMaterial<PrincipledMaterial>(R"(<bsdf type="principledthin">
        <float name="diff_trans" value="1.4"/><float name="eta" value="1.33"/></bsdf>)");
    EXPECT_TRUE(thin.thin);
    EXPECT_EQ(thin.diffuseTransmission.value, 1.4f);
    EXPECT_EQ(thin.eta, 1.33f);

    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="principledthin"><float name="metallic" value="0.5"/></bsdf></shape>)")),
                HasSubstr("the parameter 'metallic' is not supported"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="principled"><rgb name="sheen" value="0.1, 0.2, 0.3"/></bsdf></shape>)")),
                HasSubstr("'sheen' must be one number or a texture"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="principled"><texture name="sheeen" type="checkerboard"/></bsdf></shape>)")),
                HasSubstr("not a parameter of principled"));
}

// Whether a ray from `origin` along `dir` hits anything, and at what distance.
float hitDistance(const World& world, Vec3 origin, Vec3 dir) {
    Ray ray;
    ray.origin = origin;
    ray.dir = dir;
    const Hit hit = world.accel->intersect(ray);
    return hit.valid() ? hit.t : -1.0f;
}

TEST(MitsubaImport, DisksCylindersAndEmittingSpheresAreMeshesOrExactSurfaces) {
    // The rectangle of xmlScene() is at z = 0 in [-1, 1]²: these shapes sit above it.
    const World world = buildWorld(parse(xmlScene(R"(
        <shape type="disk"><transform name="to_world"><scale value="0.5"/><translate z="2"/></transform></shape>
        <shape type="cylinder"><point name="p0" x="3" y="0" z="0"/><point name="p1" x="3" y="0" z="2"/>
            <float name="radius" value="0.5"/></shape>
        <shape type="sphere"><point name="center" x="-3" y="0" z="1"/><float name="radius" value="0.5"/>
            <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>)")), {});
    // The disk (radius 0.5 at z = 2), through its polygonal rim's error.
    EXPECT_NEAR(hitDistance(world, Vec3(0.3f, 0, 5), Vec3(0, 0, -1)), 3.0f, 1e-5f);
    EXPECT_NEAR(hitDistance(world, Vec3(0.51f, 0, 5), Vec3(0, 0, -1)), 5.0f, 1e-5f);  // the rectangle below
    {
        // Its front (the side a one-sided emitter lights) faces +z, as Mitsuba's.
        Ray ray;
        ray.origin = Vec3(0.2f, 0.1f, 5);
        ray.dir = Vec3(0, 0, -1);
        const Hit hit = world.accel->intersect(ray);
        const SurfaceHit surface(world, ray, hit);
        EXPECT_GT(surface.interaction().Ng.z, 0.99f);
    }
    // The open tube from (3, 0, 0) to (3, 0, 2), exact: x = 3.5 from outside.
    EXPECT_NEAR(hitDistance(world, Vec3(6, 0, 1), Vec3(-1, 0, 0)), 2.5f, 1e-5f);
    // The emitting sphere is a mesh within 10^-4 of the radius, and a light.
    EXPECT_NEAR(hitDistance(world, Vec3(-3, 0, 5), Vec3(0, 0, -1)), 3.5f, 1e-4f);
    EXPECT_GT(world.lightSet.lights().size(), 1000u);

    const SceneDesc d = parse(xmlScene(R"(<shape type="disk"/>)"));
    EXPECT_EQ(d.shapes.back().kind, ShapeKind::Parametric);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cylinder"><point name="p1" x="0" y="0" z="0"/></shape>)")),
                HasSubstr("p0 and p1 must differ"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="disk"><bsdf type="diffuse"><texture name="reflectance" type="checkerboard"/></bsdf></shape>)")),
                HasSubstr("a textured material on a Mitsuba disk is not supported"));
}

TEST(MitsubaImport, HideEmittersIsTheRenderSetting) {
    EXPECT_TRUE(parse(xmlScene("", R"(<integrator type="path"><boolean name="hide_emitters" value="true"/></integrator>)"))
                    .render.hideEmitters);
    EXPECT_TRUE(parse(xmlScene("", R"(<integrator type="direct"><boolean name="hide_emitters" value="true"/></integrator>)"))
                    .render.hideEmitters);
    EXPECT_FALSE(parse(xmlScene("")).render.hideEmitters);
}

TEST(MitsubaImport, AFilmCropIsTheScenesCrop) {
    std::string text = xmlScene("");
    const std::string film = R"(<integer name="height" value="32"/>)";
    text.replace(text.find(film), film.size(),
                 film + R"(<integer name="crop_offset_x" value="8"/><integer name="crop_offset_y" value="4"/>
                           <integer name="crop_width" value="16"/>)");
    const SceneDesc d = parse(text);
    ASSERT_TRUE(d.film.crop.has_value());
    EXPECT_EQ(d.film.crop->x0, 8);
    EXPECT_EQ(d.film.crop->y0, 4);
    EXPECT_EQ(d.film.crop->x1, 24);
    EXPECT_EQ(d.film.crop->y1, 32);  // the rest of the film's height
    std::string outside = xmlScene("");
    outside.replace(outside.find(film), film.size(), film + R"(<integer name="crop_width" value="65"/>)");
    EXPECT_THAT(xmlError(outside), HasSubstr("must lie inside the film"));
    EXPECT_FALSE(parse(xmlScene("")).film.crop.has_value());
}

TEST(MitsubaImport, ANullBsdfIsAnInvisibleSurfaceButNoInvisibleLight) {
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><bsdf type="null"/></shape>)"));
    ASSERT_EQ(d.materials.size(), 2u);
    EXPECT_EQ(d.materials[1].material.opacity.value, 0.0f);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="null"/><emitter type="area"/></shape>)")),
                HasSubstr(R"(<bsdf type="null">: an emitter with a null BSDF (an invisible light) is not supported)"));
}

TEST(MitsubaImport, ANormalmapIsTheNormalMapOfItsNestedBsdfWithTerminatorShadowing) {
    const fs::path dir = test::scratchDir("mitsuba-normalmap");
    test::writeFile(dir / "n.png", "not read while parsing");
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><bsdf type="normalmap">
        <texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/>
          <string name="filename" value="n.png"/></texture>
        <bsdf type="diffuse"/></bsdf></shape>)"), {}, dir / "scene.xml");
    const Material& m = d.materials.at(1).material;
    EXPECT_EQ(m.normalMap.file.filename(), "n.png");
    EXPECT_TRUE(m.terminatorShadowing);
    EXPECT_EQ(m.normalMap.sampling.filter, TextureFilter::Bilinear);  // Mitsuba's point reads
    // The identity constant adds nothing; other constants are refused.
    const SceneDesc identity = parse(xmlScene(R"(<shape type="cube"><bsdf type="normalmap">
        <texture name="normalmap" type="rawconstant"><vector name="value" value="0.5, 0.5, 1"/></texture>
        <bsdf type="diffuse"/></bsdf></shape>)"));
    EXPECT_TRUE(identity.materials.at(1).material.normalMap.file.empty());
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="normalmap">
        <texture name="normalmap" type="rawconstant"><vector name="value" value="0.6, 0.5, 1"/></texture>
        <bsdf type="diffuse"/></bsdf></shape>)")),
                HasSubstr("a constant normal map other than the identity (0.5, 0.5, 1) is not supported"));
}

TEST(MitsubaImport, ReconstructionFilters) {
    const auto filmWith = [](const std::string& rfilter) {
        std::string text = xmlScene("");
        const std::string film = R"(<film type="hdrfilm">)";
        text.replace(text.find(film), film.size(), film + rfilter);
        return text;
    };
    const SceneDesc gaussian = parse(xmlScene(""));  // Mitsuba's default: Gaussian, sigma 0.5
    EXPECT_EQ(gaussian.film.filter, "gaussian");
    EXPECT_EQ(gaussian.film.filterRadius, 2.0f);
    const SceneDesc tent = parse(filmWith(R"(<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>)"));
    EXPECT_EQ(tent.film.filter, "tent");
    EXPECT_EQ(tent.film.filterRadius, 1.5f);
    EXPECT_THAT(xmlError(filmWith(R"(<rfilter type="mitchell"/>)")),
                HasSubstr("this reconstruction filter is not supported (box, tent and gaussian are)"));
}

TEST(MitsubaImport, TransformsApplyInTheOrderWritten) {
    const fs::path dir = test::scratchDir("mitsuba-transform");
    test::writeFile(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const SceneDesc d = parse(xmlScene(R"(<shape type="obj" id="moved">
    <string name="filename" value="tri.obj"/>
    <transform name="to_world"><translate x="1"/><scale value="2"/></transform>
  </shape>)"), {}, dir / "scene.xml");
    ASSERT_EQ(d.shapes.size(), 2u);
    // Translated first, then scaled: the origin lands at (2, 0, 0).
    const Vec4 origin = d.shapes[1].transform * Vec4(0, 0, 0, 1);
    EXPECT_FLOAT_EQ(origin.x, 2.0f);
    EXPECT_FLOAT_EQ(d.shapes[1].transform[0][0], 2.0f);
}

TEST(MitsubaImport, SpectrumFilesAreTheSpectraTheyList) {
    const fs::path dir = test::scratchDir("mitsuba-spd");
    test::writeFile(dir / "spectra/red.spd", "# a comment\n400 0.1\n\n500 0.3  # another\n600 0.8\n");
    const auto reflectance = [&](const std::string& spectrum) {
        test::writeFile(dir / "scene.xml", xmlScene(R"(<path value="spectra"/>
  <shape type="cube"><bsdf type="diffuse">)" + spectrum + "</bsdf></shape>"));
        return SceneDocument::read(dir / "scene.xml").parse().materials.at(1).material;
    };
    const auto diffuseOf = [](const Material& m) { return std::get<DiffuseMaterial>(m.kind).color.value; };
    EXPECT_EQ(diffuseOf(reflectance(R"(<spectrum name="reflectance" filename="red.spd"/>)")),
              diffuseOf(reflectance(R"(<spectrum name="reflectance" value="400:0.1, 500:0.3, 600:0.8"/>)")));
    test::writeFile(dir / "spectra/bad.spd", "400 0.1\n500 0.3 7\n");
    EXPECT_THAT(test::errorMessage([&] { reflectance(R"(<spectrum name="reflectance" filename="bad.spd"/>)"); }),
                HasSubstr("bad.spd:2: expected a wavelength and a value, got 3 numbers"));
    EXPECT_THAT(test::errorMessage([&] { reflectance(R"(<spectrum name="reflectance" filename="gone.spd"/>)"); }),
                HasSubstr("scene.xml:12: cannot open"));
}

TEST(MitsubaImport, SerializedShapesPickTheirMeshByShapeIndex) {
    const fs::path dir = test::scratchDir("mitsuba-serialized");
    test::writeFile(dir / "scene.serialized", "read when the world is built");
    const SceneDesc d = parse(xmlScene(R"(<shape type="serialized"><string name="filename" value="scene.serialized"/>
        <integer name="shape_index" value="2"/></shape>)"), {}, dir / "scene.xml");
    EXPECT_EQ(d.shapes.at(1).file.filename(), "scene.serialized");
    EXPECT_EQ(d.shapes.at(1).shapeIndex, 2u);
    EXPECT_EQ(d.shapes.at(1).fileNormals, ShapeDesc::FileNormals::Smooth);  // Mitsuba computes them
    test::writeFile(dir / "mesh.bin", "x");
    EXPECT_THAT(test::errorMessage([&] {
                    parse(xmlScene(R"(<shape type="serialized"><string name="filename" value="mesh.bin"/></shape>)"),
                          {}, dir / "scene.xml");
                }),
                HasSubstr("the file must end in .serialized"));
}

TEST(MitsubaImport, FlipNormalsTurnsAMeshAround) {
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><boolean name="flip_normals" value="true"/></shape>)"));
    EXPECT_TRUE(d.shapes.at(1).flipNormals);
    EXPECT_FALSE(d.shapes.at(0).flipNormals);
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="sphere"><boolean name="flip_normals" value="true"/></shape>)")),
                HasSubstr("flip_normals on a sphere is not supported yet"));
}

TEST(MitsubaImport, IdsAndRefsShareOneMaterialAndLightsMap) {
    const SceneDesc d = parse(xmlScene(R"(
  <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
  <shape type="sphere"><float name="radius" value="0.5"/><ref id="red"/></shape>
  <shape type="cube"><ref id="red"/></shape>
  <emitter type="point"><point name="position" x="0" y="2" z="0"/><rgb name="intensity" value="10"/></emitter>
  <emitter type="constant"><rgb name="radiance" value="0.25"/></emitter>)"));
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[1].kind, ShapeKind::Implicit);
    EXPECT_EQ(d.shapes[1].material, "red");
    EXPECT_EQ(d.shapes[2].material, "red");
    EXPECT_EQ(d.shapes[0].material, "mitsuba-default");  // Mitsuba's grey 0.5
    ASSERT_EQ(d.lights.size(), 1u);
    EXPECT_EQ(d.background, Color(0.25f));
}

TEST(MitsubaImport, IncludesAreSplicedInAndCyclesRefused) {
    const fs::path dir = test::scratchDir("mitsuba-include");
    test::writeFile(dir / "parts/light.xml", R"(<scene version="3.0.0">
  <emitter type="point"><point name="position" x="0" y="2" z="0"/></emitter>
</scene>)");
    test::writeFile(dir / "main.xml", xmlScene(R"(<include filename="parts/light.xml"/>)"));
    EXPECT_EQ(SceneDocument::read(dir / "main.xml").parse().lights.size(), 1u);

    test::writeFile(dir / "loop.xml", xmlScene(R"(<include filename="loop.xml"/>)"));
    EXPECT_THAT(test::errorMessage([&] { SceneDocument::read(dir / "loop.xml"); }),
                HasSubstr(":11: <include filename=\"loop.xml\">: includes itself (a cycle)"));
    test::writeFile(dir / "gone.xml", xmlScene(R"(<include filename="nowhere.xml"/>)"));
    EXPECT_THAT(test::errorMessage([&] { SceneDocument::read(dir / "gone.xml"); }),
                HasSubstr("gone.xml:11: cannot open"));
}

TEST(MitsubaImport, MalformedOrUnsupportedInputIsOneErrorWithItsLine) {
    EXPECT_THAT(xmlError("<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n</scene>"),
                HasSubstr("scene.xml:3: malformed XML"));
    EXPECT_THAT(xmlError("<scene version=\"0.6.0\"/>"),
                HasSubstr("scene.xml:1: <scene version=\"0.6.0\">: only scene versions 2.x and 3.x"));
    EXPECT_THAT(xmlError(xmlScene(R"(<medium type="homogeneous"/>)")),
                HasSubstr("scene.xml:11: <medium type=\"homogeneous\">: participating media are not supported"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="rectangle"><bsdf type="hair"/></shape>)")),
                HasSubstr("scene.xml:11: <bsdf type=\"hair\">: this BSDF is not supported yet"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="rectangle"><float name="sharpness" value="1"/></shape>)")),
                HasSubstr("scene.xml:11: <shape type=\"rectangle\">: the parameter 'sharpness' is not supported"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="rectangle"><ref id="nothing"/></shape>)")),
                HasSubstr("scene.xml:11: <ref id=\"nothing\">: no object with this id before it"));
    EXPECT_THAT(xmlError(xmlScene(R"(<teapot/>)")),
                HasSubstr("scene.xml:11: <teapot>: not an element of Mitsuba 3's scene language"));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="rectangle"><transform name="to_world"><rotate angle="10"/></transform></shape>)")),
                HasSubstr("scene.xml:11: <rotate>: needs a non-zero axis"));
    EXPECT_THAT(xmlError(xmlScene(R"(<emitter type="point"><rgb name="intensity" value="1, two, 3"/></emitter>)")),
                HasSubstr("is not a list of numbers"));
}

TEST(MitsubaImport, CheckerboardsAreStrahlTexturedColours) {
    const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><bsdf type="diffuse">
    <texture name="reflectance" type="checkerboard">
      <rgb name="color0" value="0.9"/><transform name="to_uv"><scale x="4" y="2"/></transform>
    </texture></bsdf></shape>)"));
    ASSERT_EQ(d.materials.size(), 2u);  // the rectangle's default and the cube's
    const auto* diffuse = std::get_if<DiffuseMaterial>(&d.materials[1].material.kind);
    ASSERT_NE(diffuse, nullptr);
    ASSERT_TRUE(diffuse->color.checkerboard.has_value());
    EXPECT_EQ(diffuse->color.checkerboard->color0, Color(0.9f));
    EXPECT_EQ(diffuse->color.checkerboard->color1, Color(0.2f));
    EXPECT_EQ(diffuse->color.checkerboard->scale, Vec2(4.0f, 2.0f));
    EXPECT_THAT(xmlError(xmlScene(R"(<shape type="cube"><bsdf type="diffuse">
    <texture name="reflectance" type="checkerboard">
      <transform name="to_uv"><rotate z="1" angle="30"/></transform>
    </texture></bsdf></shape>)")),
                HasSubstr("a to_uv other than a positive scale is not supported yet"));
    // In strahl JSON: one of texture and checkerboard.
    EXPECT_THAT(test::errorMessage([] {
                    parseSceneText(R"({"materials": [{"name": "m", "color": {"checkerboard": {},
                        "texture": "x.png"}}], "shapes": [{"type": "mesh",
                        "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [0,1,2]}]})",
                                   "scene.json");
                }),
                HasSubstr("/materials/0/color: 'texture' and 'checkerboard' are exclusive"));
}

// The colour of the first emitting material's emission, or the diffuse
// colour of material `index`.
Color emissionOf(const SceneDesc& d) {
    for (const auto& m : d.materials)
        if (m.material.emits()) return m.material.emission.value;
    ADD_FAILURE() << "no emitting material";
    return Color(0.0f);
}
Color diffuseColour(const SceneDesc& d, size_t index) {
    const auto* diffuse = std::get_if<DiffuseMaterial>(&d.materials.at(index).material.kind);
    if (!diffuse) ADD_FAILURE() << "material " << index << " is not diffuse";
    return diffuse ? diffuse->color.value : Color(0.0f);
}
float luminance(const Color& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

std::string spectralRectangle(const std::string& reflectance, const std::string& radiance) {
    return R"(<shape type="rectangle"><bsdf type="diffuse"><spectrum name="reflectance" value=")" +
           reflectance + R"("/></bsdf><emitter type="area"><spectrum name="radiance" value=")" +
           radiance + R"("/></emitter></shape>)";
}

TEST(MitsubaImport, SpectraBecomeRgbAsInMitsubasRgbVariants) {
    // A constant reflectance is that grey (D65 is a reflectance's white).
    SceneDesc d = parse(xmlScene(spectralRectangle("360:0.5, 830:0.5", "400:0, 500:8, 600:15.6, 700:18.4")));
    const Color grey = diffuseColour(d, 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(grey[c], 0.5f, 1e-3f) << c;
    // Emitted light is integrated without D65: a constant 1 over the visible
    // range has luminance 1 and is the equal-energy white, (1.2048, 0.9483,
    // 0.9089) in linear sRGB, as a single value 1 gives it in an emitter.
    d = parse(xmlScene(spectralRectangle("0.5", "360:1, 830:1")));
    const Color white = emissionOf(d);
    EXPECT_NEAR(luminance(white), 1.0f, 1e-3f);
    d = parse(xmlScene(spectralRectangle("0.5", "1")));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(emissionOf(d)[c], white[c], 1e-3f) << c;
    EXPECT_NEAR(emissionOf(d).r, 1.2048f, 1e-4f);
    EXPECT_NEAR(emissionOf(d).b, 0.9089f, 1e-4f);
    EXPECT_EQ(diffuseColour(d, 1), Color(0.5f));  // a single value is grey outside emitters
    // Orange light (590-630 nm) is red and green without blue (clamped at 0);
    // a reflectance above 1 is clamped to 1, radiance is not.
    d = parse(xmlScene(spectralRectangle("400:3, 700:3", "590:0, 610:20, 630:0")));
    const Color orange = emissionOf(d);
    EXPECT_GT(orange.r, orange.g);
    EXPECT_GT(orange.g, 0.0f);
    EXPECT_EQ(orange.b, 0.0f);
    EXPECT_GT(orange.r, 1.0f);
    EXPECT_EQ(diffuseColour(d, 1), Color(1.0f));

    EXPECT_THAT(xmlError(xmlScene(spectralRectangle("500:0.5", "1"))),
                HasSubstr("scene.xml:11: <spectrum name=\"reflectance\">: needs at least two wavelengths"));
    EXPECT_THAT(xmlError(xmlScene(spectralRectangle("500:0.5, 400:0.5", "1"))),
                HasSubstr("wavelengths must increase (400 after 500)"));
    EXPECT_THAT(xmlError(xmlScene(spectralRectangle("500:0.5, 600-0.5", "1"))),
                HasSubstr("'600-0.5' is not a wavelength:value pair"));
}

// A mesh file without normals is smooth in Mitsuba (it computes them), flat
// with face_normals; the file's own normals are kept otherwise.
TEST(MitsubaImport, MeshFilesWithoutNormalsAreSmoothUnlessFaceNormals) {
    const fs::path dir = test::scratchDir("mitsuba-normals");
    // A square pyramid without normals: 4 sides and a base.
    test::writeFile(dir / "pyramid.obj",
                    "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1 0\n"
                    "f 2 1 5\nf 3 2 5\nf 4 3 5\nf 1 4 5\nf 1 2 3 4\n");
    const auto build = [&](const std::string& params) {
        const SceneDesc d =
            parse(xmlScene(R"(<shape type="obj"><string name="filename" value="pyramid.obj"/>)" +
                           params + "</shape>"),
                  {}, dir / "scene.xml");
        return buildWorld(d, BuildOptions{});
    };
    const auto apexNormal = [](const World& w) {
        const TriangleMesh& mesh = w.shapes.at(1).mesh;  // after the default rectangle
        if (mesh.normals.empty()) return Vec3(0.0f);
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            if (mesh.positions[i].y > 0.5f) return mesh.normals[i];
        ADD_FAILURE() << "no apex";
        return Vec3(0.0f);
    };
    EXPECT_NEAR(apexNormal(build("")).y, 1.0f, 1e-6f);  // the sides' mean at the apex
    EXPECT_EQ(apexNormal(build(R"(<boolean name="face_normals" value="true"/>)")), Vec3(0.0f));
}

TEST(MitsubaImport, BitmapsAreReadAtThePointWithTheirWrapModeAndToUv) {
    const fs::path dir = test::scratchDir("mitsuba-bitmap");
    test::writeFile(dir / "carrot.png", "not read while parsing");
    const auto bitmap = [&](const std::string& params) {
        const SceneDesc d = parse(xmlScene(R"(<shape type="cube"><bsdf type="diffuse">
          <texture name="reflectance" type="bitmap"><string name="filename" value="carrot.png"/>)" +
                                        params + "</texture></bsdf></shape>"),
                                  {}, dir / "scene.xml");
        return std::get<DiffuseMaterial>(d.materials.at(1).material.kind).color.texture;
    };
    TextureRef t = bitmap("");
    EXPECT_EQ(t.sampling.filter, TextureFilter::Bilinear);  // Mitsuba has no MIP levels
    EXPECT_EQ(t.sampling.wrap, TextureWrap::Repeat);
    EXPECT_EQ(t.stTransform, Mat3(1.0f));
    t = bitmap(R"(<string name="filter_type" value="nearest"/><string name="wrap_mode" value="clamp"/>
      <transform name="to_uv"><scale value="2"/><translate value="-0.5, -0.5, 0"/></transform>)");
    EXPECT_EQ(t.sampling.filter, TextureFilter::Nearest);
    EXPECT_EQ(t.sampling.wrap, TextureWrap::Clamp);
    const Vec3 corner = t.stTransform * Vec3(1.0f, 1.0f, 1.0f);  // scaled first, then moved
    EXPECT_FLOAT_EQ(corner.x, 1.5f);
    EXPECT_FLOAT_EQ(corner.y, 1.5f);
    EXPECT_THAT(test::errorMessage([&] { bitmap(R"(<string name="wrap_mode" value="tile"/>)"); }),
                HasSubstr("wrap_mode must be repeat, mirror or clamp"));
}

TEST(MitsubaImport, ASpotFallsOffLinearlyInTheAngleAndProjectsItsBitmap) {
    const fs::path dir = test::scratchDir("mitsuba-spot");
    test::writeFile(dir / "slide.png", "not read while parsing");
    const SceneDesc d = parse(xmlScene(R"(<emitter type="spot">
      <rgb name="intensity" value="5"/><float name="cutoff_angle" value="20"/>
      <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, 4" up="0, 1, 0"/></transform>
      <texture name="texture" type="bitmap"><string name="filename" value="slide.png"/></texture>
    </emitter>)"), {}, dir / "scene.xml");
    const auto& spot = std::get<SpotLight>(d.lights.at(0).light.kind);
    EXPECT_EQ(spot.position, Vec3(1, 2, 3));
    EXPECT_EQ(spot.direction, Vec3(0, 0, 1));
    EXPECT_EQ(spot.intensity, Color(5.0f));
    EXPECT_EQ(spot.shape, SpotLight::Falloff::LinearAngle);
    EXPECT_NEAR(spot.cosTotalWidth, std::cos(glm::radians(20.0f)), 1e-6f);
    EXPECT_NEAR(spot.cosFalloffStart, std::cos(glm::radians(15.0f)), 1e-6f);  // 3/4 of the cutoff
    // Mitsuba's image frame: s along its local +x (up × axis), t along +y.
    ASSERT_TRUE(spot.image);
    EXPECT_NEAR(spot.image->x.x, 1.0f, 1e-6f);
    EXPECT_NEAR(spot.image->y.y, 1.0f, 1e-6f);
    EXPECT_EQ(spot.image->texture.sampling.filter, TextureFilter::Bilinear);
    EXPECT_THAT(xmlError(xmlScene(R"(<emitter type="spot"><transform name="to_world"><scale x="2"/></transform></emitter>)")),
                HasSubstr("a to_world that is not a rotation (times a uniform scale) is not supported"));
}

TEST(MitsubaImport, AProjectorKeepsItsFrameAndFovAndGivesPiTimesItsIrradiance) {
    const SceneDesc d = parse(xmlScene(R"(<emitter type="projector">
      <rgb name="irradiance" value="0.5"/><float name="scale" value="2"/><float name="fov" value="60"/>
      <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    </emitter>)"));
    const auto& p = std::get<ProjectorLight>(d.lights.at(0).light.kind);
    EXPECT_EQ(p.position, Vec3(0, 3, 0));
    EXPECT_EQ(p.axis, Vec3(0, -1, 0));
    EXPECT_NEAR(p.up.z, 1.0f, 1e-6f);
    EXPECT_NEAR(p.irradiance.r, kPi, 1e-5f);  // π × scale × irradiance, Mitsuba's
    EXPECT_FLOAT_EQ(p.fovDegrees, 60.0f);
    EXPECT_EQ(p.fovAxis, ProjectorLight::FovAxis::X);
    // Without a fov: Mitsuba's 50 mm lens, along the diagonal.
    const SceneDesc lens = parse(xmlScene(R"(<emitter type="projector">
      <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    </emitter>)"));
    const auto& q = std::get<ProjectorLight>(lens.lights.at(0).light.kind);
    EXPECT_EQ(q.fovAxis, ProjectorLight::FovAxis::Diagonal);
    EXPECT_NEAR(q.fovDegrees, 46.793f, 1e-3f);
}

TEST(MitsubaImport, AnEnvmapIsAnEnvironmentLightTurnedAQuarterWithRowsFromPoleToPole) {
    const fs::path dir = test::scratchDir("mitsuba-envmap");
    test::writeFile(dir / "sky.exr", "not read while parsing");
    const auto light = [&](const std::string& transform) {
        const SceneDesc d = parse(xmlScene(R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
          <float name="scale" value="2"/>)" + transform + "</emitter>"), {}, dir / "scene.xml");
        EXPECT_EQ(d.lights.size(), 1u);
        return std::get<EnvironmentLight>(d.lights.at(0).light.kind);
    };
    EnvironmentLight env = light("");
    EXPECT_EQ(env.rows, RowLayout::PoleToPole);
    EXPECT_EQ(env.scale, Color(2.0f));
    // Mitsuba's image centre looks along +z, strahl's along +x: the world's +z
    // is the map's +x.
    const Vec3 zInMap = env.worldToEnvironment * Vec3(0, 0, 1);
    EXPECT_NEAR(zInMap.x, 1.0f, 1e-6f);
    EXPECT_NEAR(zInMap.z, 0.0f, 1e-6f);
    // Turned 90° about +y, Mitsuba's centre looks along +x: strahl's default.
    env = light(R"(<transform name="to_world"><rotate y="1" angle="90"/></transform>)");
    const Vec3 xInMap = env.worldToEnvironment * Vec3(1, 0, 0);
    EXPECT_NEAR(xInMap.x, 1.0f, 1e-6f);
    EXPECT_THAT(
        xmlError(xmlScene(
            R"(<emitter type="envmap"><string name="filename" value=")" +
            (dir / "sky.exr").string() +
            R"("/><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>)")),
        HasSubstr("a to_world other than a rotation about +y is not supported yet"));
}

TEST(MitsubaImport, StrahlJsonScenesTakeNoDefines) {
    EXPECT_THAT(test::errorMessage([] {
                    SceneDocument::fromText(R"({"shapes": []})", "scene.json", {{"spp", "4"}});
                }),
                HasSubstr("scene.json: -D spp: strahl JSON scenes have no parameters"));
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(MitsubaImport, CurveFilesAreRoundStrandsWhoseRadiiTheTransformKeeps) {
    const fs::path dir = test::scratchDir("mitsuba-curves");
    // Two strands, a blank line between them, radii per point.
    test::writeFile(dir / "hair.txt", "0 0 0 0.1\n0 0 1 0.1\n0 1 2 0.1\n0 1 3 0.05\n\n# next\n1 0 0 0.2\n1 0 1 0.2\n");
    const SceneDesc d = parse(xmlScene(R"(<shape type="bsplinecurve" id="fur">
    <string name="filename" value="hair.txt"/>
    <transform name="to_world"><scale value="2"/></transform>
  </shape>
  <shape type="linearcurve"><string name="filename" value="hair.txt"/></shape>)"), {}, dir / "scene.xml");
    ASSERT_EQ(d.shapes.size(), 3u);
    EXPECT_EQ(d.shapes[1].kind, ShapeKind::Curves);
    EXPECT_EQ(d.shapes[1].curves.basis, CurveBasis::BSpline);
    EXPECT_EQ(d.shapes[1].curves.type, CurveType::Round);
    EXPECT_FALSE(d.shapes[1].curveRadiusFollowsTransform);
    EXPECT_EQ(d.shapes[2].curves.basis, CurveBasis::Linear);
    // The B-spline's second strand has 2 points: fewer than its basis needs.
    EXPECT_THAT(test::errorMessage([&] { buildWorld(d, BuildOptions{}); }),
                HasSubstr("strand 1 has 2 control points, but a bspline segment needs 4"));
    test::writeFile(dir / "hair.txt", "0 0 0 0.1\n0 0 1 0.1\n0 1 2 0.1\n0 1 3 0.05\n");
    const World world = buildWorld(d, BuildOptions{});
    const CurveSet* curves = world.shapes[1].user->asCurves();
    ASSERT_NE(curves, nullptr);
    EXPECT_EQ(curves->primitiveCount(), 1u);
    // Points doubled, radii as written (Mitsuba does not scale them).
    EXPECT_EQ(curves->desc().points[3], Vec4(0, 2, 6, 0.05f));
    EXPECT_EQ(world.shapes[2].user->primitiveCount(), 3u);
    EXPECT_THAT(
        xmlError(xmlScene(R"(<shape type="linearcurve"><string name="filename" value="x.txt"/>
      <boolean name="flip_normals" value="true"/></shape>)")),
        HasSubstr("flip_normals"));
}

}  // namespace
}  // namespace strahl
