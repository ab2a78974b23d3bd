// libFuzzer harness: a views file (glint render --views-file) read and parsed as the command
// does, over a base view, then every view placed around a unit sphere, so that hostile numbers
// (huge, tiny, negative zooms and angles) reach the camera maths (issue 23: views files).
#include "fuzz/fuzz_common.h"
#include "render/view.h"
#include "render/view_list.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return glint::fuzz::read_file(".txt", "", data, size, [](const std::filesystem::path& path) {
        glint::ViewSpec base;
        base.width = 64;
        base.height = 48;
        const auto specs =
            glint::parse_view_list(glint::read_views_file(path.string()), '\n', base, "views file");
        const glint::FramingSphere sphere{};
        for (const auto& spec : specs) (void)glint::make_view(sphere, spec);
    });
}
