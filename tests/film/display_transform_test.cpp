// DisplayTransform: the built-in config's views, config precedence
// (--ocio-config, $OCIO, built-in), errors and the processor cache.

#include "strahl/film/display_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "strahl/core/error.h"
#include "test_support.h"

namespace strahl {
namespace {

// Sets or unsets an environment variable for the lifetime of the object.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (value != nullptr)
            ::setenv(name, value, 1);
        else
            ::unsetenv(name);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_.c_str(), old_->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }

  private:
    std::string name_;
    std::optional<std::string> old_;
};

// A minimal valid OCIO v2 config: display "Test Monitor" with a pure 2.2 gamma
// view (default) and a linear view.
constexpr const char* kTestConfig = R"(ocio_profile_version: 2

roles:
  default: linear
  scene_linear: linear

file_rules:
  - !<Rule> {name: Default, colorspace: default}

displays:
  Test Monitor:
    - !<View> {name: Gamma 2.2, colorspace: gamma22}
    - !<View> {name: Linear, colorspace: linear}

colorspaces:
  - !<ColorSpace>
    name: linear
    encoding: scene-linear

  - !<ColorSpace>
    name: gamma22
    from_scene_reference: !<ExponentTransform> {value: 2.2, direction: inverse}
)";

std::filesystem::path writeFile(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file) << text;
    return file;
}

// Applies the transform to grey pixels of the given values; returns the
// outputs, checking that the three channels agree.
std::vector<float> applyToGreys(const DisplayTransform& transform, const std::vector<float>& in) {
    std::vector<float> rgb;
    for (float v : in) rgb.insert(rgb.end(), {v, v, v});
    transform.apply(rgb, static_cast<int>(in.size()), 1);
    std::vector<float> out;
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_FLOAT_EQ(rgb[3 * i], rgb[3 * i + 1]) << "input " << in[i];
        EXPECT_FLOAT_EQ(rgb[3 * i], rgb[3 * i + 2]) << "input " << in[i];
        out.push_back(rgb[3 * i]);
    }
    return out;
}

std::string errorOf(const ColorSettings& settings) {
    return test::errorMessage([&] { DisplayTransform::get(settings); });
}

using test::contains;

// Every test starts without $OCIO, so the built-in config is the default.
class DisplayTransformTest : public ::testing::Test {
  private:
    ScopedEnv noOcio_{"OCIO", nullptr};
};

TEST_F(DisplayTransformTest, BuiltinDefaultsToSrgbStandard) {
    const auto transform = DisplayTransform::get({});
    EXPECT_EQ(transform->description(), "builtin / sRGB / Standard");
}

TEST_F(DisplayTransformTest, StandardIsThePiecewiseSrgbEncoding) {
    const auto transform = DisplayTransform::get({"", "sRGB", "Standard"});
    const std::vector<float> out = applyToGreys(*transform, {0.0f, 0.001f, 0.18f, 0.5f, 1.0f});
    EXPECT_NEAR(out[0], 0.0f, 1e-6f);
    EXPECT_NEAR(out[1], 12.92f * 0.001f, 1e-4f);  // the linear toe
    EXPECT_NEAR(out[2], 0.4614f, 5e-4f);          // 118 / 255
    EXPECT_NEAR(out[3], 1.055f * std::pow(0.5f, 1.0f / 2.4f) - 0.055f, 5e-4f);
    EXPECT_NEAR(out[4], 1.0f, 1e-4f);
}

TEST_F(DisplayTransformTest, RawIsTheIdentity) {
    const auto transform = DisplayTransform::get({"", "", "Raw"});
    EXPECT_EQ(transform->description(), "builtin / sRGB / Raw");
    std::vector<float> rgb{0.18f, 2.5f, -0.25f, 0.0f, 1.0f, 1000.0f};
    const std::vector<float> in = rgb;
    transform->apply(rgb, 2, 1);
    EXPECT_EQ(rgb, in);
}

