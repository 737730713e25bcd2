// MappedFile: open, check that the file is regular, map it read-only.

#include "strahl/meshio/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "strahl/core/error.h"
#include "text_scan.h"

namespace fs = std::filesystem;

namespace strahl::meshio {

namespace {

// Closes the descriptor on every path out of the constructor; the mapping
// stays valid after close.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

MappedFile::MappedFile(const fs::path& file) {
    refuseSpecialFile(file);  // before open(): opening a FIFO would block

    errno = 0;
    const Descriptor d{::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY)};
    if (d.fd < 0) fail(file.string(), ": cannot open: ", std::strerror(errno));
    struct stat st {};
    if (::fstat(d.fd, &st) != 0) fail(file.string(), ": cannot open: ", std::strerror(errno));
    if (S_ISDIR(st.st_mode)) fail(file.string(), ": cannot open: ", std::strerror(EISDIR));
    if (!S_ISREG(st.st_mode)) fail(file.string(), ": cannot open: not a regular file");
    if (st.st_size == 0) return;  // mmap refuses a length of 0

    size_ = static_cast<size_t>(st.st_size);
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, d.fd, 0);
    if (p == MAP_FAILED) fail(file.string(), ": cannot map: ", std::strerror(errno));
    data_ = p;
    // The decoders read the mapping front to back in as many streams as there
    // are threads: ask the kernel to read ahead (a hint; failure is harmless).
    ::madvise(data_, size_, MADV_WILLNEED);
}

MappedFile::~MappedFile() {
    if (data_) ::munmap(data_, size_);
}

}  // namespace strahl::meshio
