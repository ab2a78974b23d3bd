// libFuzzer harness: calibration.json (analysis/calibrate.h read_calibration).
#include "fuzz/fuzz_common.h"
#include "report/calibration_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".json", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::read_calibration(path);
    });
}
