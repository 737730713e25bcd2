// TextureSystem: images written with OpenImageIO into a scratch folder and
// looked up through the texture system: exact texels, bilinear filtering,
// periodic wrap, MIP top = mean, sRGB decoding of 8/16-bit colour images,
// linear EXR, alpha, registration errors and deduplication, triplanar
// blending, and parallel lookups.

#include "strahl/texture/texture_system.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include "strahl/core/error.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace strahl {
namespace {

template <typename T>
void writeImage(const fs::path& file, int width, int height, int channels, OIIO::TypeDesc type,
                const std::vector<T>& pixels) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, channels, type);
    // Pixels as given: no division by alpha on the way into a PNG.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    ASSERT_TRUE(out->open(file.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(type, pixels.data())) << out->geterror();
    ASSERT_TRUE(out->close()) << out->geterror();
}

// The reference sRGB EOTF, in double precision.
double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// 4 x 4 RGB checker, one texel per cell: A where x + y is even, B elsewhere.
// Each channel of A + B is even, so the mean is a whole code value.
constexpr uint8_t kA[3] = {200, 50, 10};
constexpr uint8_t kB[3] = {20, 100, 240};

fs::path writeChecker(const fs::path& dir) {
    std::vector<uint8_t> pixels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) pixels.push_back((x + y) % 2 == 0 ? kA[c] : kB[c]);
    const fs::path file = dir / "checker.png";
    writeImage(file, 4, 4, 3, OIIO::TypeDesc::UINT8, pixels);
    return file;
}

Vec3 checkerTexel(int x, int y) {
    const uint8_t* code = (x + y) % 2 == 0 ? kA : kB;
    return Vec3(code[0], code[1], code[2]) / 255.0f;
}

// 4 x 4 float RGB, every texel different, values beyond 1.
Vec3 exrTexel(int x, int y) { return Vec3(0.25f + float(x), 1.5f * float(y + 1), 7.0f); }

fs::path writeExr(const fs::path& dir) {
    std::vector<float> pixels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) pixels.push_back(exrTexel(x, y)[c]);
    const fs::path file = dir / "gradient.exr";
    writeImage(file, 4, 4, 3, OIIO::TypeDesc::FLOAT, pixels);
    return file;
}

// A uniform 4 x 4 single-channel image of `code`.
template <typename T>
fs::path writeGrey(const fs::path& file, T code, OIIO::TypeDesc type) {
    writeImage(file, 4, 4, 1, type, std::vector<T>(16, code));
    return file;
}

// The st of the centre of texel (x, y) of a 4 x 4 image; t runs down.
Vec2 centre(int x, int y) { return Vec2((float(x) + 0.5f) / 4.0f, (float(y) + 0.5f) / 4.0f); }

void expectNear(const Vec4& actual, const Vec4& expected, float tolerance) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c;
}

TEST(TextureSystem, TexelCentreAtFootprintZeroIsTheTexel) {
    const fs::path dir = test::scratchDir("texture-centre");
    TextureSystem textures;
    const TextureHandle data = textures.add(writeChecker(dir), TextureEncoding::Data);
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Color);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            SCOPED_TRACE(testing::Message() << "texel " << x << ", " << y);
            expectNear(textures.lookup(data, centre(x, y), 0.0f), Vec4(checkerTexel(x, y), 1.0f),
                       1e-6f);
            EXPECT_EQ(textures.lookup(exr, centre(x, y), 0.0f), Vec4(exrTexel(x, y), 1.0f));
        }
}

TEST(TextureSystem, BetweenTexelCentresIsBilinearAndWrapsAtTheEdge) {
    const fs::path dir = test::scratchDir("texture-bilinear");
    TextureSystem textures;
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Data);
    // Halfway between texels (1, 2) and (2, 2).
    const Vec4 mid = textures.lookup(exr, Vec2(0.5f, centre(0, 2).y), 0.0f);
    expectNear(mid, Vec4(0.5f * (exrTexel(1, 2) + exrTexel(2, 2)), 1.0f), 1e-5f);
    // At s = 0, halfway between the last column and the first.
    const Vec4 seam = textures.lookup(exr, Vec2(0.0f, centre(0, 1).y), 0.0f);
    expectNear(seam, Vec4(0.5f * (exrTexel(3, 1) + exrTexel(0, 1)), 1.0f), 1e-5f);
}

