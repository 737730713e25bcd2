// The .bpt Bézier patch reader: the shipped Utah teapot (32 patches, its
// extent, shared patch borders, orientation), and the "file:line: what" errors
// of malformed input, including a patch count that lies.

#include "strahl/meshio/bezier_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "strahl/core/error.h"
#include "test_support.h"

namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace strahl {
namespace {

const fs::path kTeapot = test::sourceDir() / "scenes/data/teapot.bpt";

// One patch: a planar net, each point on its own line.
std::string patchText(const std::string& degrees = "3 3") {
    std::string text = degrees + "\n";
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) text += std::to_string(i) + " " + std::to_string(j) + " 0.5\n";
    return text;
}

fs::path writeBpt(const std::string& test, const std::string& text) {
    const fs::path file = test::scratchDir(test) / "patches.bpt";
    test::writeFile(file, text);
    return file;
}

std::string loadError(const std::string& test, const std::string& text) {
    const fs::path file = writeBpt(test, text);
    return test::errorMessage([&] { loadBezierFile(file); });
}

// The four edges of a patch as control point rows, each as listed in the net.
std::array<std::array<DVec3, 4>, 4> edges(const BezierPatch& p) {
    std::array<std::array<DVec3, 4>, 4> e;
    for (size_t k = 0; k < 4; ++k) {
        e[0][k] = p.points[k];          // u = 0
        e[1][k] = p.points[12 + k];     // u = 1
        e[2][k] = p.points[4 * k];      // v = 0
        e[3][k] = p.points[4 * k + 3];  // v = 1
    }
    return e;
}

bool degenerate(const std::array<DVec3, 4>& e) {
    return std::all_of(e.begin(), e.end(), [&](const DVec3& p) { return p == e[0]; });
}

TEST(BezierFile, TeapotLoads) {
    const std::vector<BezierPatch> patches = loadBezierFile(kTeapot);
    ASSERT_EQ(patches.size(), 32u);

    const ParametricSurfacePtr teapot = makeBezierPatchSet(patches, "teapot.bpt");
    EXPECT_NO_THROW(validateParametricSurface(*teapot));
    DVec3 lo(num::kInf), hi(-num::kInf);
    for (uint32_t patch = 0; patch < 32; ++patch)
        for (int i = 0; i <= 32; ++i)
            for (int j = 0; j <= 32; ++j) {
                const DVec3 p = teapot->point(patch, i / 32.0, j / 32.0);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
    EXPECT_NEAR(lo.x, -3.0, 1e-3);
    EXPECT_NEAR(hi.x, 3.434, 2e-3);  // the spout's tip
    EXPECT_NEAR(lo.y, -2.0, 1e-3);
    EXPECT_NEAR(hi.y, 2.0, 1e-3);
    EXPECT_NEAR(lo.z, 0.0, 1e-3);
    EXPECT_NEAR(hi.z, 3.15, 1e-3);  // the lid's knob
}

TEST(BezierFile, TeapotPatchesShareTheirBorders) {
    const std::vector<BezierPatch> patches = loadBezierFile(kTeapot);
    // Every non-degenerate edge is another patch's edge (same control points,
    // either direction), except the open ones: the rim's top (4), the lid's
    // rim (4), and both ends of the handle (4) and of the spout (4).
    int open = 0, shared = 0;
    for (size_t a = 0; a < patches.size(); ++a)
        for (const auto& edge : edges(patches[a])) {
            if (degenerate(edge)) continue;  // the poles of the lid and the bottom
            std::array<DVec3, 4> reversed = edge;
            std::reverse(reversed.begin(), reversed.end());
            bool found = false;
            for (size_t b = 0; b < patches.size() && !found; ++b)
                for (const auto& other : edges(patches[b]))
                    if (b != a && (other == edge || other == reversed)) found = true;
            (found ? shared : open)++;
        }
    EXPECT_EQ(open, 16);
    EXPECT_EQ(shared, 32 * 4 - 16 - 8);  // 8 degenerate edges: 4 at the lid's knob, 4 at the bottom
}

TEST(BezierFile, TeapotNormalsPointIntoThePot) {
    const ParametricSurfacePtr teapot = makeBezierPatchSet(loadBezierFile(kTeapot), "teapot");
    // Body (patches 4-11): towards the z axis; bottom (28-31): up.
    for (uint32_t patch = 4; patch < 12; ++patch) {
        const DVec3 p = teapot->point(patch, 0.5, 0.5), n = teapot->normal(patch, 0.5, 0.5);
        EXPECT_LT(glm::dot(n, DVec3(p.x, p.y, 0.0)), 0.0) << "patch " << patch;
    }
    for (uint32_t patch = 28; patch < 32; ++patch)
        EXPECT_GT(teapot->normal(patch, 0.5, 0.5).z, 0.0);
}

TEST(BezierFile, ReadsBlankLinesCommentsAndCrlf) {
    std::string text = "# two patches\n2\n\n" + patchText() + "  # between\n" + patchText();
    std::string crlf;
    for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    for (const std::string& t : {text, crlf}) {
        const std::vector<BezierPatch> patches = loadBezierFile(writeBpt("bpt-blank", t));
        ASSERT_EQ(patches.size(), 2u);
        EXPECT_EQ(patches[1].points[0], DVec3(0, 0, 0.5));
        EXPECT_EQ(patches[1].points[7], DVec3(1, 3, 0.5));  // i = 1, j = 3
        EXPECT_EQ(patches[1].points[15], DVec3(3, 3, 0.5));
    }
}

TEST(BezierFile, MissingFileIsAnError) {
    const fs::path file = test::scratchDir("bpt-missing") / "none.bpt";
    const std::string m = test::errorMessage([&] { loadBezierFile(file); });
    EXPECT_THAT(m, HasSubstr(file.string() + ": cannot open"));
}

TEST(BezierFile, MalformedInputNamesFileAndLine) {
    struct Case {
        const char* name;
        std::string text;
        std::string expected;  // after "<file>:"
    };
    std::string fifteenPoints = patchText();
    fifteenPoints.resize(fifteenPoints.rfind("3 3 0.5\n"));
    std::string nanPoint = patchText();
    nanPoint.replace(nanPoint.find("1 2 0.5"), 7, "1 nan 0.5");
    std::string wordPoint = patchText();
    wordPoint.replace(wordPoint.find("0 1 0.5"), 7, "0 1 zz");
    std::string hugePoint = patchText();
    hugePoint.replace(hugePoint.find("2 2 0.5"), 7, "1e999 2 0.5");
    std::string extraToken = patchText();
    extraToken.replace(extraToken.find("2 0 0.5"), 7, "2 0 0.5 7");
    std::string twoValues = patchText();
    twoValues.replace(twoValues.find("3 1 0.5"), 7, "3 1");
    const Case cases[] = {
        {"empty", "", " empty file"},
        {"blank", "\n\n  \n", " empty file"},
        {"count-word", "teapot\n" + patchText(), "1: cannot parse the patch count 'teapot'"},
        {"count-negative", "-1\n" + patchText(), "1: cannot parse the patch count '-1'"},
        {"count-fraction", "1.5\n" + patchText(), "1: cannot parse the patch count '1.5'"},
        {"count-extra", "1 2\n" + patchText(), "1: unexpected '2' after the patch count"},
        {"count-zero", "0\n", "1: the file declares 0 patches"},
        {"degree", "1\n3 2\n" + patchText().substr(4), "2: patch 0 has degrees 3 2; only bicubic"},
        {"degree-missing", "1\n" + patchText().substr(4) + "0 0 0\n",
         "2: expected the degree line \"3 3\" of patch 0, got '0 0 0.5'"},
        {"degree-one", "1\n3\n" + patchText().substr(4),
         "2: expected the degree line \"3 3\" of patch 0, got '3'"},
        {"truncated-points", "1\n" + fifteenPoints + "\n\n",
         "20: unexpected end of file: patch 0 has 15 of its 16"},
        {"truncated-patch",
         "2\n" + patchText() + patchText().substr(0, 4) + "0 0 0\n" + std::string(100, ' '),
         "21: unexpected end of file: patch 1 has 1 of its 16"},
        {"nan", "1\n" + nanPoint, "9: the y coordinate 'nan' is not finite"},
        {"word", "1\n" + wordPoint, "4: cannot parse z coordinate 'zz' as a number"},
        {"huge", "1\n" + hugePoint, "13: x coordinate '1e999' is out of range"},
        {"extra-token", "1\n" + extraToken, "11: unexpected '7' after control point 8 of patch 0"},
        {"two-values", "1\n" + twoValues, "16: missing z coordinate"},
        {"surplus", "1\n" + patchText() + patchText(),
         "19: unexpected '3' after the last patch: the first line declares 1 patch"},
    };
    for (const Case& c : cases) {
        const fs::path file = writeBpt(std::string("bpt-") + c.name, c.text);
        const std::string m = test::errorMessage([&] { loadBezierFile(file); });
        EXPECT_THAT(m, HasSubstr(file.string() + ":" + c.expected)) << c.name;
    }
}

TEST(BezierFile, LyingCountFailsBeforeAllocating) {
    // 10^12 patches would be 384 TB: the count is checked against the file size
    // first, so this is a strahl::Error, not std::bad_alloc.
    const fs::path file = writeBpt("bpt-lying", "1000000000000\n" + patchText());
    try {
        loadBezierFile(file);
        ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr(file.string() + ":1: the patch count 1000000000000 is more "
                                                        "than the file can hold (1 at most"));
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not a strahl::Error: " << e.what();
    }
    // Beyond 64 bits it does not even parse.
    const std::string m = loadError("bpt-lying-huge", "99999999999999999999999\n" + patchText());
    EXPECT_THAT(m, HasSubstr(":1: cannot parse the patch count"));
    // A count one too high that the file size cannot rule out ends at the end.
    const std::string one =
        loadError("bpt-lying-one", "2\n" + patchText() + std::string(200, '\n'));
    EXPECT_THAT(
        one, HasSubstr("unexpected end of file: expected the degree line \"3 3\" of patch 1 of 2"));
}

}  // namespace
}  // namespace strahl