TEST_F(DisplayTransformTest, FilmicRollsHighlightsOffBelowWhite) {
    const auto transform = DisplayTransform::get({"", "sRGB", "Filmic"});
    std::vector<float> in{0.0f};
    for (float stop = -14.0f; stop <= 12.0f; stop += 0.125f) in.push_back(std::exp2(stop));
    const std::vector<float> out = applyToGreys(*transform, in);
    for (size_t i = 1; i < out.size(); ++i)
        EXPECT_GE(out[i], out[i - 1]) << "not monotonic between " << in[i - 1] << " and " << in[i];
    EXPECT_NEAR(out.front(), 0.0f, 1e-3f);
    EXPECT_LT(out.back(), 1.0f);

    const std::vector<float> anchors = applyToGreys(*transform, {0.18f, 1.0f, 16.0f});
    EXPECT_GT(anchors[0], 0.38f);  // mid grey stays roughly mid grey
    EXPECT_LT(anchors[0], 0.50f);
    EXPECT_LT(anchors[1], 0.95f);  // scene white is not yet display white
    EXPECT_GT(anchors[2], 0.9f);
    EXPECT_LT(anchors[2], 1.0f);
}

TEST_F(DisplayTransformTest, ProcessorsAreCachedPerDisplayAndView) {
    const auto a = DisplayTransform::get({});
    const auto b = DisplayTransform::get({"", "sRGB", "Standard"});
    const auto c = DisplayTransform::get({"", "sRGB", "Filmic"});
    EXPECT_EQ(a.get(), b.get());
    EXPECT_NE(a.get(), c.get());
}

TEST_F(DisplayTransformTest, OneTransformServesManyThreads) {
    const auto transform = DisplayTransform::get({"", "", "Filmic"});
    std::vector<float> reference(3 * 256);
    for (size_t i = 0; i < reference.size(); ++i) reference[i] = static_cast<float>(i) / 64.0f;
    std::vector<std::vector<float>> buffers(4, reference);
    transform->apply(reference, 256, 1);

    std::vector<std::thread> threads;
    for (auto& buffer : buffers)
        threads.emplace_back([&transform, &buffer] { transform->apply(buffer, 16, 16); });
    for (auto& thread : threads) thread.join();
    for (const auto& buffer : buffers) EXPECT_EQ(buffer, reference);
}

TEST_F(DisplayTransformTest, UnknownDisplayListsTheAvailableOnes) {
    const std::string message = errorOf({"", "Cinema", ""});
    EXPECT_TRUE(contains(message, "'Cinema'")) << message;
    EXPECT_TRUE(contains(message, "'sRGB'")) << message;
}

TEST_F(DisplayTransformTest, UnknownViewListsTheAvailableOnes) {
    const std::string message = errorOf({"", "sRGB", "ACES"});
    EXPECT_TRUE(contains(message, "'ACES'")) << message;
    for (const char* view : {"'Standard'", "'Filmic'", "'Raw'"})
        EXPECT_TRUE(contains(message, view)) << message;
}

TEST_F(DisplayTransformTest, ApplyRejectsABufferOfTheWrongSize) {
    const auto transform = DisplayTransform::get({});
    std::vector<float> rgb(3 * 5);
    EXPECT_THROW(transform->apply(rgb, 2, 2), Error);
    std::vector<float> empty;
    EXPECT_NO_THROW(transform->apply(empty, 0, 0));
}

TEST_F(DisplayTransformTest, OcioEnvironmentVariableIsHonoured) {
    const auto config = writeFile(test::scratchDir("film-ocio-env") / "env.ocio", kTestConfig);
    const ScopedEnv env("OCIO", config.c_str());
    const auto transform = DisplayTransform::get({});
    EXPECT_EQ(transform->description(), config.string() + " / Test Monitor / Gamma 2.2");
    const std::vector<float> out = applyToGreys(*transform, {0.18f, 1.0f});
    EXPECT_NEAR(out[0], std::pow(0.18f, 1.0f / 2.2f), 1e-4f);
    EXPECT_NEAR(out[1], 1.0f, 1e-5f);

    const std::string message = errorOf({"", "", "Standard"});
    EXPECT_TRUE(contains(message, "$OCIO (" + config.string() + ")")) << message;
    EXPECT_TRUE(contains(message, "'Gamma 2.2', 'Linear'")) << message;
}

