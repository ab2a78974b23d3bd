// libFuzzer harness: binary PLY. The first input byte picks the byte order (even: little,
// odd: big endian); the rest follows "ply / format binary_… 1.0" (elements, end_header, body).
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const bool big = (data[0] & 1) != 0;
    return glint::fuzz::load_mesh_input(
        ".ply",
        big ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n",
        data + 1, size - 1);
}
