// Buffer views and accessors: each checked against its buffer (type, component
// type, stride, range, sparse substitution) before anything is read, then read
// as numbers, normalized integers mapped as the glTF specification says.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

#include "gltf_reader.h"

namespace strahl::meshio::gltf {

namespace {

std::string componentTypeName(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "byte";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "unsigned byte";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "unsigned short";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "unsigned int";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "float";
        default:
            return concat("component type ", type);
    }
}

std::string typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return concat("type ", type);
    }
}

size_t componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
    }
}

// Only the accessor types the loader reads (SCALAR, VEC2, VEC3).
size_t componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        default:
            return 0;
    }
}

// One component as a number: floats as they are, normalized integers mapped
// onto [0, 1] (unsigned) or [-1, 1] (signed) as the glTF specification says,
// other integers as their value.
double readComponent(const unsigned char* p, int componentType, bool normalized) {
    const auto load = [p]<typename T>(T) {
        T value;
        std::memcpy(&value, p, sizeof value);
        return value;
    };
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return double(load(float{}));
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return double(load(uint32_t{}));
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const double v = load(uint8_t{});
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double v = load(uint16_t{});
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double v = load(int8_t{});
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double v = load(int16_t{});
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        default:
            return 0.0;  // excluded by checkAccessor
    }
}

}  // namespace

size_t GltfReader::totalBufferBytes() const {
    size_t total = 0;
    for (const tinygltf::Buffer& b : model_.buffers) total += b.data.size();
    return total;
}

// Buffer view `view` checked against its buffer; returns its first byte.
const unsigned char* GltfReader::checkedView(int view, const std::string& place) const {
    if (view < 0 || size_t(view) >= model_.bufferViews.size())
        error(place, ": buffer view ", view, " does not exist (", model_.bufferViews.size(),
              " buffer views)");
    const tinygltf::BufferView& v = model_.bufferViews[size_t(view)];
    if (v.buffer < 0 || size_t(v.buffer) >= model_.buffers.size())
        error(place, ": buffer view ", view, " refers to buffer ", v.buffer,
              ", which does not exist (", model_.buffers.size(), " buffers)");
    const std::vector<unsigned char>& data = model_.buffers[size_t(v.buffer)].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
        error(place, ": buffer view ", view, " (", v.byteLength, " bytes from offset ",
              v.byteOffset, ") reads past the end of buffer ", v.buffer, " (", data.size(),
              " bytes)");
    return data.data() + v.byteOffset;
}

// `bytes` bytes from `offset` of buffer view `view`, or an error naming `what`.
const unsigned char* GltfReader::viewRange(int view, size_t offset, size_t bytes,
                                           const std::string& place,
                                           const std::string& what) const {
    const unsigned char* start = checkedView(view, place);
    const size_t length = model_.bufferViews[size_t(view)].byteLength;
    if (offset > length || bytes > length - offset)
        error(place, ": ", what, " reads past the end of buffer view ", view, " (", bytes,
              " bytes from offset ", offset, ", the view has ", length, ")");
    return start + offset;
}