TEST(TextureSystem, WrapsPeriodically) {
    const fs::path dir = test::scratchDir("texture-wrap");
    TextureSystem textures;
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Data);
    const Vec2 st(0.3f, 0.6f);
    for (const float footprint : {0.0f, 0.1f}) {
        const Vec4 base = textures.lookup(exr, st, footprint);
        for (const Vec2 shift : {Vec2(1, 0), Vec2(0, 1), Vec2(1, 1), Vec2(-1, 0), Vec2(3, -2)}) {
            SCOPED_TRACE(testing::Message() << "shift " << shift.x << ", " << shift.y);
            expectNear(textures.lookup(exr, st + shift, footprint), base, 1e-5f);
        }
    }
}

// The bilinear and nearest filters (Mitsuba's bitmap) read the full-resolution
// image at the point, whatever the footprint, in each wrap mode: the gradient
// EXR along the centre line of one texel row, at footprint 0.5 (half the image).
class ExactFilters : public testing::Test {
protected:
    Vec4 along(int row, float s, TextureWrap wrap, TextureFilter filter) const {
        return textures.lookup(exr, Vec2(s, centre(0, row).y), 0.5f, {wrap, filter});
    }
    TextureSystem textures;
    TextureHandle exr = textures.add(writeExr(test::scratchDir("texture-exact")), TextureEncoding::Data);
};

TEST_F(ExactFilters, NearestReadsTheTexelUnderThePointInEachWrapMode) {
    const auto at = [&](float s, TextureWrap wrap) { return along(1, s, wrap, TextureFilter::Nearest); };
    for (int x = 0; x < 4; ++x) {
        // Anywhere inside the texel, not only at its centre.
        EXPECT_EQ(at((float(x) + 0.1f) / 4.0f, TextureWrap::Repeat), Vec4(exrTexel(x, 1), 1.0f));
        EXPECT_EQ(at((float(x) + 0.9f) / 4.0f, TextureWrap::Clamp), Vec4(exrTexel(x, 1), 1.0f));
    }
    // Beyond the right edge: texel 1 of the next copy, of the mirrored copy
    // (its third from the left: 4 - 1 - 1 = 2), or the edge texel.
    const float s = (4.0f + 1.5f) / 4.0f;
    EXPECT_EQ(at(s, TextureWrap::Repeat), Vec4(exrTexel(1, 1), 1.0f));
    EXPECT_EQ(at(s, TextureWrap::Mirror), Vec4(exrTexel(2, 1), 1.0f));
    EXPECT_EQ(at(s, TextureWrap::Clamp), Vec4(exrTexel(3, 1), 1.0f));
    // Left of the left edge: mirrored texel 0 is texel 0 itself.
    EXPECT_EQ(at(-0.1f, TextureWrap::Mirror), Vec4(exrTexel(0, 1), 1.0f));
    EXPECT_EQ(at(-0.1f, TextureWrap::Repeat), Vec4(exrTexel(3, 1), 1.0f));
    EXPECT_EQ(at(-0.1f, TextureWrap::Clamp), Vec4(exrTexel(0, 1), 1.0f));
}

TEST_F(ExactFilters, BilinearInterpolatesTexelCentresInEachWrapMode) {
    const auto at = [&](float s, TextureWrap wrap) { return along(2, s, wrap, TextureFilter::Bilinear); };
    const auto mix = [](int a, int b) { return Vec4(0.5f * (exrTexel(a, 2) + exrTexel(b, 2)), 1.0f); };
    expectNear(at(0.5f, TextureWrap::Repeat), mix(1, 2), 1e-5f);
    // At s = 0: between the last and the first column, the first twice
    // (mirrored), or the first (clamped).
    expectNear(at(0.0f, TextureWrap::Repeat), mix(3, 0), 1e-5f);
    expectNear(at(0.0f, TextureWrap::Mirror), mix(0, 0), 1e-5f);
    expectNear(at(0.0f, TextureWrap::Clamp), mix(0, 0), 1e-5f);
    expectNear(at(1.0f + 0.5f / 4.0f, TextureWrap::Mirror), mix(3, 3), 1e-5f);
    expectNear(at(10.0f + 0.5f, TextureWrap::Clamp), mix(3, 3), 1e-5f);
    expectNear(at(10.0f + 0.5f, TextureWrap::Repeat), mix(1, 2), 1e-4f);
}

