// libFuzzer harness: a NumPy .npy ground-truth mask (scenario key truth_mask) read by
// read_npy_mask.
#include "fuzz/fuzz_common.h"
#include "scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".npy", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::read_npy_mask(path);
    });
}
