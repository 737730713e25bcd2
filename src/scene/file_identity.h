#pragma once
// Internal to the scene module: the name under which the importers' include-
// cycle checks compare files.

#include <filesystem>
#include <system_error>

namespace strahl::scene_detail {

// `file` made absolute with symbolic links, "." and ".." resolved as far as
// the file system allows (std::filesystem::weakly_canonical). A path the file
// system refuses to resolve (a name longer than it allows, a loop of links)
// is compared in its lexically normal absolute form instead of throwing: the
// include then fails with its own clear error when it is opened.
inline std::filesystem::path fileIdentity(const std::filesystem::path& file) {
    std::error_code ec;
    std::filesystem::path canonical = std::filesystem::weakly_canonical(file, ec);
    if (!ec) return canonical;
    std::filesystem::path absolute = std::filesystem::absolute(file, ec);
    return (ec ? file : absolute).lexically_normal();
}

}  // namespace strahl::scene_detail
