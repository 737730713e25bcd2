// Inflating zlib and gzip streams (inflate.h).

#include "inflate.h"

#include <zlib.h>

#include <algorithm>
#include <limits>

#include "strahl/core/error.h"

namespace strahl::meshio {

namespace {
// Larger than any mesh strahl could hold with its BVH on the machines it runs on.
constexpr size_t kMaxInflatedBytes = size_t(8) << 30;
constexpr size_t kChunk = size_t(1) << 20;
}  // namespace

std::string inflateAll(std::string_view data, const std::string& name, Compression compression) {
    z_stream z{};
    // 15 + 16: the largest window, with gzip's header and trailer.
    const int windowBits = compression == Compression::Gzip ? 15 + 16 : 15;
    if (inflateInit2(&z, windowBits) != Z_OK) fail(name, ": cannot start zlib");
    size_t fed = 0;
    std::string out;
    int status = Z_OK;
    while (status == Z_OK) {
        if (z.avail_in == 0 && fed < data.size()) {
            // zlib counts its input in 32 bits: feed larger inputs in parts.
            const size_t part = std::min<size_t>(data.size() - fed, std::numeric_limits<uInt>::max());
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data() + fed));
            z.avail_in = static_cast<uInt>(part);
            fed += part;
        }
        const size_t done = out.size();
        if (done + kChunk > kMaxInflatedBytes) {
            inflateEnd(&z);
            fail(name, ": the compressed data inflates to more than 8 GiB");
        }
        out.resize(done + kChunk);
        z.next_out = reinterpret_cast<Bytef*>(out.data() + done);
        z.avail_out = static_cast<uInt>(kChunk);
        status = inflate(&z, Z_NO_FLUSH);
        out.resize(out.size() - z.avail_out);
        if (status == Z_BUF_ERROR && z.avail_in == 0 && fed == data.size()) break;  // the input ended first
    }
    const char* message = z.msg;
    inflateEnd(&z);
    if (status != Z_STREAM_END && status != Z_BUF_ERROR)
        fail(name, ": the compressed data is corrupt (zlib: ", message ? message : "error", ")");
    if (status == Z_BUF_ERROR && compression == Compression::Gzip)
        fail(name, ": the compressed data ends early (truncated)");
    return out;
}

}  // namespace strahl::meshio
