// libFuzzer harness: a glTF whose buffers name files (issue 52). The input is the glTF JSON,
// written into a folder that holds a real buffer below it (bins/data.bin), a FIFO (bins/fifo),
// and a buffer beside the folder (../outside.bin), so fuzzed URIs reach each: a file below the
// glTF is read, one outside it or a FIFO is refused with a message, nothing blocks or crashes.
#include "fuzz/fuzz_common.h"

#include <sys/stat.h>

#include <cstring>
#include <fstream>

namespace {

namespace fs = std::filesystem;

// The per-process folder: <tmp>/glint-fuzz-gltf-<pid>/g/{bins/data.bin, bins/fifo} and
// <tmp>/glint-fuzz-gltf-<pid>/outside.bin; made once.
fs::path folder() {
    static const fs::path root = [] {
        const fs::path r =
            fs::temp_directory_path() / ("glint-fuzz-gltf-" + std::to_string(::getpid()));
        fs::create_directories(r / "g" / "bins");
        // Three positions and three 16-bit indices (the seeds' triangle), 44 bytes.
        const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const std::uint16_t indices[4] = {0, 1, 2, 0};
        for (const fs::path& p : {r / "g" / "bins" / "data.bin", r / "outside.bin"}) {
            std::ofstream out(p, std::ios::binary);
            out.write(reinterpret_cast<const char*>(positions), sizeof positions);
            out.write(reinterpret_cast<const char*>(indices), sizeof indices);
        }
        ::mkfifo((r / "g" / "bins" / "fifo").c_str(), 0600);
        return r;
    }();
    return root / "g";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const fs::path path = folder() / "scene.gltf";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        (void)glint::load_mesh(
            path, glint::LoadOptions{.allow_points_only = true, .max_triangles = 1'000'000});
    } catch (const glint::Error&) {
        // refused with a message: what hostile input should get
    }
    return 0;
}
