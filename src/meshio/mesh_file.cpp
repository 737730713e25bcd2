// File-level parts of meshio: dispatch on the extension (mesh_format.h), reading a whole file,
// warnings, and the case-insensitive file lookup used for .mtl and texture names.

#include "strahl/meshio/mesh_file.h"
#include "strahl/meshio/mesh_format.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <system_error>
#include <vector>

#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl {

namespace meshio {

namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

void refuseSpecialFile(const fs::path& file) {
    std::error_code statusError;
    const fs::file_status status = fs::status(file, statusError);
    if (!statusError && fs::exists(status) && !fs::is_regular_file(status) &&
        !fs::is_directory(status))
        fail(file.string(), ": cannot open: not a regular file");
}

std::string readWholeFile(const fs::path& file) {
    refuseSpecialFile(file);  // a folder fails with EISDIR below

    errno = 0;
    std::unique_ptr<std::FILE, FileCloser> f(std::fopen(file.c_str(), "rb"));
    if (!f) fail(file.string(), ": cannot open: ", std::strerror(errno));

    // Read straight into a buffer of the expected size, then pick up anything the
    // size did not announce (a growing file, or a directory, whose size is an error
    // and whose read fails with EISDIR below).
    std::error_code ec;
    const uintmax_t expected = fs::file_size(file, ec);
    std::string data(ec ? 0 : static_cast<size_t>(expected), '\0');
    data.resize(std::fread(data.data(), 1, data.size(), f.get()));
    char chunk[1 << 16];
    while (!std::ferror(f.get()) && !std::feof(f.get())) {
        const size_t n = std::fread(chunk, 1, sizeof chunk, f.get());
        data.append(chunk, n);
    }
    if (std::ferror(f.get())) fail(file.string(), ": cannot open: ", std::strerror(errno));
    return data;
}

namespace {
std::mutex warningMutex;
MeshWarningHandler warningHandler;  // empty: print to stderr
}  // namespace

void warn(const std::string& message) {
    // Loaders run in parallel; one lock keeps lines whole and the handler safe.
    std::lock_guard lock(warningMutex);
    if (warningHandler)
        warningHandler(message);
    else
        std::fprintf(stderr, "strahl: warning: %s\n", message.c_str());
}

void reportWarning(const std::string& message) { warn(message); }

std::string toLower(std::string_view s) {
    std::string out(s);
    for (char& c : out) {
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    }
    return out;
}

}  // namespace meshio

void setMeshWarningHandler(MeshWarningHandler handler) {
    std::lock_guard lock(meshio::warningMutex);
    meshio::warningHandler = std::move(handler);
}

LoadedMesh loadMeshFile(const fs::path& file) {
    if (const MeshFormat* format = findMeshFormat(file)) return format->load(file);
    fail(file.string(), ": unknown mesh file extension '", file.extension().string(),
         "' (expected ", meshExtensionList(", ", " or "), ")");
}

fs::path findFileCaseInsensitive(const fs::path& dir, const std::string& name) {
    // Split on both separators: .mtl files written on Windows use backslashes.
    std::vector<std::string> parts;
    std::string part;
    for (const char c : name) {
        if (c == '/' || c == '\\') {
            if (!part.empty() && part != ".") parts.push_back(part);
            part.clear();
        } else {
            part += c;
        }
    }
    if (!part.empty() && part != ".") parts.push_back(part);
    if (parts.empty()) return {};

    // An empty dir (an OBJ named without a folder) means the working directory,
    // which directory_iterator needs spelled out.
    fs::path current = name[0] == '/' ? fs::path("/") : dir.empty() ? fs::path(".") : dir;
    for (size_t i = 0; i < parts.size(); ++i) {
        // Inner components must be folders, the last one must not be.
        const bool wantDirectory = i + 1 < parts.size();
        const auto fits = [&](const fs::path& p) {
            std::error_code statusError;  // a missing file is just "does not fit"
            const fs::file_status st = fs::status(p, statusError);
            return fs::exists(st) && fs::is_directory(st) == wantDirectory;
        };
        const fs::path exact = current / parts[i];
        if (parts[i] == ".." || fits(exact)) {
            current = exact;
            continue;
        }
        // Several spellings may match ("a.jpg" and "A.JPG"): take the smallest
        // name so the result does not depend on directory order.
        const std::string wanted = meshio::toLower(parts[i]);
        fs::path match;
        std::error_code ec;  // an unreadable folder ends the scan: not found
        for (fs::directory_iterator it(current, ec), end; !ec && it != end; it.increment(ec)) {
            const fs::path candidate = it->path();
            if (meshio::toLower(candidate.filename().string()) != wanted || !fits(candidate))
                continue;
            if (match.empty() || candidate.filename() < match.filename()) match = candidate;
        }
        if (match.empty()) return {};
        current = match;
    }
    return current;
}

}  // namespace strahl
