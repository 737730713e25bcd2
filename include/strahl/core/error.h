#pragma once
// The one error type of strahl. Every user-facing failure (bad scene, bad mesh,
// unwritable output) throws strahl::Error with a message that names the file and
// the place; the CLI prints it and exits non-zero. Never thrown through Embree.

#include <sstream>
#include <stdexcept>
#include <string>

namespace strahl {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Builds a message from any streamable pieces: fail("bad index ", i, " in ", file).
template <typename... Args>
std::string concat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}

template <typename... Args>
[[noreturn]] void fail(const Args&... args) {
    throw Error(concat(args...));
}

}  // namespace strahl
