// The PLY format's vocabulary for the PLY reader: value types, the header's elements and
// properties, and the loads of binary values in either byte order.
#pragma once

#include "mesh/detail/scan.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glint::detail::ply {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

inline std::size_t size_of(Type t) {
    switch (t) {
        case Type::Int8:
        case Type::UInt8: return 1;
        case Type::Int16:
        case Type::UInt16: return 2;
        case Type::Int32:
        case Type::UInt32:
        case Type::Float32: return 4;
        case Type::Float64: return 8;
    }
    return 0;
}

inline bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

inline std::optional<Type> parse_type(std::string_view s) {
    if (s == "char" || s == "int8") return Type::Int8;
    if (s == "uchar" || s == "uint8") return Type::UInt8;
    if (s == "short" || s == "int16") return Type::Int16;
    if (s == "ushort" || s == "uint16") return Type::UInt16;
    if (s == "int" || s == "int32") return Type::Int32;
    if (s == "uint" || s == "uint32") return Type::UInt32;
    if (s == "float" || s == "float32") return Type::Float32;
    if (s == "double" || s == "float64") return Type::Float64;
    return std::nullopt;
}

// Where a vertex property's value goes.
enum class Target { Ignore, X, Y, Z, Nx, Ny, Nz, Red, Green, Blue, Label, Scalar, FaceIndices };

struct Property {
    std::string name;
    Type type = Type::Float32;
    bool is_list = false;
    Type count_type = Type::UInt8;
    Target target = Target::Ignore;
    std::size_t scalar_index = 0;  ///< into Mesh::scalars when target == Scalar
    std::size_t offset = 0;        ///< byte offset in a fixed-size binary item
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    bool is_fixed_size = true;  ///< no list property: every item has the same byte size
    std::size_t stride = 0;     ///< bytes per item when is_fixed_size
};

// CloudCompare's name for a scalar field, `scalar_<name>` (glint's atlas writes it: mesh/write.h),
// read back as <name>, unless the element also has a property <name>.
inline std::string scalar_name(const Element& e, const std::string& s) {
    constexpr std::string_view kPrefix = "scalar_";
    if (s.size() <= kPrefix.size() || !s.starts_with(kPrefix)) return s;
    const std::string bare = s.substr(kPrefix.size());
    for (const auto& p : e.properties)
        if (p.name == bare) return s;
    return bare;
}

enum class Encoding { Ascii, BinaryLe, BinaryBe };

template <class T, bool Swap>
T load(const char* p) {
    return load_bytes<T, Swap>(p);
}

template <bool Swap>
double load_value(const char* p, Type t) {
    switch (t) {
        case Type::Int8: return load<std::int8_t, Swap>(p);
        case Type::UInt8: return load<std::uint8_t, Swap>(p);
        case Type::Int16: return load<std::int16_t, Swap>(p);
        case Type::UInt16: return load<std::uint16_t, Swap>(p);
        case Type::Int32: return load<std::int32_t, Swap>(p);
        case Type::UInt32: return load<std::uint32_t, Swap>(p);
        case Type::Float32: return static_cast<double>(load<float, Swap>(p));
        case Type::Float64: return load<double, Swap>(p);
    }
    return 0.0;
}

// Integer value of a list count or index (exact for every PLY integer type).
template <bool Swap>
std::int64_t load_int(const char* p, Type t) {
    switch (t) {
        case Type::Int8: return load<std::int8_t, Swap>(p);
        case Type::UInt8: return load<std::uint8_t, Swap>(p);
        case Type::Int16: return load<std::int16_t, Swap>(p);
        case Type::UInt16: return load<std::uint16_t, Swap>(p);
        case Type::Int32: return load<std::int32_t, Swap>(p);
        case Type::UInt32: return load<std::uint32_t, Swap>(p);
        case Type::Float32: return clamp_to<std::int64_t>(load<float, Swap>(p));
        case Type::Float64: return clamp_to<std::int64_t>(load<double, Swap>(p));
    }
    return 0;
}

}  // namespace glint::detail::ply
