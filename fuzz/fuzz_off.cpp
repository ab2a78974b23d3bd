// libFuzzer harness: OFF through the checks and assimp.
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::load_mesh_input(".off", "", data, size);
}