TEST(TextureSystem, BilinearDecodesSrgbBeforeInterpolating) {
    // Black and white texels: halfway between them is linear 0.5, as in a
    // renderer that converts the image to linear first (Mitsuba); the
    // footprint filter interpolates the codes and decodes 0.5 (0.214).
    const fs::path dir = test::scratchDir("texture-srgb-bilinear");
    const fs::path file = dir / "bw.png";
    writeImage(file, 2, 1, 1, OIIO::TypeDesc::UINT8, std::vector<uint8_t>{0, 255});
    TextureSystem textures;
    const TextureHandle bw = textures.add(file, TextureEncoding::Color);
    const Vec2 between(0.5f, 0.5f);
    EXPECT_NEAR(textures.lookup(bw, between, 0.0f, {TextureWrap::Clamp, TextureFilter::Bilinear}).r,
                0.5f, 1e-6f);
    EXPECT_NEAR(textures.lookup(bw, between, 0.0f).r, srgbToLinear(0.5), 1e-3f);
}

TEST(TextureSystem, LargeFootprintGivesTheImageMean) {
    const fs::path dir = test::scratchDir("texture-mean");
    TextureSystem textures;
    const TextureHandle checker = textures.add(writeChecker(dir), TextureEncoding::Data);
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Data);
    const Vec4 checkerMean(0.5f * (checkerTexel(0, 0) + checkerTexel(1, 0)), 1.0f);
    const Vec4 exrMean(1.75f, 3.75f, 7.0f, 1.0f);  // means of 0.25..3.25, 1.5..6, 7
    for (const Vec2 st : {Vec2(0.1f, 0.2f), Vec2(0.5f, 0.5f), Vec2(0.9f, 0.35f)})
        for (const float footprint : {1.0f, 10.0f, kInfinity}) {
            SCOPED_TRACE(testing::Message() << "st " << st.x << ", " << st.y << " footprint "
                                            << footprint);
            expectNear(textures.lookup(checker, st, footprint), checkerMean, 1e-6f);
            expectNear(textures.lookup(exr, st, footprint), exrMean, 1e-5f);
        }
}

TEST(TextureSystem, ColorPngIsDecodedFromSrgb) {
    const fs::path dir = test::scratchDir("texture-srgb");
    TextureSystem textures;
    const TextureHandle grey =
        textures.add(writeGrey<uint8_t>(dir / "grey.png", 128, OIIO::TypeDesc::UINT8),
                     TextureEncoding::Color);
    const Vec4 v = textures.lookup(grey, Vec2(0.3f, 0.8f), 0.0f);
    EXPECT_NEAR(v.r, 0.2158f, 1e-4f);
    EXPECT_NEAR(v.r, srgbToLinear(128.0 / 255.0), 1e-6);
    EXPECT_EQ(v.g, v.r);  // grey replicated
    EXPECT_EQ(v.b, v.r);
    EXPECT_EQ(v.a, 1.0f);  // no alpha channel

    // Every texel of the checker decodes exactly at its centre.
    const TextureHandle checker = textures.add(writeChecker(dir), TextureEncoding::Color);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const Vec4 c = textures.lookup(checker, centre(x, y), 0.0f);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(c[k], srgbToLinear(checkerTexel(x, y)[k]), 1e-6)
                    << x << ", " << y << " channel " << k;
        }
}

TEST(TextureSystem, Color16BitIsDecodedFromSrgb) {
    const fs::path dir = test::scratchDir("texture-srgb16");
    TextureSystem textures;
    const TextureHandle grey =
        textures.add(writeGrey<uint16_t>(dir / "grey16.png", 20000, OIIO::TypeDesc::UINT16),
                     TextureEncoding::Color);
    EXPECT_NEAR(textures.lookup(grey, Vec2(0.5f), 0.0f).r, srgbToLinear(20000.0 / 65535.0),
                1e-6);
}

TEST(TextureSystem, DataIsReturnedRaw) {
    const fs::path dir = test::scratchDir("texture-data");
    TextureSystem textures;
    const TextureHandle grey =
        textures.add(writeGrey<uint8_t>(dir / "grey.png", 128, OIIO::TypeDesc::UINT8),
                     TextureEncoding::Data);
    expectNear(textures.lookup(grey, Vec2(0.3f, 0.8f), 0.0f), Vec4(Vec3(128.0f / 255.0f), 1.0f),
               1e-6f);
}

