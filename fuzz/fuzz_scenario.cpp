// libFuzzer harness: scenario TOML (scenario/scenario.h load_scenario: sections, keys, options).
#include "fuzz/fuzz_common.h"
#include "scenario/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".toml", "", data, size, [](const std::filesystem::path& path) {
        (void)glint::load_scenario(path, path.parent_path());
    });
}
