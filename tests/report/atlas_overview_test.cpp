// atlas.png (report/detail/atlas_overview.h) keeps its texts off the surface: the direction
// letters at the panels' edges sit in the panels' margins, and a close-up's title has its own
// strip above the picture (issue 26: "+x" lay on the outline of the panels from ±z, the
// close-up's title on the surface).
#include "report/detail/atlas_overview.h"

#include "mesh/phantom.h"
#include "render/renderer.h"
#include "report/detail/canvas.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

// Surface pixels of the layout inside `box` (clipped to the sheet).
int surface_pixels_in(const detail::OverviewLayout& layout, const detail::PixelBox& box) {
    int n = 0;
    for (int y = std::max(box.y0, 0); y < std::min(box.y1, layout.height); ++y)
        for (int x = std::max(box.x0, 0); x < std::min(box.x1, layout.width); ++x)
            n += layout.surface[static_cast<std::size_t>(y * layout.width + x)];
    return n;
}

// The quick start's pair (README): a condyle with a 0.3 mm dent of radius 2 at (2, −1, 8.8),
// here as the fields the atlas shows, without a sweep.
TEST(AtlasOverview, EdgeLettersAndCloseUpTitlesKeepOffTheSurface) {
    const Mesh mesh = make_phantom({.kind = PhantomKind::Condyle});
    const Vec3d dent(2, -1, 8.8);
    constexpr double kRadius = 2.0, kDepth = 0.3;
    std::vector<float> distance;
    std::vector<std::int32_t> region;
    std::vector<std::uint8_t> seen(mesh.positions.size(), 1);
    Region r{.id = 1, .area = 8.4, .peak_depth = -kDepth, .centroid = dent};
    for (const auto& p : mesh.positions) {
        const double d = (p.cast<double>() - dent).norm();
        const bool in = d < kRadius;
        distance.push_back(in ? static_cast<float>(-kDepth * (1.0 - d / kRadius)) : 0.0f);
        region.push_back(in ? 1 : 0);
        r.vertex_count += in ? 1u : 0u;
    }
    ASSERT_GT(r.vertex_count, 0u);
    const std::vector<Region> regions{r};
    const detail::SurfaceFields fields{distance, region, seen};
    const detail::LegendContent legend{.limit = kDepth, .unit = "mm"};
    const SweepPlan plan;
    detail::OverviewLayout layout;
    Renderer renderer(mesh, RenderOptions{.backend = Backend::Embree, .supersample = 2});
    const std::string png = detail::atlas_overview_png(renderer, {.mesh = &mesh,
                                                                  .fields = &fields,
                                                                  .legend = &legend,
                                                                  .limit = kDepth,
                                                                  .regions = &regions,
                                                                  .plan = &plan,
                                                                  .coverage = 1.0,
                                                                  .name = "ref.ply",
                                                                  .unit = "mm",
                                                                  .layout = &layout});
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "atlas_overview";
    fs::create_directories(dir);
    std::ofstream(dir / "atlas.png", std::ios::binary) << png;  // to look at when this fails

    ASSERT_EQ(layout.surface.size(), static_cast<std::size_t>(layout.width * layout.height));
    EXPECT_GT(std::count(layout.surface.begin(), layout.surface.end(), 1), 6 * 10000);
    ASSERT_EQ(layout.letters.size(), 6u * 3u);   // up, left and right on each direction
    ASSERT_EQ(layout.captions.size(), 6u + 1u);  // each direction and the one close-up
    for (std::size_t i = 0; i < layout.letters.size(); ++i)
        EXPECT_EQ(surface_pixels_in(layout, layout.letters[i]), 0)
            << "edge letter " << i % 3 << " of panel " << i / 3 << " lies on the surface";
    for (std::size_t i = 0; i < layout.captions.size(); ++i)
        EXPECT_EQ(surface_pixels_in(layout, layout.captions[i]), 0)
            << (i < 6 ? "caption of panel " : "title of close-up ") << (i < 6 ? i : i - 6)
            << " lies on the surface";
    // The close-up is filled with surface: its title lies above the picture.
    const detail::PixelBox& title = layout.captions.back();
    EXPECT_GT(surface_pixels_in(layout, {title.x0, title.y1, title.x1, title.y1 + 240}), 0);
}

}  // namespace
}  // namespace glint
