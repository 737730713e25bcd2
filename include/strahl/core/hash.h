#pragma once
// 64-bit FNV-1a (Fowler, Noll, Vo): a fast, well-spread hash of bytes, enough
// to tell one file or setting from another and to name cache files; not a
// security measure.

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace strahl {

inline constexpr uint64_t kFnv1aOffsetBasis = 14695981039346656037ull;
inline constexpr uint64_t kFnv1aPrime = 1099511628211ull;

// `hash` continues a previous hash (chained over several pieces).
inline uint64_t fnv1a(const void* data, size_t size, uint64_t hash = kFnv1aOffsetBasis) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        hash ^= p[i];
        hash *= kFnv1aPrime;
    }
    return hash;
}

inline uint64_t fnv1a(std::string_view bytes, uint64_t hash = kFnv1aOffsetBasis) {
    return fnv1a(bytes.data(), bytes.size(), hash);
}

}  // namespace strahl
