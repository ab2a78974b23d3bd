// libFuzzer harness: fit.json (registration/fit_io.h read_fit).
#include "fuzz/fuzz_common.h"
#include "registration/fit_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".json", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::read_fit(path.string());
    });
}