TEST(TextureSystem, FloatExrIsLinearUnchanged) {
    const fs::path dir = test::scratchDir("texture-exr");
    TextureSystem textures;
    const fs::path file = writeExr(dir);
    const TextureHandle color = textures.add(file, TextureEncoding::Color);
    const TextureHandle data = textures.add(file, TextureEncoding::Data);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(textures.lookup(color, centre(x, y), 0.0f), Vec4(exrTexel(x, y), 1.0f));
            EXPECT_EQ(textures.lookup(color, centre(x, y), 0.0f),
                      textures.lookup(data, centre(x, y), 0.0f));
        }
}

TEST(TextureSystem, AlphaIsUnassociatedAndNotDecoded) {
    const fs::path dir = test::scratchDir("texture-alpha");
    TextureSystem textures;
    const fs::path rgba = dir / "rgba.png";
    writeImage(rgba, 2, 2, 4, OIIO::TypeDesc::UINT8, std::vector<uint8_t>(16, 128));
    const fs::path greyAlpha = dir / "grey-alpha.png";
    writeImage(greyAlpha, 2, 2, 2, OIIO::TypeDesc::UINT8,
               std::vector<uint8_t>{64, 128, 64, 128, 64, 128, 64, 128});
    const float half = 128.0f / 255.0f;

    const Vec4 c = textures.lookup(textures.add(rgba, TextureEncoding::Color), Vec2(0.5f), 0.0f);
    expectNear(c, Vec4(Vec3(float(srgbToLinear(half))), half), 1e-6f);
    const Vec4 g =
        textures.lookup(textures.add(greyAlpha, TextureEncoding::Color), Vec2(0.5f), 0.0f);
    expectNear(g, Vec4(Vec3(float(srgbToLinear(64.0 / 255.0))), half), 1e-6f);
}

TEST(TextureSystem, LookupColorAndLookupChannelAgreeWithLookup) {
    const fs::path dir = test::scratchDir("texture-channels");
    TextureSystem textures;
    const fs::path rgba = dir / "rgba.png";
    std::vector<uint8_t> pixels;
    for (int i = 0; i < 16; ++i)
        for (const int base : {10, 70, 130, 190}) pixels.push_back(uint8_t(base + 3 * i));
    writeImage(rgba, 4, 4, 4, OIIO::TypeDesc::UINT8, pixels);
    const TextureHandle handles[] = {
        textures.add(rgba, TextureEncoding::Color),
        textures.add(writeChecker(dir), TextureEncoding::Color),
        textures.add(writeGrey<uint8_t>(dir / "grey.png", 77, OIIO::TypeDesc::UINT8),
                     TextureEncoding::Data),
    };
    for (const TextureHandle h : handles)
        for (const float footprint : {0.0f, 0.3f}) {
            const Vec2 st(0.37f, 0.81f);
            const Vec4 full = textures.lookup(h, st, footprint);
            const Color rgb = textures.lookupColor(h, st, footprint);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], full[c], 1e-6f) << c;
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(textures.lookupChannel(h, c, st, footprint), full[c], 1e-6f) << c;
        }
    EXPECT_TRUE(test::contains(
        test::errorMessage([&] { textures.lookupChannel(handles[0], 4, Vec2(0.5f), 0.0f); }),
        "channel 4"));
}

TEST(TextureSystem, MissingFileThrowsNamingIt) {
    const fs::path dir = test::scratchDir("texture-missing");
    TextureSystem textures;
    const fs::path file = dir / "no-such-texture.png";
    const std::string message =
        test::errorMessage([&] { textures.add(file, TextureEncoding::Color); });
    EXPECT_TRUE(test::contains(message, file.string())) << message;
    EXPECT_TRUE(test::contains(message, "no such file")) << message;
    EXPECT_EQ(textures.textureCount(), 0u);
}

TEST(TextureSystem, FolderThrows) {
    const fs::path dir = test::scratchDir("texture-folder");
    TextureSystem textures;
    const std::string message =
        test::errorMessage([&] { textures.add(dir, TextureEncoding::Data); });
    EXPECT_TRUE(test::contains(message, dir.string())) << message;
    EXPECT_TRUE(test::contains(message, "not a regular file")) << message;
}

