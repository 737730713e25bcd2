// Textures and their images: an image file on disk for each texture, found
// from its percent-decoded URI next to the glTF, or extracted once from the
// file (data URI or buffer view) into a temporary folder.

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "gltf_reader.h"
#include "strahl/core/hash.h"

namespace strahl::meshio::gltf {

namespace {

// RFC 3986 percent-decoding of a URI path ("my%20file.png"); a '%' not
// followed by two hex digits is kept as it is.
std::string percentDecode(std::string_view uri) {
    const auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    std::string out;
    out.reserve(uri.size());
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size()) {
            const int hi = hex(uri[i + 1]), lo = hex(uri[i + 2]);
            if (hi >= 0 && lo >= 0) {
                out += static_cast<char>(hi * 16 + lo);
                i += 2;
                continue;
            }
        }
        out += uri[i];
    }
    return out;
}

std::string hex64(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// File extension for encoded image bytes: the content decides, the declared MIME
// type only when the content is not recognised. Empty: not a format strahl reads.
std::string imageExtension(const unsigned char* bytes, size_t size, const std::string& mime) {
    static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G'};
    static constexpr unsigned char kJpeg[] = {0xFF, 0xD8, 0xFF};
    if (size >= sizeof kPng && std::memcmp(bytes, kPng, sizeof kPng) == 0) return ".png";
    if (size >= sizeof kJpeg && std::memcmp(bytes, kJpeg, sizeof kJpeg) == 0) return ".jpg";
    if (mime == "image/png") return ".png";
    if (mime == "image/jpeg") return ".jpg";
    return {};
}

}  // namespace

// The image file of texture `index` (-1: none), or empty with a warning.
fs::path GltfReader::texture(int index, int texCoord, const std::string& place) {
    if (index < 0) return {};
    if (size_t(index) >= model_.textures.size())
        error(place, ": texture ", index, " does not exist (", model_.textures.size(),
              " textures)");
    if (texCoord != 0)
        warnOnce("texcoord",
                 concat(place, ": uses TEXCOORD_", texCoord, "; strahl reads TEXCOORD_0 only"));
    const int source = model_.textures[size_t(index)].source;
    if (source < 0) {
        // Only an extension (KTX2, WebP, ...) gives its image.
        meshio::warn(concat(name_, ": ", place, ": texture ", index,
                            " has no PNG/JPEG source; the texture is ignored"));
        return {};
    }
    if (size_t(source) >= model_.images.size())
        error(place, ": texture ", index, " refers to image ", source, ", which does not exist (",
              model_.images.size(), " images)");
    return image(size_t(source));
}

fs::path GltfReader::image(size_t index) {
    if (images_.size() < model_.images.size()) images_.resize(model_.images.size());
    if (!images_[index]) images_[index] = resolveImage(index);
    return *images_[index];
}

fs::path GltfReader::resolveImage(size_t index) {
    const tinygltf::Image& img = model_.images[index];
    const std::string place = concat("images[", index, "]");
    if (img.bufferView >= 0) {
        const unsigned char* bytes = checkedView(img.bufferView, place);
        return extracted(index, bytes, model_.bufferViews[size_t(img.bufferView)].byteLength,
                         img.mimeType);
    }
    if (!img.image.empty())
        return extracted(index, img.image.data(), img.image.size(), img.mimeType);
    if (img.uri.rfind("data:", 0) == 0) {
        meshio::warn(concat(name_, ": ", place, ": unsupported data URI type '",
                            img.uri.substr(0, std::min<size_t>(img.uri.find(','), 40)),
                            "'; the texture is ignored"));
        return {};
    }
    if (img.uri.find("://") != std::string::npos) {
        meshio::warn(concat(name_, ": ", place, ": '", img.uri,
                            "' is not a relative path; the texture is ignored"));
        return {};
    }
    const std::string decoded = percentDecode(img.uri);
    fs::path found = findFileCaseInsensitive(folder_, decoded);
    if (found.empty())
        meshio::warn(concat(name_, ": ", place, ": texture '", decoded,
                            "' not found; materials using it get no texture"));
    return found;
}

// Writes an embedded image once into temp/strahl-gltf-<hash of the glTF's
// path>/image<i>-<hash of the bytes>.<ext> and returns that path: a file of
// that name and size is the same image and is reused.
fs::path GltfReader::extracted(size_t index, const unsigned char* bytes, size_t size,
                               const std::string& mime) {
    const std::string place = concat(name_, ": images[", index, "]: ");
    const std::string ext = imageExtension(bytes, size, mime);
    if (ext.empty()) {
        meshio::warn(concat(place, "embedded image of type '", mime,
                            "' is neither PNG nor JPEG; the texture is ignored"));
        return {};
    }
    std::error_code ec;
    const fs::path temp = fs::temp_directory_path(ec);
    if (ec) {
        meshio::warn(concat(place, "no temporary folder for the embedded image (", ec.message(),
                            "); the texture is ignored"));
        return {};
    }
    const fs::path dir = temp / ("strahl-gltf-" + hex64(fileHash_));
    const fs::path file = dir / concat("image", index, '-', hex64(fnv1a(bytes, size)), ext);
    if (fs::file_size(file, ec) == size && !ec) return file;
    // Written under a unique name, then renamed: a loader running in parallel
    // never sees half an image.
    static std::atomic<unsigned> counter{0};
    const fs::path part = concat(file.string(), ".part-", getpid(), '-', counter++);
    bool written = false;
    fs::create_directories(dir, ec);
    if (!ec) {
        std::FILE* f = std::fopen(part.c_str(), "wb");
        if (f != nullptr) {
            written = std::fwrite(bytes, 1, size, f) == size;
            written = std::fclose(f) == 0 && written;
        }
        if (written) fs::rename(part, file, ec);
        written = written && !ec;
        std::error_code ignored;  // nothing to remove after a successful rename
        if (!written) fs::remove(part, ignored);
    }
    if (!written) {
        meshio::warn(concat(place, "cannot write the embedded image to ", file.string(),
                            "; the texture is ignored"));
        return {};
    }
    return file;
}

}  // namespace strahl::meshio::gltf