TEST_F(DisplayTransformTest, ConfigFileTakesPrecedenceOverOcio) {
    const auto dir = test::scratchDir("film-ocio-precedence");
    const auto config = writeFile(dir / "explicit.ocio", kTestConfig);
    const ScopedEnv env("OCIO", (dir / "missing.ocio").c_str());
    const auto transform = DisplayTransform::get({config.string(), "", "Linear"});
    EXPECT_EQ(transform->description(), config.string() + " / Test Monitor / Linear");
    EXPECT_NEAR(applyToGreys(*transform, {0.18f})[0], 0.18f, 1e-6f);
}

TEST_F(DisplayTransformTest, ViewsOfAnExternalConfigAreChecked) {
    const auto config = writeFile(test::scratchDir("film-ocio-views") / "views.ocio", kTestConfig);
    const std::string message = errorOf({config.string(), "Test Monitor", "Standard"});
    EXPECT_TRUE(contains(message, config.string())) << message;
    EXPECT_TRUE(contains(message, "'Gamma 2.2', 'Linear'")) << message;
}

TEST_F(DisplayTransformTest, MissingOcioFileIsNamed) {
    const auto missing = test::scratchDir("film-ocio-missing") / "nowhere.ocio";
    const ScopedEnv env("OCIO", missing.c_str());
    const std::string message = errorOf({});
    EXPECT_TRUE(contains(message, "$OCIO")) << message;
    EXPECT_TRUE(contains(message, missing.string())) << message;
}

TEST_F(DisplayTransformTest, InvalidOcioContentIsNamed) {
    const auto broken = writeFile(test::scratchDir("film-ocio-invalid") / "broken.ocio",
                                  "ocio_profile_version: 2\ncolorspaces: [ {{{\n");
    const ScopedEnv env("OCIO", broken.c_str());
    const std::string message = errorOf({});
    EXPECT_TRUE(contains(message, "$OCIO")) << message;
    EXPECT_TRUE(contains(message, broken.string())) << message;
    EXPECT_TRUE(contains(message, "invalid OpenColorIO config")) << message;
}

TEST_F(DisplayTransformTest, MissingOrInvalidConfigFileIsNamed) {
    const auto dir = test::scratchDir("film-ocio-file");
    const auto missing = dir / "absent.ocio";
    std::string message = errorOf({missing.string(), "", ""});
    EXPECT_TRUE(contains(message, missing.string())) << message;

    // Well-formed YAML, but a view refers to a colour space that does not exist.
    std::string text = kTestConfig;
    text.replace(text.find("colorspace: gamma22"), 19, "colorspace: gamma24");
    const auto invalid = writeFile(dir / "invalid.ocio", text);
    message = errorOf({invalid.string(), "", ""});
    EXPECT_TRUE(contains(message, invalid.string())) << message;
    EXPECT_TRUE(contains(message, "invalid OpenColorIO config")) << message;
}

TEST_F(DisplayTransformTest, ConfigWithoutSceneLinearRoleIsRejected) {
    std::string text = kTestConfig;
    text.erase(text.find("  scene_linear: linear\n"), 23);
    const auto config = writeFile(test::scratchDir("film-ocio-role") / "norole.ocio", text);
    const std::string message = errorOf({config.string(), "", ""});
    EXPECT_TRUE(contains(message, config.string())) << message;
    EXPECT_TRUE(contains(message, "scene_linear")) << message;
}

}  // namespace
}  // namespace strahl
