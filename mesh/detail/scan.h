// Byte and text scanning shared by glint's own mesh readers (PLY, STL, VTK) and the checks
// made before assimp sees a file: endian-aware loads, line and word splitting, and the limits
// every reader applies before it allocates or loops (counts against the bytes left, the
// triangle budget, cancellation).
#pragma once

#include "mesh/cancel.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace glint::detail {

/// Reads a T stored at `p` (any alignment); byte-swapped when `Swap` (the file's byte order
/// differs from the machine's, which is little endian wherever glint runs).
template <class T, bool Swap>
T load_bytes(const char* p) {
    if constexpr (sizeof(T) == 1) {
        T v;
        std::memcpy(&v, p, 1);
        return v;
    } else {
        using U =
            std::conditional_t<sizeof(T) == 2, std::uint16_t,
                               std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>;
        U u;
        std::memcpy(&u, p, sizeof(U));
        if constexpr (Swap) {
            if constexpr (sizeof(U) == 2) u = static_cast<U>(__builtin_bswap16(u));
            if constexpr (sizeof(U) == 4) u = __builtin_bswap32(u);
            if constexpr (sizeof(U) == 8) u = __builtin_bswap64(u);
        }
        return std::bit_cast<T>(u);
    }
}

/// `v` converted to an integer type, clamped to its range (NaN gives 0): a file's value
/// outside the range must not be undefined behaviour; the reader reports it as an index or
/// label that is out of range instead.
template <class Int>
Int clamp_to(double v) {
    constexpr double lo = static_cast<double>(std::numeric_limits<Int>::min());
    constexpr double hi = static_cast<double>(std::numeric_limits<Int>::max());
    if (!(v == v)) return 0;
    if (v <= lo) return std::numeric_limits<Int>::min();
    if (v >= hi) return std::numeric_limits<Int>::max();
    return static_cast<Int>(v);
}

/// The line of `data` starting at `pos` (without '\n' and a trailing '\r'); advances `pos`
/// past it. False at the end of the data.
bool next_line(std::span<const char> data, std::size_t& pos, std::string_view& line);

/// Words of a line separated by spaces, tabs or '\r'.
[[nodiscard]] std::vector<std::string_view> split_words(std::string_view line);

/// ASCII case-insensitive equality (keywords such as "facet" / "FACET").
[[nodiscard]] bool iequals(std::string_view a, std::string_view b);

/// `s` cut to `max` characters with control and non-ASCII bytes shown as '?' (for messages).
[[nodiscard]] std::string printable(std::string_view s, std::size_t max = 40);

/// Polls cancellation every 4096 iterations of a reader loop.
/// \throw Cancelled once SIGINT / SIGTERM arrived
inline void poll_cancel(std::uint64_t i) {
    if ((i & 0xFFFu) == 0) throw_if_cancelled();
}

/// Refuses a declared count the remaining bytes cannot hold: each of the `count` items needs at
/// least `min_bytes`. Checked before any allocation or loop over the count.
/// \throw InputError `mesh "<source>": <what> declares N items of at least B bytes each, but
///        only L bytes follow: the file is truncated or the count is wrong`
void check_count_fits(std::uint64_t count, std::uint64_t min_bytes, std::uint64_t bytes_left,
                      const std::string& source, const std::string& what);

/// Refuses more than `max_triangles` triangles (LoadOptions::max_triangles).
/// \throw InputError `mesh "<source>": <what> N triangles, more than the limit M (--max-triangles)`
void check_triangle_budget(std::uint64_t triangles, std::uint64_t max_triangles,
                           const std::string& source, const std::string& what);

}  // namespace glint::detail
