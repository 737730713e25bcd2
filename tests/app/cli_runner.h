#pragma once
// Runs the strahl binary built with the tests (STRAHL_BINARY) and captures its
// exit status, stdout and stderr — shared by the CLI tests.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "sanitizers/sanitized.h"
#include "test_support.h"

namespace strahl::test {

struct RunResult {
    int status = -1;
    std::string out, err;
};

// `args` is appended to the binary's path as a shell command line. ctest runs
// tests in parallel processes, so the capture files carry the process id.
inline RunResult runStrahl(const std::string& args) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path();
    const std::string tag = std::to_string(getpid());
    const fs::path out = dir / ("strahl-cli-stdout-" + tag + ".txt");
    const fs::path err = dir / ("strahl-cli-stderr-" + tag + ".txt");
    const std::string command = std::string(STRAHL_BINARY) + " " + args + " >" + out.string() +
                                " 2>" + err.string();
    const int raw = std::system(command.c_str());
    RunResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = readFile(out);
    r.err = readFile(err);
    fs::remove(out);
    fs::remove(err);
    // Under the sanitizers a report stops strahl with status 86
    // (scripts/sanitize.sh); UBSan's report is in the stderr captured here.
    // Fail whatever status the test itself expects.
    if (kSanitized) {
        EXPECT_NE(r.status, kSanitizerExitCode) << "a sanitizer stopped strahl:\n" << r.err;
    }
    return r;
}

}  // namespace strahl::test