TEST(TextureSystem, TextFileNamedPngThrowsNamingIt) {
    const fs::path dir = test::scratchDir("texture-text");
    const fs::path file = dir / "notes.png";
    test::writeFile(file, "this is not an image\n");
    TextureSystem textures;
    const std::string message =
        test::errorMessage([&] { textures.add(file, TextureEncoding::Color); });
    EXPECT_TRUE(test::contains(message, file.string())) << message;
    EXPECT_TRUE(test::contains(message, "cannot read the texture")) << message;
    EXPECT_EQ(textures.textureCount(), 0u);
}

TEST(TextureSystem, SameFileAndEncodingIsRegisteredOnce) {
    const fs::path dir = test::scratchDir("texture-dedup");
    fs::create_directories(dir / "sub");
    const fs::path file = writeChecker(dir);
    TextureSystem textures;
    const TextureHandle first = textures.add(file, TextureEncoding::Color);
    ASSERT_TRUE(first.valid());
    EXPECT_EQ(textures.add(file, TextureEncoding::Color).index, first.index);
    EXPECT_EQ(textures.add(dir / "." / "checker.png", TextureEncoding::Color).index, first.index);
    EXPECT_EQ(textures.add(dir / "sub" / ".." / "checker.png", TextureEncoding::Color).index,
              first.index);
    EXPECT_EQ(textures.textureCount(), 1u);

    // The same file as data is another texture (raw, not decoded).
    const TextureHandle data = textures.add(file, TextureEncoding::Data);
    EXPECT_NE(data.index, first.index);
    EXPECT_EQ(textures.add(file, TextureEncoding::Data).index, data.index);
    EXPECT_EQ(textures.textureCount(), 2u);
    EXPECT_NEAR(textures.lookup(data, centre(0, 0), 0.0f).r, 200.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(textures.lookup(first, centre(0, 0), 0.0f).r, srgbToLinear(200.0 / 255.0), 1e-6);
}

TEST(TextureSystem, InvalidHandleThrows) {
    TextureSystem textures;
    EXPECT_THROW(textures.lookup(TextureHandle{}, Vec2(0.5f), 0.0f), Error);
    EXPECT_THROW(textures.lookup(TextureHandle{0}, Vec2(0.5f), 0.0f), Error);
}

TEST(TextureSystem, CacheSizeMustBePositive) {
    EXPECT_THROW(TextureSystem(0.0f), Error);
    EXPECT_THROW(TextureSystem(-5.0f), Error);
    EXPECT_THROW(TextureSystem(std::nanf("")), Error);
    EXPECT_NO_THROW(TextureSystem(16.0f));
}

TEST(TextureSystem, TriplanarWithNormalPlusZIsTheXyProjection) {
    const fs::path dir = test::scratchDir("texture-triplanar-z");
    TextureSystem textures;
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Data);
    const Vec3 p(0.3f, 0.7f, 5.2f);
    const float scale = 2.0f;
    for (const float footprint : {0.0f, 0.2f})
        for (const Vec3 n : {Vec3(0, 0, 1), Vec3(0, 0, -3)}) {
            const Vec4 expected = textures.lookup(exr, Vec2(p.x * scale, p.y * scale), footprint);
            EXPECT_EQ(textures.triplanar(exr, p, n, scale, 4.0f, footprint), expected);
        }
}

TEST(TextureSystem, TriplanarBlendsByNormalPowerNormalised) {
    const fs::path dir = test::scratchDir("texture-triplanar-blend");
    TextureSystem textures;
    const TextureHandle exr = textures.add(writeExr(dir), TextureEncoding::Data);
    const Vec3 p(0.1f, 0.45f, 0.8f);
    const Vec4 yz = textures.lookup(exr, Vec2(p.y, p.z), 0.0f);
    const Vec4 xz = textures.lookup(exr, Vec2(p.x, p.z), 0.0f);
    const Vec4 xy = textures.lookup(exr, Vec2(p.x, p.y), 0.0f);

    // Equal components: equal weights, whatever the sharpness.
    expectNear(textures.triplanar(exr, p, Vec3(1.0f), 1.0f, 4.0f, 0.0f), (yz + xz + xy) / 3.0f,
               1e-5f);
    // n = (0, 0.6, 0.8), sharpness 2: weights 0.36 and 0.64.
    expectNear(textures.triplanar(exr, p, Vec3(0.0f, 0.6f, 0.8f), 1.0f, 2.0f, 0.0f),
               0.36f * xz + 0.64f * xy, 1e-5f);
    // A degenerate normal blends all three equally rather than failing.
    expectNear(textures.triplanar(exr, p, Vec3(0.0f), 1.0f, 4.0f, 0.0f), (yz + xz + xy) / 3.0f,
               1e-5f);
}

