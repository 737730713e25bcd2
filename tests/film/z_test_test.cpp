// Mitsuba's render-test criterion (film/z_test.h) on images whose answer is
// known: the z value and p-value of one pixel, the Šidák level, the 99.75 %
// rule, and the error image.

#include "strahl/film/z_test.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

#include "strahl/core/error.h"
#include "test_support.h"

namespace strahl {
namespace {

RgbImage filled(int w, int h, float value) {
    RgbImage image;
    image.width = w;
    image.height = h;
    image.rgb.assign(size_t(3 * w * h), value);
    return image;
}

TEST(ZTest, AnImageEqualToTheReferencePasses) {
    const RgbImage ref = filled(8, 4, 0.5f);
    const ZTestResult r = zTest(ref, 100, ref, filled(8, 4, 0.01f));
    EXPECT_TRUE(r.passed);
    EXPECT_EQ(r.values, 96u);
    EXPECT_EQ(r.passing, 96u);
    EXPECT_DOUBLE_EQ(r.alpha, 1.0 - std::pow(0.99, 1.0 / 32.0));
}

TEST(ZTest, TheStatisticIsTheScaledDifferenceInXyz) {
    RgbImage mean = filled(2, 1, 0.5f), ref = filled(2, 1, 0.5f);
    const RgbImage var = filled(2, 1, 0.04f);
    // A grey offset d in RGB is an offset of d times the row sums in XYZ:
    // Y's row sums to 1.0 (0.212671 + 0.715160 + 0.072169).
    for (int c = 0; c < 3; ++c) mean.rgb[size_t(c)] = 0.6f;
    const ZTestResult r = zTest(mean, 25, ref, var);
    const double dy = (0.6 - 0.5) * 1.0, vary = 0.04 * 1.0;
    EXPECT_NEAR(r.z[1], dy * std::sqrt(25 / vary), 1e-4);
    ASSERT_FALSE(r.worst.empty());
    EXPECT_EQ(r.worst[0].x, 0);
    EXPECT_NEAR(r.worst[0].p, std::erfc(r.worst[0].z / std::sqrt(2.0)), 1e-12);
    EXPECT_EQ(r.z[4], 0.0f);  // the second pixel agrees
}

TEST(ZTest, ThreeInAThousandValuesMayFailButNotMore) {
    // 100 x 10 pixels, 3000 values, of which 99.75 % is 2992.5: 7 failing
    // values pass the image, 8 do not. Adding 0.002 to B moves Z by 0.0019,
    // z = 6.0 at 1000 spp and variance 1e-4 (past alpha's z of 4.4), but X and
    // Y by much less (z 1.1 and 0.5): one failing value per pixel.
    const RgbImage ref = filled(100, 10, 0.5f), var = filled(100, 10, 1e-4f);
    for (size_t failing : {7u, 8u}) {
        RgbImage mean = ref;
        for (size_t i = 0; i < failing; ++i) mean.rgb[3 * i + 2] += 0.002f;
        const ZTestResult r = zTest(mean, 1000, ref, var);
        EXPECT_EQ(r.values - r.passing, failing);
        EXPECT_EQ(r.passed, failing == 7) << r.summary();
        EXPECT_EQ(r.worst[0].channel, 2);
    }
}

TEST(ZTest, NonFiniteValuesFailAndBadInputIsAnError) {
    const RgbImage ref = filled(2, 2, 0.5f), var = filled(2, 2, 0.01f);
    RgbImage mean = ref;
    mean.rgb[0] = std::nanf("");
    EXPECT_LT(zTest(mean, 10, ref, var).passing, 12u);
    EXPECT_THROW(zTest(filled(3, 2, 0.5f), 10, ref, var), Error);
    EXPECT_THROW(zTest(ref, 0, ref, var), Error);
}

TEST(ZTest, TheErrorImageMarksTheFailingPixels) {
    const auto dir = test::scratchDir("ztest-image");
    const RgbImage ref = filled(4, 2, 0.5f), var = filled(4, 2, 1e-4f);
    RgbImage mean = ref;
    mean.rgb[3 * 5 + 1] = 2.0f;  // pixel (1, 1)
    const ZTestResult r = zTest(mean, 100, ref, var);
    writeZTestImage(dir / "errors.exr", mean, ref, r);
    auto in = OIIO::ImageInput::open((dir / "errors.exr").string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> pixels(size_t(spec.width * spec.height * spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    const auto channel = [&](const std::string& name) { return spec.channelindex(name); };
    ASSERT_GE(channel("fails"), 0);
    ASSERT_GE(channel("mean.G"), 0);
    for (int pixel = 0; pixel < 8; ++pixel) {
        const float* p = &pixels[size_t(pixel * spec.nchannels)];
        EXPECT_EQ(p[channel("fails")], pixel == 5 ? 1.0f : 0.0f) << pixel;
        EXPECT_EQ(p[channel("mean.G")], pixel == 5 ? 2.0f : 0.5f) << pixel;
    }
    EXPECT_THROW(readRgbImage(dir / "missing.exr"), Error);
}

}  // namespace
}  // namespace strahl
