// libFuzzer harness: VTK legacy POLYDATA (our reader).
#include "fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::load_mesh_input(".vtk", "", data, size);
}
