#pragma once
// Arrays equal bit for bit (memcmp: -0 and 0 differ, as they should when two
// loaders must produce the same mesh). Empty arrays are equal without calling
// memcmp, whose pointers must not be null even for a length of 0.

#include <cstring>
#include <vector>

namespace strahl::test {

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace strahl::test
