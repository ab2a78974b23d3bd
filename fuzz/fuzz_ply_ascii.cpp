// libFuzzer harness: ASCII PLY (the input follows a fixed "ply / format ascii" start).
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::load_mesh_input(".ply", "ply\nformat ascii 1.0\n", data, size);
}
