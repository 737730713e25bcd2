#pragma once
// A read-only memory mapping of a whole regular file (POSIX mmap, MAP_PRIVATE),
// unmapped when the object goes away. The PLY loader decodes straight from it
// and the pbrt importer tokenizes its included files in place: no copy of the
// file, and several threads can read it at once.

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace strahl::meshio {

class MappedFile {
public:
    // Throws "file: cannot open: <strerror>" when the file is missing or
    // unreadable, and "file: cannot open: not a regular file" for a device,
    // FIFO or socket (the same messages as readWholeFile). An empty file maps
    // to an empty view.
    explicit MappedFile(const std::filesystem::path& file);
    ~MappedFile();
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;

    std::string_view bytes() const { return {static_cast<const char*>(data_), size_}; }

private:
    void* data_ = nullptr;
    size_t size_ = 0;
};

}  // namespace strahl::meshio
