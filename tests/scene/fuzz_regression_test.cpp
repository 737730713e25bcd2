// Replays, through the fuzz targets' own harness (fuzz/fuzz_harness.h), every
// input a fuzz target failed on (tests/data/fuzz/<target>/, one file per bug
// fixed) and the seed corpora (fuzz/corpus/<target>/). Each input must load or
// be rejected with a strahl::Error: never crash, hang or throw anything else.
// Under the sanitizer build this also checks them for leaks and undefined
// behaviour. docs/reliability.md, "Fuzzing".

#include <gtest/gtest.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "../../fuzz/fuzz_harness.h"
#include "strahl/core/error.h"
#include "strahl/scene/scene_builder.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

struct FuzzTarget {
    const char* name;  // as in fuzz/: the folder names of its inputs
    void (*run)(std::string_view input);
};

const FuzzTarget kTargets[] = {
    {"fuzz_scene_json", &fuzz::runSceneJson},
    {"fuzz_mitsuba_xml", &fuzz::runMitsubaXml},
    {"fuzz_pbrt", &fuzz::runPbrt},
    {"fuzz_ply", &fuzz::runPly},
    {"fuzz_serialized", &fuzz::runSerialized},
    {"fuzz_obj", &fuzz::runObj},
    {"fuzz_gltf", &fuzz::runGltf},
    {"fuzz_formula", &fuzz::runFormula},
};

const FuzzTarget& targetNamed(std::string_view name) {
    for (const FuzzTarget& t : kTargets) {
        if (t.name == name) return t;
    }
    throw std::invalid_argument(std::string(name));
}

// The files of `dir`, sorted (none if it does not exist).
std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->is_regular_file()) files.push_back(it->path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Runs one input; returns the strahl::Error message, or "" if it loaded.
std::string replay(const FuzzTarget& target, const fs::path& file) {
    const std::string input = test::readFile(file);
    try {
        target.run(input);
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << file << ": threw something other than strahl::Error: " << e.what();
    }
    return {};
}

class FuzzRegression : public testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzRegression, FoundInputsLoadOrFailWithAnError) {
    const FuzzTarget& target = GetParam();
    for (const fs::path& file : filesIn(test::sourceDir() / "tests/data/fuzz" / target.name)) {
        SCOPED_TRACE(file.string());
        replay(target, file);
    }
}

TEST_P(FuzzRegression, SeedCorpusLoadsOrFailsWithAnError) {
    const FuzzTarget& target = GetParam();
    const std::vector<fs::path> seeds = filesIn(test::sourceDir() / "fuzz/corpus" / target.name);
    EXPECT_FALSE(seeds.empty()) << "no seed corpus for " << target.name;
    for (const fs::path& file : seeds) {
        SCOPED_TRACE(file.string());
        replay(target, file);
    }
}

// The bugs behind tests/data/fuzz/, each with the error its input now gives.

// readWholeFile reads regular files only: /dev/zero named as a material library
// or a Bezier patch file was read until memory ran out.
TEST(FuzzRegressionInputs, DevicesAreNotRegularFiles) {
    const fs::path dir = test::sourceDir() / "tests/data/fuzz";
    const std::string expected = "/dev/zero: cannot open: not a regular file";
    EXPECT_TRUE(test::contains(
        replay(targetNamed("fuzz_obj"), dir / "fuzz_obj/mtllib_dev_zero.obj"), expected));
    // The scene parser only names the patch file: building the scene reads it.
    const fs::path scene = dir / "fuzz_scene_json/bezier_file_dev_zero.json";
    EXPECT_EQ(replay(targetNamed("fuzz_scene_json"), scene), "");
    BuildOptions naive;
    naive.accel = AccelKind::Naive;
    EXPECT_TRUE(test::contains(
        test::errorMessage([&] { buildWorld(parseSceneText(test::readFile(scene), scene), naive); }),
        expected));
}

// A serialized mesh with no triangles copied its (empty) index array with a
// null destination pointer, undefined behaviour even for 0 bytes.
TEST(FuzzRegressionInputs, ASerializedMeshWithoutTrianglesIsNoUndefinedBehaviour) {
    const fs::path input = test::sourceDir() / "tests/data/fuzz/fuzz_serialized/no_triangles.serialized";
    ASSERT_TRUE(fs::exists(input));
    replay(targetNamed("fuzz_serialized"), input);  // UBSan checks the copy in the sanitizer build
}

// A mesh offset near 2^64 in the dictionary passed the bounds check once 4
// was added to it (unsigned wrap-around) and was read far outside the file.
TEST(FuzzRegressionInputs, ASerializedOffsetPastTheFileIsAnError) {
    const fs::path input = test::sourceDir() / "tests/data/fuzz/fuzz_serialized/offset_wraps_around.serialized";
    EXPECT_TRUE(test::contains(replay(targetNamed("fuzz_serialized"), input), "is outside the file"));
}

// A pbrt index far beyond any integer type was converted to one to be named
// in its error message (undefined behaviour); it is named as read.
TEST(FuzzRegressionInputs, APbrtIndexBeyondEveryIntegerTypeIsAnError) {
    const fs::path input = test::sourceDir() / "tests/data/fuzz/fuzz_pbrt/index_beyond_long_long.pbrt";
    EXPECT_TRUE(test::contains(replay(targetNamed("fuzz_pbrt"), input),
                               "\"integer indices\": index 3.33333e+29 is out of range (3 points)"));
}

// An included file name longer than the file system allows made the include-
// cycle check (std::filesystem::weakly_canonical) throw std::filesystem_error,
// which ended the process; it is now the include's own clear error.
TEST(FuzzRegressionInputs, AnIncludedNameTooLongForTheFileSystemIsAnError) {
    const fs::path dir = test::sourceDir() / "tests/data/fuzz";
    const std::string pbrt = replay(targetNamed("fuzz_pbrt"), dir / "fuzz_pbrt/include_name_too_long.pbrt");
    EXPECT_TRUE(test::contains(pbrt, "scene.pbrt:1: Include \"aaaa")) << pbrt;
    EXPECT_TRUE(test::contains(pbrt, "(File name too long)")) << pbrt;
    const std::string xml =
        replay(targetNamed("fuzz_mitsuba_xml"), dir / "fuzz_mitsuba_xml/include_name_too_long.xml");
    EXPECT_TRUE(test::contains(xml, "scene.xml:2")) << xml;
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegression, testing::ValuesIn(kTargets),
                         [](const testing::TestParamInfo<FuzzTarget>& target) {
                             return std::string(target.param.name);
                         });

}  // namespace
}  // namespace strahl
