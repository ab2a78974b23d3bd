// libFuzzer harness: landmarks JSON (registration/landmarks.h read_landmarks).
#include "fuzz/fuzz_common.h"
#include "registration/landmarks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".json", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::read_landmarks(path.string());
    });
}
