// Image regression: every scene in scenes/regression/ is rendered and compared
// with its stored reference in tests/golden/ (float EXR). The renders are
// deterministic, so the tolerance only absorbs differences of floating-point
// code generation between machines/compilers, not noise.
// STRAHL_UPDATE_REFERENCES=1 rewrites the references instead (look at them!).

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "strahl/film/image_output.h"
#include "render_helpers.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

// Per-pixel tolerance on scene-linear values: 2e-3 absolute (far below what a
// visible change produces), and at most 0.1% of the pixels above 1e-4.
constexpr float kFailThreshold = 2e-3f;
constexpr float kWarnThreshold = 1e-4f;
constexpr double kMaxWarnFraction = 0.001;

class Regression : public ::testing::TestWithParam<std::string> {};

TEST_P(Regression, MatchesReference) {
    const fs::path scene = test::sourceDir() / "scenes/regression" / (GetParam() + ".json");
    const fs::path reference = test::sourceDir() / "tests/golden" / (GetParam() + ".exr");
    const SceneDesc desc = parseSceneFile(scene);
    const Film film = test::renderFilm(desc);

    const fs::path rendered = test::scratchDir("regression-" + GetParam()) / "render.exr";
    OutputSettings settings;
    settings.exrFloat = true;
    writeImage(film, rendered, settings, ImageMetadata{});

    if (std::getenv("STRAHL_UPDATE_REFERENCES")) {
        fs::create_directories(reference.parent_path());
        fs::copy_file(rendered, reference, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "reference rewritten: " << reference;
    }
    ASSERT_TRUE(fs::exists(reference))
        << reference << " is missing; create it with STRAHL_UPDATE_REFERENCES=1 (see "
        << "scenes/regression/README.md)";

    OIIO::ImageBuf expected(reference.string()), actual(rendered.string());
    const auto result =
        OIIO::ImageBufAlgo::compare(actual, expected, kFailThreshold, kWarnThreshold);
    ASSERT_FALSE(result.error) << "cannot compare with " << reference;
    const double pixels = double(desc.film.width) * desc.film.height;
    EXPECT_EQ(result.nfail, 0u) << "max error " << result.maxerror << " at pixel ("
                                << result.maxx << ", " << result.maxy << ")";
    EXPECT_LE(double(result.nwarn) / pixels, kMaxWarnFraction) << result.nwarn << " pixels differ";
}

// Every scene in the folder: a new scene without a reference fails until its
// reference is made.
INSTANTIATE_TEST_SUITE_P(Scenes, Regression, ::testing::ValuesIn(test::regressionScenes()),
                         test::sceneTestName);

TEST(RegressionSet, CoversTheScenesItWasMadeFor) {
    const std::vector<std::string> scenes = test::regressionScenes();
    for (const char* name : {"quad_and_box", "cornell_direct", "cornell_ortho_normal",
                             "cornell_primid", "implicit_direct", "instances", "curves"}) {
        EXPECT_NE(std::find(scenes.begin(), scenes.end(), name), scenes.end()) << name;
    }
}

}  // namespace
}  // namespace strahl
