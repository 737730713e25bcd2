#pragma once
// Shared by the meshio loader tests: the meshio warnings of a scope.

#include <string>

#include "strahl/meshio/mesh_file.h"

namespace strahl::test {

// Collects the meshio warnings of its lifetime, one line each, and restores
// the default handler (stderr) when it ends.
class WarningCapture {
public:
    WarningCapture() {
        setMeshWarningHandler([this](const std::string& m) { text_ += m + "\n"; });
    }
    ~WarningCapture() { setMeshWarningHandler(nullptr); }
    WarningCapture(const WarningCapture&) = delete;
    WarningCapture& operator=(const WarningCapture&) = delete;
    const std::string& text() const { return text_; }

private:
    std::string text_;
};

}  // namespace strahl::test
