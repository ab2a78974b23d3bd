// The value types of VTK legacy files: their names, sizes and big-endian loads (the VTK
// reader's vocabulary, apart from its parser).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace glint::detail {

enum class VtkType {
    Bit,
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Float32,
    Float64,
    String
};

/// The type a DATATYPE word names (any case), nullopt for one glint does not know.
[[nodiscard]] std::optional<VtkType> parse_vtk_type(std::string_view word);

/// Bytes of one binary value; 0 for Bit and String.
[[nodiscard]] std::size_t size_of(VtkType t);

/// a·b, saturating instead of wrapping (counts come from the file).
[[nodiscard]] std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b);

[[nodiscard]] bool is_integer(VtkType t);

/// One big-endian binary value at p (VTK legacy binary is always big endian).
[[nodiscard]] double load_value(const char* p, VtkType t);

}  // namespace glint::detail
