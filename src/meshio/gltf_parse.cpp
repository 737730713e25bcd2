// Parsing: tinygltf reads the JSON (or .glb) and its buffers into the model,
// after the checks of the GLB layout and of image views it lacks; extensions
// strahl does not read are refused (required) or named in a warning (used).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include "gltf_reader.h"
#include "strahl/core/hash.h"

// tinygltf's implementation is compiled here, configured by gltf_reader.h (no
// image decoding). Included last: it declares nlohmann::json with hidden
// visibility, which must not be the first declaration of anything else (a
// libc function such as getpid would become hidden).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

namespace strahl::meshio::gltf {

namespace {

// Extensions whose data the loader reads; any other one listed in
// extensionsRequired is an error, in extensionsUsed a warning.
constexpr std::string_view kSupportedExtensions[] = {
    "KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission"};

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kGlbBinChunk = 0x004E4942;   // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12;          // magic, version, length
constexpr size_t kGlbChunkHeaderBytes = 8;      // length, type

uint32_t readLe32(std::string_view bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof value);
    return value;
}

// tinygltf's image callback. Data-URI images arrive decoded from base64 and are
// kept as they are (still PNG/JPEG bytes). Images in buffer views are left
// alone: tinygltf hands them over without checking the view against its
// buffer, so the reader extracts them itself after checking.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// tinygltf looks for external buffers in the glTF's folder (given as an absolute
// path) and then in the working directory; refusing relative paths drops the
// second guess.
bool fileExistsInGltfFolder(const std::string& path, void* userData) {
    return fs::path(path).is_absolute() && tinygltf::FileExists(path, userData);
}

// tinygltf's messages end in '\n' and may be several: join them into one line.
// Each is cut at 200 characters, as some quote a whole base64 data URI.
std::string oneLine(const std::string& text) {
    constexpr size_t kMaxLine = 200;
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string_view line = meshio::trimBlanks({text.data() + start, end - start});
        if (!line.empty()) {
            if (!out.empty()) out += "; ";
            out += line.substr(0, kMaxLine);
            if (line.size() > kMaxLine) out += "...";
        }
        start = end + 1;
    }
    return out;
}

}  // namespace

// Runs a tinygltf call. tinygltf 2.7 throws for some inputs instead of
// failing (std::out_of_range for a .glb whose BIN chunk is longer than a
// zero-length buffer, say): that becomes a strahl::Error naming the file.
template <typename Call>
bool GltfReader::guarded(Call&& call) const {
    try {
        return call();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        error("tinygltf could not read the file: ", e.what());
    }
}

void GltfReader::parse(std::string_view bytes) {
    std::error_code ec;
    const fs::path absolute = fs::weakly_canonical(fs::absolute(path_, ec), ec);
    const std::string absoluteName = ec ? name_ : absolute.string();
    fileHash_ = fnv1a(absoluteName.data(), absoluteName.size());
    const fs::path folder = ec ? path_.parent_path() : absolute.parent_path();
    folder_ = path_.parent_path();

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&keepEncodedImage, nullptr);
    loader.SetFsCallbacks({&fileExistsInGltfFolder, &tinygltf::ExpandFilePath,
                           &tinygltf::ReadWholeFile, &tinygltf::WriteWholeFile, nullptr});
    std::string err, warn;
    bool ok = false;
    const bool binary = bytes.size() >= 4 && readLe32(bytes, 0) == kGlbMagic;
    if (binary) {
        const uint32_t length = checkGlbLayout(bytes);
        checkImageViewsStartInTheirBuffers(
            bytes.substr(kGlbHeaderBytes + kGlbChunkHeaderBytes, readLe32(bytes, 12)));
        ok = guarded([&] {
            return loader.LoadBinaryFromMemory(&model_, &err, &warn,
                                               reinterpret_cast<const unsigned char*>(bytes.data()),
                                               length, folder.string());
        });
    } else {
        if (bytes.size() > std::numeric_limits<unsigned int>::max())
            fail(name_, ": ", bytes.size(), " bytes of JSON is more than tinygltf reads (4 GiB)");
        checkImageViewsStartInTheirBuffers(bytes);
        ok = guarded([&] {
            return loader.LoadASCIIFromString(&model_, &err, &warn, bytes.data(),
                                              static_cast<unsigned int>(bytes.size()),
                                              folder.string());
        });
    }
    if (!ok) fail(name_, ": ", err.empty() ? "cannot parse the glTF" : oneLine(err));
    // Messages tinygltf reports without failing are warnings.
    for (const std::string* text : {&warn, &err}) {
        if (!text->empty()) meshio::warn(name_ + ": " + oneLine(*text));
    }
}

