// Mitsuba 3's own render tests (../shared/data/mitsuba-tests, SOURCE.txt), as
// Mitsuba runs them: each scene rendered by `strahl render scene.xml` with
// spp = 2,000,000 / pixel count and seed 0, and judged against Mitsuba's
// reference mean and per-sample variance by Mitsuba's z-test (film/z_test.h).
// A scene strahl cannot render yet must fail with one clear error naming the
// file, the line and the element, and write nothing: each case below says
// which it is, and docs/mitsuba.md has the table.
//
// Under the sanitizers (scripts/sanitize.sh) each scene renders 1/16 of the
// samples and the test checks the render (exit 0, the reference's size, finite
// pixels) but not the z-test: at a few samples per pixel a pixel mean is far
// from normal, and the z-test is the Release suite's job; what the sanitizer run
// adds is every importer and render path of these scenes under ASan and UBSan.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/cli_runner.h"
#include "app/exr_file.h"
#include "strahl/film/z_test.h"
#include "sanitizers/sanitized.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

struct MitsubaCase {
    const char* group;
    const char* name;      // the scene's file stem, test_<name>
    // "" : renders and passes. Else: a part of its one error.
    const char* expected;
};

// Why each unsupported scene fails is in docs/mitsuba.md ("Mitsuba's render tests").
const MitsubaCase kCases[] = {
    {"floating_sphere", "directional_direct", ""},
    {"instancing", "instancing_path", ""},
    {"bsdf_spheres", "arealight_path", ""},
    {"bsdf_spheres", "bumpmap_path", ""},
    {"bsdf_spheres", "constant_path", ""},
    {"bsdf_spheres", "envmap_path", ""},
    {"bsdf_spheres", "normalmap_identity_roughconductor_path", ""},
    {"bsdf_spheres", "normalmap_path", ""},
    {"bsdf_spheres", "pointlight_path", ""},
    {"bsdf_spheres", "roughdielectric_path", ""},
    {"bsdf_spheres", "roughplastic_linear_path", ""},
    {"bsdf_spheres", "textured_diffuse_path", ""},
    {"bsdf_spheres", "texturedprincipled1_path", ""},
    {"bsdf_spheres", "texturedprincipled2_path", ""},
    {"bsdf_spheres", "texturedprincipledthin_path", ""},
    {"mesh_attributes", "mesh_attributes_1_face_direct", ""},
    {"mesh_attributes", "mesh_attributes_3_face_direct", ""},
    {"orthographic_sensor", "orthographic_path", ""},
    {"participating_media", "hetero_sigmat_albedo_volpath", "<medium type=\"heterogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "hetero_sigmat_volpath", "<medium type=\"heterogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_area_light_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_dielectric_envmap_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_emitter_inside_medium_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_null_envmap_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_obj_inside_medium_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "homo_roughdielectric_spot_volpath", "<medium type=\"homogeneous\" id=\"medium1\">: participating media are not supported"},
    {"participating_media", "surf_area_light_volpath", ""},
    {"projector", "projector_constant_direct", ""},
    {"projector", "projector_textured_direct", ""},
    {"spot_light", "spot_direct", ""},
    {"texture_interp", "texture_interp_direct", ""},
    {"various_emitters", "various_emitters_ptracer", ""},
};

fs::path scenes() { return test::sharedData() / "mitsuba-tests/tests/scenes"; }

class MitsubaRenderTest : public testing::TestWithParam<MitsubaCase> {};

TEST_P(MitsubaRenderTest, PassesMitsubasTestOrFailsWithOneClearError) {
    STRAHL_REQUIRE_SHARED_DATA();
    const MitsubaCase& c = GetParam();
    const fs::path folder = scenes() / c.group;
    const std::string stem = std::string("test_") + c.name;
    const fs::path scene = folder / (stem + ".xml");
    ASSERT_TRUE(fs::exists(scene)) << scene;
    const std::string refName = stem.substr(0, stem.rfind('_'));  // without the integrator
    const RgbImage reference = readRgbImage(folder / "refs" / (refName + "_ref_rgb.exr"));
    const RgbImage variance = readRgbImage(folder / "refs" / (refName + "_ref_rgb_var.exr"));
    const int fullSpp = 2000000 / (reference.width * reference.height);
    const int spp = test::fullOrSanitized(fullSpp, std::max(1, fullSpp / 16));

    const fs::path dir = test::scratchDir("mitsuba-" + std::string(c.name));
    const fs::path out = dir / "render.exr";
    const test::RunResult r = test::runStrahl("render " + scene.string() + " --spp " +
                                              std::to_string(spp) + " --seed 0 --exr-float -q -o " +
                                              out.string());
    if (*c.expected) {
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_TRUE(test::contains(r.err, c.expected)) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(out));
        return;
    }
    ASSERT_EQ(r.status, 0) << r.err;
    const RgbImage mean = readRgbImage(out);
    if constexpr (test::kSanitized) {
        ASSERT_EQ(mean.width, reference.width);
        ASSERT_EQ(mean.height, reference.height);
        EXPECT_TRUE(std::all_of(mean.rgb.begin(), mean.rgb.end(), [](float v) { return std::isfinite(v); }));
        return;
    }
    const ZTestResult z = zTest(mean, spp, reference, variance);
    std::printf("%s/%s: %s\n", c.group, c.name, z.summary().c_str());
    if (!z.passed) {
        const fs::path errors = dir / "errors.exr";
        writeZTestImage(errors, mean, reference, z);
        ADD_FAILURE() << c.name << ": " << z.summary() << "; error image " << errors;
    }
}

