// libFuzzer harness: a NRRD (.nrrd: header and voxels in one file) read with ITK through
// read_volume, then, when the volume is small, its iso-surface at the middle of the value range
// through VTK, so hostile geometry (zero, negative or huge spacing, a singular direction)
// reaches extraction.
#include "fuzz/fuzz_common.h"
#include "fuzz/fuzz_volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".nrrd", "", data, size, [](const std::filesystem::path& path) {
        const glint::Volume volume = glint::read_volume(path, glint::fuzz::kMaxVoxels);
        glint::fuzz::extract_small(volume);
    });
}
