// libFuzzer harness: calibration.json (scanner/calibrate.h read_calibration).
#include "fuzz/fuzz_common.h"
#include "scanner/calibrate.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".json", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::read_calibration(path);
    });
}
