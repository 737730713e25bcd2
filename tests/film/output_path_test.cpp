// Output paths: supported extensions, unwritable destinations, and the
// guarantee that a failed write leaves no file (final or temporary) behind.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "strahl/core/error.h"
#include "strahl/film/film.h"
#include "strahl/film/image_output.h"
#include "test_support.h"

namespace strahl {
namespace {

namespace fs = std::filesystem;

Film smallFilm() {
    Film film(2, 2, PixelRect{0, 0, 2, 2}, {AovKind::Depth});
    film.addSample(0, 0, Color(1.0f), AovSample{});
    return film;
}

std::vector<std::string> listFolder(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    return names;
}

// The message of the strahl::Error that `action` throws, or "" after a failure.
template <typename Action>
std::string errorOf(Action action) {
    return test::errorMessage(action);
}

using test::contains;

TEST(OutputPath, AcceptsSupportedExtensionsInAnyCaseAndLeavesNoProbeFile) {
    const fs::path dir = test::scratchDir("film-path-ok");
    for (const char* name : {"a.exr", "b.EXR", "c.png", "d.jpg", "e.jpeg", "f.tif", "g.TiFf"})
        EXPECT_NO_THROW(checkOutputPath(dir / name)) << name;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputPath, UnsupportedExtensionNamesItAndTheSupportedOnes) {
    const fs::path dir = test::scratchDir("film-path-ext");
    const fs::path file = dir / "render.bmp";
    std::string message = errorOf([&] { checkOutputPath(file); });
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, "'.bmp'")) << message;
    EXPECT_TRUE(contains(message, ".exr .png .jpg .jpeg .tif .tiff")) << message;

    message = errorOf([&] { writeImage(smallFilm(), file, {}, {}); });
    EXPECT_TRUE(contains(message, "'.bmp'")) << message;
    message = errorOf([&] { checkOutputPath(dir / "render"); });
    EXPECT_TRUE(contains(message, "no extension")) << message;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputPath, MissingFolderIsReportedAndNothingIsCreated) {
    const fs::path dir = test::scratchDir("film-path-missing");
    const fs::path file = dir / "not" / "there" / "out.exr";
    std::string message = errorOf([&] { checkOutputPath(file); });
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, "does not exist")) << message;

    message = errorOf([&] { writeImage(smallFilm(), file, {}, {}); });
    EXPECT_TRUE(contains(message, file.string() + ": cannot write: ")) << message;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(OutputPath, AFolderIsNotAnOutputFile) {
    const fs::path dir = test::scratchDir("film-path-folder");
    const fs::path file = dir / "looks-like-an-image.exr";
    fs::create_directory(file);
    const std::string message = errorOf([&] { checkOutputPath(file); });
    EXPECT_TRUE(contains(message, file.string())) << message;
    EXPECT_TRUE(contains(message, "folder")) << message;

    // writeImage gets as far as the rename, which fails; the temporary goes.
    EXPECT_THROW(writeImage(smallFilm(), file, {}, {}), Error);
    EXPECT_EQ(listFolder(dir), std::vector<std::string>{"looks-like-an-image.exr"});
    EXPECT_TRUE(fs::is_empty(file));
}

TEST(OutputPath, ReadOnlyFolderIsReportedAndLeftEmpty) {
    if (::geteuid() == 0)
        GTEST_SKIP() << "running as root, which ignores folder permissions, so a "
                        "chmod 0555 folder stays writable";
    const fs::path dir = test::scratchDir("film-path-readonly");
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                             fs::perms::group_exec | fs::perms::others_read |
                             fs::perms::others_exec);
    for (const char* name : {"out.exr", "out.png"}) {
        const fs::path file = dir / name;
        std::string message = errorOf([&] { checkOutputPath(file); });
        EXPECT_TRUE(contains(message, file.string())) << message;
        EXPECT_TRUE(contains(message, "ermission denied")) << message;

        message = errorOf([&] { writeImage(smallFilm(), file, {}, {}); });
        EXPECT_TRUE(contains(message, file.string() + ": cannot write: ")) << message;
    }
    EXPECT_TRUE(fs::is_empty(dir));
    fs::permissions(dir, fs::perms::owner_all);  // so the next run can clear it
}

TEST(OutputPath, SuccessfulWriteLeavesOnlyTheImage) {
    const fs::path dir = test::scratchDir("film-path-clean");
    checkOutputPath(dir / "beauty.exr");
    writeImage(smallFilm(), dir / "beauty.exr", {}, {});
    EXPECT_EQ(listFolder(dir), std::vector<std::string>{"beauty.exr"});
}

TEST(OutputPath, RelativeFileNameUsesTheCurrentFolder) {
    const fs::path dir = test::scratchDir("film-path-relative");
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    EXPECT_NO_THROW(checkOutputPath("plain.png"));
    EXPECT_NO_THROW(writeImage(smallFilm(), "plain.exr", {}, {}));
    fs::current_path(previous);
    EXPECT_EQ(listFolder(dir), std::vector<std::string>{"plain.exr"});
}

}  // namespace
}  // namespace strahl
