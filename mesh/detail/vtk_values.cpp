#include "mesh/detail/vtk_values.h"

#include "mesh/detail/scan.h"

#include <string>

namespace glint::detail {

namespace {

// Big-endian load (VTK legacy binary is always big endian).
template <class T>
T load_be(const char* p) {
    return load_bytes<T, true>(p);
}

}  // namespace

std::optional<VtkType> parse_vtk_type(std::string_view s) {
    std::string t(s);
    for (char& c : t) c = static_cast<char>(c | 0x20);  // VTK writes them lower case; accept any
    if (t == "bit") return VtkType::Bit;
    if (t == "char" || t == "signed_char") return VtkType::Int8;
    if (t == "unsigned_char") return VtkType::UInt8;
    if (t == "short") return VtkType::Int16;
    if (t == "unsigned_short") return VtkType::UInt16;
    if (t == "int") return VtkType::Int32;
    if (t == "unsigned_int") return VtkType::UInt32;
    // note: "long" is written with the writer's sizeof(long); VTK's binary files come from
    // LP64 platforms in practice, so 8 bytes. vtkIdType is 64-bit in default VTK builds.
    if (t == "long" || t == "vtktypeint64" || t == "vtkidtype") return VtkType::Int64;
    if (t == "unsigned_long" || t == "vtktypeuint64") return VtkType::UInt64;
    if (t == "float") return VtkType::Float32;
    if (t == "double") return VtkType::Float64;
    if (t == "string" || t == "utf8_string") return VtkType::String;
    return std::nullopt;
}

std::size_t size_of(VtkType t) {
    switch (t) {
        case VtkType::Int8:
        case VtkType::UInt8: return 1;
        case VtkType::Int16:
        case VtkType::UInt16: return 2;
        case VtkType::Int32:
        case VtkType::UInt32:
        case VtkType::Float32: return 4;
        case VtkType::Int64:
        case VtkType::UInt64:
        case VtkType::Float64: return 8;
        case VtkType::Bit:
        case VtkType::String: return 0;
    }
    return 0;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

bool is_integer(VtkType t) {
    return t != VtkType::Float32 && t != VtkType::Float64 && t != VtkType::String;
}

double load_value(const char* p, VtkType t) {
    switch (t) {
        case VtkType::Int8: return load_be<std::int8_t>(p);
        case VtkType::UInt8: return load_be<std::uint8_t>(p);
        case VtkType::Int16: return load_be<std::int16_t>(p);
        case VtkType::UInt16: return load_be<std::uint16_t>(p);
        case VtkType::Int32: return load_be<std::int32_t>(p);
        case VtkType::UInt32: return load_be<std::uint32_t>(p);
        case VtkType::Int64: return static_cast<double>(load_be<std::int64_t>(p));
        case VtkType::UInt64: return static_cast<double>(load_be<std::uint64_t>(p));
        case VtkType::Float32: return static_cast<double>(load_be<float>(p));
        case VtkType::Float64: return load_be<double>(p);
        case VtkType::Bit:
        case VtkType::String: return 0.0;
    }
    return 0.0;
}

}  // namespace glint::detail
