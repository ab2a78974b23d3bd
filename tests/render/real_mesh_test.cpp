// A real mesh (the ArtiSynth mandible, CT-derived): both backends agree on it, and its frames
// are written as PNGs into the test output folder for people to look at.
#include "mesh/io.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "render/view.h"
#include "tests/render/render_test_util.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

namespace glint::test {
namespace {

namespace fs = std::filesystem;

TEST(RealMesh, MandibleRendersAlikeOnBothBackends) {
    const fs::path path =
        fs::path(GLINT_SHARED_DATA_DIR) / "mandible_cbct_artisynth" / "jaw_smooth.obj";
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const LoadedMesh loaded = load_mesh(path);
    const Mesh& mesh = loaded.mesh;
    Renderer vk(mesh, test_options(Backend::Vulkan, 2));
    Renderer em(mesh, test_options(Backend::Embree, 2));
    std::vector<View> views;
    const double az[] = {0, 90, 180, 270, 45, 225};
    const double el[] = {0, 0, 0, 0, 60, -45};
    for (int i = 0; i < 6; ++i) {
        views.push_back(make_view(mesh, ViewSpec{.azimuth_deg = az[i],
                                                 .elevation_deg = el[i],
                                                 .width = 256,
                                                 .height = 256,
                                                 .index = i}));
    }
    const fs::path out = fs::path(GLINT_TEST_OUTPUT_DIR) / "render";
    fs::create_directories(out);
    std::vector<Frame> vk_frames(views.size());
    vk.render_views(views, [&](std::size_t i, const Frame& f) {
        vk_frames[i] = f;
        const std::string stem = (out / ("jaw_view" + std::to_string(i))).string();
        write_frame_image(stem + "_normal.png", f, views[i]);
        write_frame_image(stem + "_reflection.png", f, views[i],
                          FrameImageOptions{.shade = {.mode = ShadeMode::Reflection}});
        write_frame_image(stem + "_zebra.png", f, views[i],
                          FrameImageOptions{.shade = {.mode = ShadeMode::Zebra}});
    });
    std::size_t both = 0, within = 0, only_one = 0;
    em.render_views(views, [&](std::size_t i, const Frame& f) {
        const Frame& v = vk_frames[i];
        for (std::size_t p = 0; p < f.pixel_count(); ++p) {
            if (f.is_covered(p) != v.is_covered(p)) ++only_one;
            if (!(f.is_covered(p) && v.is_covered(p))) continue;
            ++both;
            if (angle_deg(pixel_normal(f, p).cast<double>(), pixel_normal(v, p).cast<double>()) <=
                0.5)
                ++within;
        }
    });
    const double share = static_cast<double>(within) / static_cast<double>(both);
    std::printf("[mandible] %zu triangles, both=%zu within0.5=%.5f only_one=%zu\n",
                mesh.triangle_count(), both, share, only_one);
    EXPECT_GT(both, 20000u);
    EXPECT_GE(share, 0.995);
    EXPECT_LE(static_cast<double>(only_one), 0.005 * static_cast<double>(both));
    expect_no_validation_messages(vk);
}

}  // namespace
}  // namespace glint::test
