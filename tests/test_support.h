#pragma once
// Shared helpers for the test suite: where the repository and ../shared/data
// are, and a skip for tests that need the shared data set.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "strahl/core/error.h"

namespace strahl::test {

inline std::filesystem::path sourceDir() { return STRAHL_SOURCE_DIR; }
inline std::filesystem::path sharedData() { return STRAHL_SHARED_DATA; }

// A fresh, empty scratch folder for one test. ctest runs every test in its own
// process, several at once, so the folder name carries the process id. The
// folders are removed when the test process exits normally (set
// STRAHL_KEEP_SCRATCH to keep them for a look after a failure).
inline std::filesystem::path scratchDir(const std::string& name) {
    struct Cleanup {
        std::vector<std::filesystem::path> dirs;
        ~Cleanup() {
            if (std::getenv("STRAHL_KEEP_SCRATCH")) return;
            std::error_code ignored;  // a folder already gone is no failure
            for (const auto& dir : dirs) std::filesystem::remove_all(dir, ignored);
        }
    };
    static Cleanup cleanup;
    auto dir = std::filesystem::temp_directory_path() /
               ("strahl-test-" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    cleanup.dirs.push_back(dir);
    return dir;
}

// Writes `text` to `path` byte for byte, creating the parent folders.
inline void writeFile(const std::filesystem::path& path, const std::string& text) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

inline std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// The message of the strahl::Error that action() throws; a test failure if it
// throws none.
template <typename Action>
std::string errorMessage(Action&& action) {
    try {
        action();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a strahl::Error";
    return {};
}

}  // namespace strahl::test

// Skips the current test when ../shared/data (next to the repository) is absent,
// as it is in a user's clone.
#define STRAHL_REQUIRE_SHARED_DATA()                                                     \
    do {                                                                                 \
        if (!std::filesystem::exists(::strahl::test::sharedData() / "MANIFEST.tsv"))     \
            GTEST_SKIP() << "needs ../shared/data (the project's shared test data set), " \
                            "which is not next to this checkout";                         \
    } while (0)
