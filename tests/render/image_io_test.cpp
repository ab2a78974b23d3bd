// Frames written as EXR / PNG through OpenImageIO, read back with their metadata; shading
// modes; the golden EXR of a lavapipe sphere.
#include "render/image_io.h"

#include "mesh/error.h"
#include "render/renderer.h"
#include "render/shade.h"
#include "tests/render/render_test_util.h"
#include "tests/render/test_meshes.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace glint::test {
namespace {

namespace fs = std::filesystem;

fs::path output_dir() {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "render";
    fs::create_directories(dir);
    return dir;
}

struct Rendered {
    Frame frame;
    View view;
};

/// `device` names the Vulkan device ("" = the default choice).
Rendered sphere_frame(Backend backend, int size, int s, const std::string& device = "") {
    const Mesh mesh = make_icosphere(4);
    RenderOptions o = test_options(backend, s);
    o.device = device;
    Renderer r(mesh, o);
    Rendered out;
    out.view = make_view(
        mesh, ViewSpec{.azimuth_deg = 30, .elevation_deg = 20, .width = size, .height = size});
    out.frame = r.render(out.view);
    expect_no_validation_messages(r);
    return out;
}

TEST(FrameImage, ExrKeepsTheFloatNumbersAndTheMetadata) {
    const Rendered r = sphere_frame(Backend::Embree, 48, 2);
    const fs::path path = output_dir() / "sphere_frame.exr";
    write_frame_image(path, r.frame, r.view, FrameImageOptions{.metadata = {{"device", "test"}}});
    OIIO::ImageBuf buf(path.string());
    ASSERT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << buf.geterror();
    const OIIO::ImageSpec& spec = buf.spec();
    ASSERT_EQ(spec.nchannels, 9);
    // OpenEXR orders channels by name on disk: look them up by name.
    const int nx = spec.channelindex("N.x");
    const int z = spec.channelindex("Z");
    const int id = spec.channelindex("id");
    const int red = spec.channelindex("R");
    ASSERT_GE(std::min({nx, z, id, red}), 0);
    EXPECT_EQ(spec.get_string_attribute("glint:mode"), "normal");
    EXPECT_EQ(spec.get_string_attribute("glint:device"), "test");
    EXPECT_EQ(std::stod(spec.get_string_attribute("glint:azimuth_deg")), 30.0);
    const int x = 24, y = 24;
    const std::size_t p = static_cast<std::size_t>(y * 48 + x);
    float px[9];
    buf.getpixel(x, y, px, 9);
    EXPECT_EQ(px[nx], r.frame.normal[3 * p]);  // float channels: bit-exact
    EXPECT_EQ(px[z], r.frame.depth[p]);
    EXPECT_EQ(static_cast<std::uint32_t>(px[id]), r.frame.primitive_id[p]);
    EXPECT_FLOAT_EQ(px[red], 0.5f * r.frame.normal[3 * p] + 0.5f);
}

TEST(FrameImage, PngIsTheEightBitPaperColour) {
    const Rendered r = sphere_frame(Backend::Embree, 40, 1);
    const fs::path path = output_dir() / "sphere_frame_paper8.png";
    write_frame_image(path, r.frame, r.view,
                      FrameImageOptions{.shade = {.mode = ShadeMode::Paper8}});
    OIIO::ImageBuf buf(path.string());
    ASSERT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::UINT8)) << buf.geterror();
    ASSERT_EQ(buf.spec().nchannels, 4);
    const std::size_t p = 20 * 40 + 20;
    unsigned char px[4];
    buf.get_pixels(OIIO::ROI(20, 21, 20, 21, 0, 1, 0, 4), OIIO::TypeDesc::UINT8, px);
    for (int c = 0; c < 3; ++c) {
        const float v = 0.5f * r.frame.normal[3 * p + static_cast<std::size_t>(c)] + 0.5f;
        EXPECT_EQ(px[c], static_cast<unsigned char>(std::lround(255.0f * v)));
    }
    EXPECT_EQ(px[3], 255);
}

TEST(FrameImage, RejectsUnknownExtensionAndUnwritableFolder) {
    const Rendered r = sphere_frame(Backend::Embree, 8, 1);
    EXPECT_THROW(write_frame_image(output_dir() / "x.bmp", r.frame, r.view), InputError);
    EXPECT_THROW(write_frame_image("/nonexistent-dir/x.png", r.frame, r.view), IoError);
}