// Accessor `index` as the `role` ("POSITION", "indices") of the primitive at
// `place`, checked for its type, component type, buffer view and range.
CheckedAccessor GltfReader::checkAccessor(int index, const std::string& place,
                                          const std::string& role, std::initializer_list<int> types,
                                          std::initializer_list<ComponentRule> rules) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        error(place, ": ", role, " accessor ", index, " does not exist (", model_.accessors.size(),
              " accessors)");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    CheckedAccessor c;
    c.index = index;
    c.subject = concat(place, ": ", role, " accessor ", index);
    if (std::find(types.begin(), types.end(), a.type) == types.end()) {
        std::string expected;
        for (int t : types) expected += (expected.empty() ? "" : " or ") + typeName(t);
        error(c.subject, " is ", typeName(a.type), ", expected ", expected);
    }
    bool allowed = false;
    for (const ComponentRule& r : rules)
        allowed = allowed || (a.componentType == r.componentType && a.normalized == r.normalized);
    if (!allowed) {
        std::string expected;
        for (const ComponentRule& r : rules)
            expected += concat(expected.empty() ? "" : " or ", r.normalized ? "normalized " : "",
                               componentTypeName(r.componentType));
        error(c.subject, " holds ", a.normalized ? "normalized " : "",
              componentTypeName(a.componentType), " values, expected ", expected);
    }

    c.accessor = &a;
    c.count = a.count;
    c.components = componentCount(a.type);
    c.elementBytes = c.components * componentBytes(a.componentType);
    if (a.bufferView >= 0) {
        const unsigned char* start = checkedView(a.bufferView, c.subject);
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        c.stride = view.byteStride != 0 ? view.byteStride : c.elementBytes;
        if (c.stride < c.elementBytes)
            error(c.subject, ": buffer view ", a.bufferView, " has byteStride ", view.byteStride,
                  ", less than its ", c.elementBytes, "-byte elements");
        // The last element must end inside the view. Computed without overflow,
        // so an absurd count fails here, before anything is allocated.
        const size_t length = view.byteLength;
        const bool fits =
            c.count == 0 || (a.byteOffset <= length && length - a.byteOffset >= c.elementBytes &&
                             c.count - 1 <= (length - a.byteOffset - c.elementBytes) / c.stride);
        if (!fits)
            error(c.subject, " reads past the end of buffer view ", a.bufferView, " (", c.count,
                  " elements of ", c.elementBytes, " bytes, stride ", c.stride, ", from offset ",
                  a.byteOffset, "; the view has ", length, " bytes)");
        c.data = start + a.byteOffset;
    } else if (c.count > totalBufferBytes() / c.elementBytes) {
        // Without a buffer view the elements are zeros (plus sparse values), so
        // no data bounds the count: one larger than all the file's bytes is a lie.
        error(c.subject, " has no buffer view and claims ", c.count,
              " elements, more than all buffers of the file hold (", totalBufferBytes(), " bytes)");
    }
    if (a.sparse.isSparse) checkSparse(c);
    return c;
}

void GltfReader::checkSparse(CheckedAccessor& c) const {
    const auto& s = c.accessor->sparse;
    if (s.count < 1 || size_t(s.count) > c.count)
        error(c.subject, ": sparse count ", s.count, " is not in 1..", c.count);
    const size_t n = size_t(s.count);
    const int indexType = s.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        error(c.subject, ": sparse indices hold ", componentTypeName(indexType),
              " values, expected unsigned byte, short or int");
    if (s.indices.byteOffset < 0 || s.values.byteOffset < 0)
        error(c.subject, ": negative sparse byteOffset");
    c.sparseCount = n;
    c.sparseIndexType = indexType;
    c.sparseIndices = viewRange(s.indices.bufferView, size_t(s.indices.byteOffset),
                                n * componentBytes(indexType), c.subject, "sparse indices");
    c.sparseValues = viewRange(s.values.bufferView, size_t(s.values.byteOffset), n * c.elementBytes,
                               c.subject, "sparse values");
}

// All elements of `c` as T, components interleaved, with the sparse values
// substituted.
template <typename T>
std::vector<T> GltfReader::readAccessor(const CheckedAccessor& c) const {
    const tinygltf::Accessor& a = *c.accessor;
    const size_t componentSize = componentBytes(a.componentType);
    std::vector<T> out(c.count * c.components, T(0));
    const auto readElement = [&](const unsigned char* p, size_t element) {
        for (size_t k = 0; k < c.components; ++k)
            out[element * c.components + k] =
                static_cast<T>(readComponent(p + k * componentSize, a.componentType, a.normalized));
    };
    if (c.data != nullptr) {
        for (size_t i = 0; i < c.count; ++i) readElement(c.data + i * c.stride, i);
    }
    const size_t indexSize = componentBytes(c.sparseIndexType);
    size_t previous = 0;
    for (size_t j = 0; j < c.sparseCount; ++j) {
        const auto target = static_cast<size_t>(
            readComponent(c.sparseIndices + j * indexSize, c.sparseIndexType, false));
        if (target >= c.count || (j > 0 && target <= previous))
            error(c.subject, ": sparse index ", target, " (entry ", j,
                  ") is out of range or not increasing (", c.count, " elements)");
        readElement(c.sparseValues + j * c.elementBytes, target);
        previous = target;
    }
    return out;
}

// The two element types read: float attributes and uint32_t indices.
template std::vector<float> GltfReader::readAccessor<float>(const CheckedAccessor&) const;
template std::vector<uint32_t> GltfReader::readAccessor<uint32_t>(const CheckedAccessor&) const;

std::vector<float> GltfReader::readFinite(const CheckedAccessor& c) const {
    std::vector<float> values = readAccessor<float>(c);
    for (size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i]))
            error(c.subject, ": element ", i / c.components, " is not finite");
    }
    return values;
}

}  // namespace strahl::meshio::gltf