TEST(TextureSystem, ParallelLookupsMatchSerial) {
    const fs::path dir = test::scratchDir("texture-threads");
    // 64 x 64 sRGB gradient: several tiles and MIP levels to load.
    constexpr int kSize = 64;
    std::vector<uint8_t> pixels;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (const int v : {4 * x, 4 * y, (x * y) % 256}) pixels.push_back(uint8_t(v));
    const fs::path file = dir / "gradient.png";
    writeImage(file, kSize, kSize, 3, OIIO::TypeDesc::UINT8, pixels);

    struct Query {
        Vec2 st;
        float footprint;
    };
    std::vector<Query> queries;
    for (int i = 0; i < 20000; ++i)
        queries.push_back({Vec2(0.0137f * float(i), 0.0291f * float(i) - 3.0f),
                           float(i % 7) * 0.02f});

    std::vector<Vec4> serial;
    {
        TextureSystem textures;
        const TextureHandle h = textures.add(file, TextureEncoding::Color);
        for (const Query& q : queries) serial.push_back(textures.lookup(h, q.st, q.footprint));
    }

    // A fresh system, so that both threads also race to load the tiles.
    TextureSystem textures;
    const TextureHandle h = textures.add(file, TextureEncoding::Color);
    std::vector<Vec4> results[2];
    auto work = [&](int thread) {
        for (size_t k = 0; k < queries.size(); ++k) {
            const Query& q = queries[thread == 0 ? k : queries.size() - 1 - k];
            results[thread].push_back(textures.lookup(h, q.st, q.footprint));
        }
    };
    std::thread a(work, 0), b(work, 1);
    a.join();
    b.join();
    ASSERT_EQ(results[0].size(), queries.size());
    ASSERT_EQ(results[1].size(), queries.size());
    size_t mismatches = 0;
    for (size_t k = 0; k < queries.size(); ++k) {
        mismatches += results[0][k] != serial[k];
        mismatches += results[1][queries.size() - 1 - k] != serial[k];
    }
    EXPECT_EQ(mismatches, 0u);
}

}  // namespace
}  // namespace strahl

namespace strahl {
namespace {

TEST(TextureSystem, SlopeIsTheExactDerivativeOfTheBilinearHeight) {
    const fs::path dir = test::scratchDir("texture-slope");
    // 4 x 2 float grey: row 0 = 0, 1, 3, 6; row 1 = 10 more.
    const std::vector<float> heights = {0, 1, 3, 6, 10, 11, 13, 16};
    writeImage(dir / "h.exr", 4, 2, 1, OIIO::TypeDesc::FLOAT, heights);
    TextureSystem textures;
    const TextureHandle h = textures.add(dir / "h.exr", TextureEncoding::Data);
    const TextureSampling bilinear{TextureWrap::Clamp, TextureFilter::Bilinear};
    // Between the centres of texels (1, 0) and (2, 0), a quarter of the way
    // down between the rows: x = 2, y = 0.75 in texels.
    const Vec3 v = textures.lookupSlope(h, Vec2(2.0f / 4.0f, 0.75f / 2.0f), bilinear);
    EXPECT_NEAR(v.x, 0.5f * (1 + 3) + 0.25f * 10, 1e-5f);
    EXPECT_NEAR(v.y, (3 - 1) * 4.0f, 1e-4f);  // per texel times the width
    EXPECT_NEAR(v.z, 10 * 2.0f, 1e-4f);       // per texel times the height
    // Nearest: flat texels, no slope.
    const Vec3 n = textures.lookupSlope(h, Vec2(0.6f, 0.25f), {TextureWrap::Clamp, TextureFilter::Nearest});
    EXPECT_EQ(n, Vec3(3.0f, 0.0f, 0.0f));
}

}  // namespace
}  // namespace strahl