TEST(Shade, ModesProduceTheirDocumentedValues) {
    const Rendered r = sphere_frame(Backend::Embree, 33, 1);
    const std::size_t centre = 16 * 33 + 16;
    // Reflection at the centre of the sphere: n = view direction, grey = n·l = l.z.
    const RgbaImage refl = shade(r.frame, r.view, ShadeOptions{.mode = ShadeMode::Reflection});
    const Vec3d l = ShadeOptions{}.light_in_camera.normalized();
    EXPECT_NEAR(refl.pixels[4 * centre], l.z(), 2e-3);  // the icosphere's facet tilt at the centre
    const RgbaImage depth = shade(r.frame, r.view, ShadeOptions{.mode = ShadeMode::Depth});
    EXPECT_GT(depth.pixels[4 * centre], 0.9f);  // nearest point is brightest
    const RgbaImage zebra = shade(r.frame, r.view, ShadeOptions{.mode = ShadeMode::Zebra});
    std::size_t white = 0, black = 0;
    for (std::size_t p = 0; p < r.frame.pixel_count(); ++p) {
        if (!r.frame.is_covered(p)) continue;
        (zebra.pixels[4 * p] > 0.5f ? white : black)++;
    }
    EXPECT_GT(white, 50u);
    EXPECT_GT(black, 50u);
    EXPECT_EQ(refl.pixels[3], 0.0f);  // corner: uncovered, alpha 0
    EXPECT_THROW((void)parse_shade_mode("phong"), InputError);
}

// Golden image (STYLE.md §7): lavapipe's frame of a fixed sphere view, stored as EXR. The
// analytic tests already pin the numbers; this one catches any change of the pipeline's
// output (conventions, sub-sample positions, resolve). Update: GLINT_UPDATE_GOLDEN=1.
// Thresholds: 1e-4 per channel (float noise across CPUs / LLVM versions is ~1e-6; a real
// change moves normals by ≥ 1e-3) and at most 0.5 % failing pixels (silhouette pixels whose
// coverage flips with a one-ulp change of the edge equations).
TEST(GoldenImage, LavapipeSphereMatchesTheStoredExr) {
    // note: pinned to lavapipe: a GPU's rasteriser may place silhouette samples differently.
    const Rendered r = sphere_frame(Backend::Vulkan, 64, 2, "llvmpipe");
    const fs::path golden = fs::path(GLINT_GOLDEN_DIR) / "render" / "LavapipeSphere.exr";
    const fs::path actual = output_dir() / "LavapipeSphere.actual.exr";
    write_frame_image(actual, r.frame, r.view);
    const char* update = std::getenv("GLINT_UPDATE_GOLDEN");
    if (update != nullptr && std::string(update) == "1") {
        fs::create_directories(golden.parent_path());
        fs::copy_file(actual, golden, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "golden updated: " << golden;
    }
    ASSERT_TRUE(fs::exists(golden))
        << "missing golden " << golden << " (run with GLINT_UPDATE_GOLDEN=1)";
    OIIO::ImageBuf a(actual.string());
    OIIO::ImageBuf g(golden.string());
    ASSERT_TRUE(a.read(0, 0, true, OIIO::TypeDesc::FLOAT) &&
                g.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    // Compare the shaded colour, coverage and the normal channels (by name: OpenEXR sorts
    // them); depth and id are covered by the analytic tests.
    const auto pick = [](const OIIO::ImageBuf& src) {
        std::vector<int> order;
        for (const char* name : {"R", "G", "B", "A", "N.x", "N.y", "N.z"})
            order.push_back(src.spec().channelindex(name));
        return OIIO::ImageBufAlgo::channels(src, 7, order);
    };
    const OIIO::ImageBuf a7 = pick(a);
    const OIIO::ImageBuf g7 = pick(g);
    ASSERT_FALSE(a7.has_error() || g7.has_error()) << a7.geterror() << g7.geterror();
    const auto cmp = OIIO::ImageBufAlgo::compare(a7, g7, 1e-4f, 1e-4f);
    const double failing = static_cast<double>(cmp.nfail) / (64.0 * 64.0);
    if (failing > 0.005) {
        const fs::path diff = output_dir() / "LavapipeSphere.diff.exr";
        OIIO::ImageBuf d = OIIO::ImageBufAlgo::absdiff(a7, g7);
        d.write(diff.string());
        ADD_FAILURE() << cmp.nfail << " pixels differ (max " << cmp.maxerror << " at " << cmp.maxx
                      << "," << cmp.maxy << "); actual: " << actual << ", diff: " << diff;
    }
}

}  // namespace
}  // namespace glint::test