// The test has the power to tell: a render 3 % too bright (the directional
// light's irradiance set to 1.03) fails it.
TEST(MitsubaRenderCheck, ARenderThreePercentTooBrightFails) {
    STRAHL_REQUIRE_SHARED_DATA();
    const fs::path folder = scenes() / "floating_sphere";
    const RgbImage reference = readRgbImage(folder / "refs/test_directional_ref_rgb.exr");
    const RgbImage variance = readRgbImage(folder / "refs/test_directional_ref_rgb_var.exr");
    const int spp = 2000000 / (reference.width * reference.height);
    const fs::path out = test::scratchDir("mitsuba-brighter") / "render.exr";
    const test::RunResult r = test::runStrahl(
        "render " + (folder / "test_directional_direct.xml").string() + " --spp " +
        std::to_string(spp) + " --set /lights/0/irradiance=1.03 --exr-float -q -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    const ZTestResult z = zTest(readRgbImage(out), spp, reference, variance);
    EXPECT_FALSE(z.passed) << z.summary();
}

// `strahl convert` writes the strahl scene the importer makes: rendering it
// (from another folder: its file names are rebased) gives the image of the
// .xml bit for bit, -D included.
TEST(MitsubaConvert, TheConvertedSceneRendersTheSameImageBitForBit) {
    const fs::path dir = test::scratchDir("mitsuba-convert");
    test::writeFile(dir / "meshes/tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    test::writeFile(dir / "scene.xml", R"(<scene version="3.0.0">
  <default name="spp" value="2"/>
  <integrator type="path"><integer name="max_depth" value="3"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 1, 6" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/>
      <rfilter type="box"/></film>
    <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
  </sensor>
  <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.6"/></bsdf>
  <shape type="obj"><string name="filename" value="meshes/tri.obj"/><ref id="grey"/></shape>
  <shape type="sphere"><point name="center" x="0.5" y="0" z="1"/><float name="radius" value="0.3"/></shape>
  <shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="90"/><translate y="2"/></transform>
    <emitter type="area"><rgb name="radiance" value="4"/></emitter>
  </shape>
  <emitter type="point"><point name="position" x="2" y="2" z="2"/><rgb name="intensity" value="3"/></emitter>
</scene>)");
    const std::string xml = (dir / "scene.xml").string();
    const fs::path convertedScene = dir / "converted/scene.json";
    test::RunResult r = test::runStrahl("convert " + xml + " -o " + convertedScene.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(test::contains(r.err, "converted' does not exist")) << r.err;
    fs::create_directories(dir / "converted");
    r = test::runStrahl("convert " + xml + " -D spp=5 -o " + convertedScene.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(test::contains(test::readFile(convertedScene), "\"../meshes/tri.obj\"")) << test::readFile(convertedScene);
    r = test::runStrahl("render " + xml + " -D spp=5 --exr-float -q -o " + (dir / "xml.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    r = test::runStrahl("render " + convertedScene.string() + " --exr-float -q -o " + (dir / "json.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    const test::ExrFile fromXml = test::readExr(dir / "xml.exr");
    EXPECT_EQ(fromXml.samples, "5");
    test::expectIdentical(fromXml, test::readExr(dir / "json.exr"), "xml and converted json");

    // -D on a JSON scene, and a convert that fails, leave nothing behind.
    r = test::runStrahl("render " + convertedScene.string() + " -D spp=3 -o " +
                        (dir / "no.exr").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(test::contains(r.err, "-D spp: strahl JSON scenes have no parameters")) << r.err;
    r = test::runStrahl("convert " + xml + " -D nothing=1 -o " + (dir / "no.json").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_FALSE(fs::exists(dir / "no.json"));
    EXPECT_FALSE(fs::exists(dir / "no.exr"));
}

INSTANTIATE_TEST_SUITE_P(MitsubaTests, MitsubaRenderTest, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<MitsubaCase>& test) {
                             return std::string(test.param.name);
                         });

}  // namespace
}  // namespace strahl