// tinygltf 2.7 hands an image stored in a buffer view to the image loader as
// &buffer.data[view.byteOffset] before anything checks the view against its
// buffer: for a view starting at or past the buffer's end, an out-of-range
// vector index — undefined behaviour (found by the sanitizer build's
// _GLIBCXX_ASSERTIONS on a mutated .glb), though nothing reads there
// (keepEncodedImage ignores the bytes; checkedView rejects the view later).
// So such a file is refused before tinygltf sees it, with checkedView's
// message. The JSON is read as tinygltf reads it (indices: integers cut to
// int; byteOffset: only if unsigned, else 0; a loaded buffer's data is
// exactly its byteLength); anything else wrong is left to tinygltf.
void GltfReader::checkImageViewsStartInTheirBuffers(std::string_view text) const {
    using nlohmann::json;
    const json doc = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    const auto member = [](const json& object, const char* key) -> const json* {
        if (!object.is_object()) return nullptr;
        const auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    };
    const auto unsignedOr = [](const json* value, uint64_t otherwise) {
        return value && value->is_number_unsigned() ? value->get<uint64_t>() : otherwise;
    };
    const auto element = [&](const char* array, const json* index, int& i) -> const json* {
        const json* items = member(doc, array);
        if (!items || !items->is_array() || !index || !index->is_number_integer()) return nullptr;
        i = static_cast<int>(index->get<int64_t>());
        return i >= 0 && size_t(i) < items->size() ? &(*items)[size_t(i)] : nullptr;
    };
    const json* images = member(doc, "images");
    if (!images || !images->is_array()) return;
    for (size_t i = 0; i < images->size(); ++i) {
        int view = -1, buffer = -1;
        const json* v = element("bufferViews", member((*images)[i], "bufferView"), view);
        const json* b = v ? element("buffers", member(*v, "buffer"), buffer) : nullptr;
        const json* bufferLength = b ? member(*b, "byteLength") : nullptr;
        if (!bufferLength || !bufferLength->is_number_unsigned()) continue;
        const uint64_t offset = unsignedOr(member(*v, "byteOffset"), 0);
        if (offset >= bufferLength->get<uint64_t>())
            error("images[", i, "]: buffer view ", view, " (",
                  unsignedOr(member(*v, "byteLength"), 0), " bytes from offset ", offset,
                  ") reads past the end of buffer ", buffer, " (", bufferLength->get<uint64_t>(),
                  " bytes)");
    }
}

// Checks the GLB header and chunk headers (tinygltf's own messages do not say
// what is missing) and returns the length the header announces.
uint32_t GltfReader::checkGlbLayout(std::string_view bytes) const {
    const auto place = [&](size_t offset) { return concat(name_, ": byte offset ", offset, ": "); };
    if (bytes.size() < kGlbHeaderBytes)
        fail(name_, ": truncated .glb: ", bytes.size(), " bytes, the header alone needs 12");
    const uint32_t version = readLe32(bytes, 4);
    if (version != 2) fail(place(4), "GLB version ", version, " (only version 2 is supported)");
    const uint32_t length = readLe32(bytes, 8);
    if (length > bytes.size())
        fail(name_, ": truncated .glb: the header announces ", length, " bytes, the file has ",
             bytes.size());
    if (length < kGlbHeaderBytes + kGlbChunkHeaderBytes)
        fail(place(kGlbHeaderBytes), "the .glb has no JSON chunk");
    const uint32_t jsonLength = readLe32(bytes, 12);
    if (readLe32(bytes, 16) != kGlbJsonChunk)
        fail(place(16), "the first chunk of a .glb must be JSON");
    const uint64_t jsonEnd = uint64_t(kGlbHeaderBytes + kGlbChunkHeaderBytes) + jsonLength;
    if (jsonEnd > length)
        fail(place(12), "truncated .glb: the JSON chunk announces ", jsonLength, " bytes, only ",
             length - kGlbHeaderBytes - kGlbChunkHeaderBytes, " follow");
    if (jsonEnd < length) {
        const size_t bin = static_cast<size_t>(jsonEnd);
        if (bin + kGlbChunkHeaderBytes > length)
            fail(place(bin), "truncated .glb: incomplete chunk header");
        const uint32_t binLength = readLe32(bytes, bin);
        if (readLe32(bytes, bin + 4) != kGlbBinChunk)
            fail(place(bin + 4), "the second chunk of a .glb must be BIN");
        if (uint64_t(bin) + kGlbChunkHeaderBytes + binLength > length)
            fail(place(bin), "truncated .glb: the BIN chunk announces ", binLength, " bytes, only ",
                 length - bin - kGlbChunkHeaderBytes, " follow");
    }
    return length;
}

void GltfReader::checkExtensions() {
    const auto supported = [](const std::string& name) {
        return std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), name) !=
               std::end(kSupportedExtensions);
    };
    for (const std::string& name : model_.extensionsRequired) {
        if (!supported(name))
            fail(name_, ": requires the glTF extension '", name,
                 "', which strahl does not support");
    }
    std::string ignored;
    for (const std::string& name : model_.extensionsUsed) {
        if (!supported(name)) ignored += (ignored.empty() ? "" : ", ") + name;
    }
    if (!ignored.empty()) meshio::warn(name_ + ": ignoring the glTF extensions " + ignored);
}

}  // namespace strahl::meshio::gltf
