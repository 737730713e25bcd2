#pragma once
// The PLY header (elements, properties, encoding) and the layout the loader
// derives from it (which vertex property plays which role, where the face index
// list is). Internal to meshio; the body decoders are ply_sequential.h and
// ply_parallel.h.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "strahl/geometry/mesh_attribute.h"

namespace strahl::meshio::ply {

enum class Scalar : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

constexpr size_t sizeOf(Scalar t) {
    switch (t) {
        case Scalar::Int8:
        case Scalar::UInt8:
            return 1;
        case Scalar::Int16:
        case Scalar::UInt16:
            return 2;
        case Scalar::Int32:
        case Scalar::UInt32:
        case Scalar::Float32:
            return 4;
        case Scalar::Float64:
            return 8;
    }
    return 0;
}

inline bool isInteger(Scalar t) {
    return t != Scalar::Float32 && t != Scalar::Float64;
}

struct Property {
    std::string name;
    Scalar type = Scalar::Float32;  // the item type for a list
    bool isList = false;
    Scalar countType = Scalar::UInt8;
    size_t headerLine = 0;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
    size_t headerLine = 0;

    const Property* find(std::string_view propertyName) const;
    // Bytes of one item in a binary body when no property is a list, else 0.
    size_t fixedBinarySize() const;
    // The fewest bytes one item can take in a binary body (lists empty, or of 3
    // items for `atLeastThree`, the face index list: shorter faces are errors).
    size_t minBinarySize(const Property* atLeastThree) const;
};

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    size_t bodyOffset = 0;     // first byte after the end_header line
    size_t endHeaderLine = 0;  // for errors about the header as a whole
};

// Throws "file: header line N: what".
Header parseHeader(const std::string& file, std::string_view data);

// What each vertex property is used for.
enum Role : int { kSkip = -1, kX, kY, kZ, kNX, kNY, kNZ, kU, kV, kRoleCount };

// A mesh attribute made of scalar properties of one element, one per channel
// (Mitsuba's naming rules: docs/mesh-files.md, "Attributes").
struct AttributeColumns {
    std::string name;              // "vertex_color", "face_weight", ...
    std::vector<size_t> properties;  // indices in the element, in channel order
};

struct Layout {
    const Element* vertex = nullptr;
    const Element* face = nullptr;
    const Property* faceIndices = nullptr;
    // One Role per vertex property; kRoleCount + c for the c-th channel of
    // the vertex attributes, counted in order over vertexAttributes.
    std::vector<int> vertexRoles;
    bool hasNormals = false;
    bool hasUvs = false;
    std::vector<AttributeColumns> vertexAttributes, faceAttributes;
    // One per face property: the channel it fills (counted as for the
    // vertices over faceAttributes), or -1.
    std::vector<int> faceChannels;

    size_t vertexChannels() const { return channelCount(vertexAttributes); }
    size_t faceChannelCount() const { return channelCount(faceAttributes); }
    static size_t channelCount(const std::vector<AttributeColumns>& attributes) {
        size_t n = 0;
        for (const AttributeColumns& a : attributes) n += a.properties.size();
        return n;
    }
};

// An attribute value as Mitsuba reads it: an integer normalised by its type's
// largest value and sRGB-decoded (Mitsuba marks integer PLY properties as
// gamma-encoded), a float as it is.
float attributeValue(double raw, Scalar type);

// The mesh's attributes for the layout's columns, vertex ones first, with no
// values yet (the body readers fill them).
std::vector<MeshAttribute> makeAttributes(const Layout& layout);

// Throws "file: header line N: what" when there is no usable vertex element
// (x, y, z; at most 2^32-1 vertices) or the face element has no integer index list.
Layout makeLayout(const std::string& file, const Header& h);

}  // namespace strahl::meshio::ply
