// libFuzzer harness: a DICOM folder. The input is cut at each "--slice--" into up to four
// files of one folder, which read_volume reads as a series (the DICOM checks, then GDCM
// through ITK), then, when the volume is small, its iso-surface (issue 23: "DICOM checked
// before GDCM sees it"; a truncated file used to abort in a GDCM assertion).
#include "fuzz/fuzz_common.h"
#include "fuzz/fuzz_volume.h"

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace {

std::filesystem::path write_series(const std::uint8_t* data, std::size_t size) {
    namespace fs = std::filesystem;
    const fs::path dir =
        fs::temp_directory_path() / ("glint-fuzz-dicom-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    constexpr std::string_view kCut = "--slice--";
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    std::size_t start = 0;
    for (int n = 0; n < 4 && start <= all.size(); ++n) {
        const std::size_t cut = n == 3 ? std::string_view::npos : all.find(kCut, start);
        const std::string_view part =
            all.substr(start, cut == std::string_view::npos ? std::string_view::npos : cut - start);
        std::FILE* f = std::fopen((dir / ("slice" + std::to_string(n) + ".dcm")).c_str(), "wb");
        if (f == nullptr) std::abort();
        if (!part.empty()) std::fwrite(part.data(), 1, part.size(), f);
        std::fclose(f);
        if (cut == std::string_view::npos) break;
        start = cut + kCut.size();
    }
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto dir = write_series(data, size);
    try {
        const glint::Volume volume = glint::read_volume(dir, glint::fuzz::kMaxVoxels);
        glint::fuzz::extract_small(volume);
    } catch (const glint::Error&) {
        // refused with a message: what hostile input should get
    }
    return 0;
}
