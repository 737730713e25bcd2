#pragma once
// Loading one binary PLY scalar from unaligned bytes, in the host's byte order
// or swapped (binary_big_endian on a little-endian host and vice versa).

#include <bit>
#include <cstdint>
#include <cstring>

#include "ply_header.h"

namespace strahl::meshio::ply {

template <typename U>
U byteSwap(U v) {
    U out = 0;
    for (size_t i = 0; i < sizeof(U); ++i) {
        out = static_cast<U>((out << 8) | (v & 0xff));
        v = static_cast<U>(v >> 8);
    }
    return out;
}

// The value of type T whose bytes (Bits wide) start at p.
template <bool kSwap, typename T, typename Bits>
T loadAs(const char* p) {
    Bits bits;
    std::memcpy(&bits, p, sizeof bits);
    if constexpr (kSwap) bits = byteSwap(bits);
    return std::bit_cast<T>(bits);
}

// An integer scalar (t must be an integer type).
template <bool kSwap>
int64_t loadInteger(const char* p, Scalar t) {
    switch (t) {
        case Scalar::Int8:
            return loadAs<kSwap, int8_t, uint8_t>(p);
        case Scalar::UInt8:
            return loadAs<kSwap, uint8_t, uint8_t>(p);
        case Scalar::Int16:
            return loadAs<kSwap, int16_t, uint16_t>(p);
        case Scalar::UInt16:
            return loadAs<kSwap, uint16_t, uint16_t>(p);
        case Scalar::Int32:
            return loadAs<kSwap, int32_t, uint32_t>(p);
        case Scalar::UInt32:
            return loadAs<kSwap, uint32_t, uint32_t>(p);
        default:
            return 0;  // not an integer type: ruled out by the header checks
    }
}

// Any scalar, as the generic reader converts it: through double.
template <bool kSwap>
double loadReal(const char* p, Scalar t) {
    switch (t) {
        case Scalar::Float32:
            return loadAs<kSwap, float, uint32_t>(p);
        case Scalar::Float64:
            return loadAs<kSwap, double, uint64_t>(p);
        default:
            return static_cast<double>(loadInteger<kSwap>(p, t));
    }
}

}  // namespace strahl::meshio::ply
