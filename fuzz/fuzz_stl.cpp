// libFuzzer harness: STL, ASCII and binary (load_mesh with an .stl name).
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::load_mesh_input(".stl", "", data, size);
}
