// render_view_pair_rows: frame pairs streamed by bands of rows. The rows put back together are
// bitwise render_view_pairs' frames on both backends, whatever the frame options; with Embree
// on both sides no band is a whole frame (the frames are never whole in memory); done(i)
// follows every band of view i, in view order; exceptions propagate.
#include "render/renderer.h"

#include "mesh/error.h"
#include "render/view.h"
#include "tests/render/render_test_util.h"
#include "tests/render/test_meshes.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint::test {
namespace {

class PairRowsTest : public testing::TestWithParam<Backend> {};

std::vector<View> views_of(const Mesh& mesh) {
    std::vector<View> views;
    for (int i = 0; i < 4; ++i)
        views.push_back(make_view(mesh, ViewSpec{.azimuth_deg = 50.0 * i,
                                                 .elevation_deg = 15.0 * i - 20,
                                                 .width = 20 + 6 * i,
                                                 .height = 18 + 5 * i,
                                                 .index = i}));
    return views;
}

// Copies rows into a frame of the view's size at their place.
void put_rows(const FrameRows& rows, Frame& frame) {
    const std::size_t first =
        static_cast<std::size_t>(rows.y0) * static_cast<std::size_t>(rows.width);
    std::copy(rows.normal.begin(), rows.normal.end(),
              frame.normal.begin() + static_cast<std::ptrdiff_t>(3 * first));
    std::copy(rows.primitive_id.begin(), rows.primitive_id.end(),
              frame.primitive_id.begin() + static_cast<std::ptrdiff_t>(first));
    std::copy(rows.depth.begin(), rows.depth.end(),
              frame.depth.begin() + static_cast<std::ptrdiff_t>(first));
    std::copy(rows.coverage.begin(), rows.coverage.end(),
              frame.coverage.begin() + static_cast<std::ptrdiff_t>(first));
    frame.normal_space = rows.normal_space;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

struct Streamed {
    std::vector<Frame> first, second;  // put back together
    int tallest_band = 0;
    std::vector<std::size_t> done_order;
};

Streamed stream(Renderer& a, Renderer& b, const std::vector<View>& views) {
    Streamed s;
    for (const View& v : views) {
        s.first.push_back(make_empty_frame(v.camera.width, v.camera.height));
        s.second.push_back(make_empty_frame(v.camera.width, v.camera.height));
    }
    std::vector<int> rows_seen(views.size(), 0);
    std::mutex mutex;
    render_view_pair_rows(
        a, b, views,
        [&](std::size_t i, const FrameRows& ra, const FrameRows& rb) {
            EXPECT_EQ(ra.y0, rb.y0);
            EXPECT_EQ(ra.height, rb.height);
            put_rows(ra, s.first[i]);
            put_rows(rb, s.second[i]);
            std::lock_guard lock(mutex);
            rows_seen[i] += ra.height;
            s.tallest_band = std::max(s.tallest_band, ra.height);
        },
        [&](std::size_t i) {
            EXPECT_EQ(rows_seen[i], views[i].camera.height)
                << "view " << i << " done before all its rows";
            s.done_order.push_back(i);
        });
    return s;
}

void expect_frames_equal(const Frame& got, const Frame& expected, const std::string& what) {
    EXPECT_EQ(got.normal_space, expected.normal_space) << what;
    EXPECT_TRUE(same_bits(got.normal, expected.normal)) << what << ": normals differ";
    EXPECT_TRUE(same_bits(got.primitive_id, expected.primitive_id))
        << what << ": primitive ids differ";
    EXPECT_TRUE(same_bits(got.depth, expected.depth)) << what << ": depths differ";
    EXPECT_TRUE(same_bits(got.coverage, expected.coverage)) << what << ": coverage differs";
    EXPECT_GT(expected.covered_count(), 0u) << what << ": nothing rendered";
}

void expect_rows_are_the_pairs(Renderer& a, Renderer& b, const std::vector<View>& views,
                               const std::string& what) {
    std::vector<Frame> expected_a, expected_b;
    render_view_pairs(a, b, views, [&](std::size_t, const Frame& fa, const Frame& fb) {
        expected_a.push_back(fa);
        expected_b.push_back(fb);
    });
    const Streamed s = stream(a, b, views);
    ASSERT_EQ(s.done_order.size(), views.size()) << what;
    for (std::size_t i = 0; i < views.size(); ++i) {
        EXPECT_EQ(s.done_order[i], i) << what;
        expect_frames_equal(s.first[i], expected_a[i], what + ", first, view " + std::to_string(i));
        expect_frames_equal(s.second[i], expected_b[i],
                            what + ", second, view " + std::to_string(i));
    }
}

TEST_P(PairRowsTest, RowsAreBitwiseThePairsFrames) {
    const Mesh bumpy = make_bumpy_sphere(2), ico = make_icosphere(2);
    auto context = std::make_shared<RenderContext>(test_options(GetParam()).context_options());
    const auto views = views_of(bumpy);
    {
        Renderer a(context, bumpy, FrameOptions{.supersample = 2}),
            b(context, ico, FrameOptions{.supersample = 2});
        expect_rows_are_the_pairs(a, b, views, "s = 2");
    }
    {
        // One sample per pixel; the second side masked and in view space.
        Renderer a(context, bumpy),
            b(context, ico, FrameOptions{.normal_space = NormalSpace::View, .min_coverage = 1.0f});
        expect_rows_are_the_pairs(a, b, views, "s = 1, view space");
    }
    {
        // Different sub-sampling on the two sides: bands of different heights.
        Renderer a(context, bumpy, FrameOptions{.supersample = 2}),
            b(context, ico, FrameOptions{.supersample = 3});
        expect_rows_are_the_pairs(a, b, views, "s = 2 and 3");
    }
}

TEST(PairRows, EmbreeNeverHandsOnAWholeFrame) {
    const Mesh mesh = make_bumpy_sphere(2);
    auto context =
        std::make_shared<RenderContext>(ContextOptions{.backend = Backend::Embree, .threads = 2});
    Renderer a(context, mesh, FrameOptions{.supersample = 2}),
        b(context, mesh, FrameOptions{.supersample = 2});
    const Streamed s = stream(a, b, views_of(mesh));
    // note: 4 sub-sample rows per ray packet: 2 output rows at s = 2.
    EXPECT_EQ(s.tallest_band, 2);
}

TEST_P(PairRowsTest, ExceptionsPropagateAndBothRenderersStayUsable) {
    const Mesh mesh = make_icosphere(2);
    auto context = std::make_shared<RenderContext>(test_options(GetParam()).context_options());
    Renderer a(context, mesh, FrameOptions{.supersample = 2}),
        b(context, mesh, FrameOptions{.supersample = 2});
    const auto views = views_of(mesh);
    EXPECT_THROW(render_view_pair_rows(
                     a, b, views,
                     [](std::size_t i, const FrameRows&, const FrameRows&) {
                         if (i == 1) throw std::runtime_error("stop in a band");
                     },
                     [](std::size_t) {}),
                 std::runtime_error);
    EXPECT_THROW(render_view_pair_rows(
                     a, b, views, [](std::size_t, const FrameRows&, const FrameRows&) {},
                     [](std::size_t i) {
                         if (i == 2) throw std::runtime_error("stop after a view");
                     }),
                 std::runtime_error);
    EXPECT_THROW(render_view_pair_rows(
                     a, a, views, [](std::size_t, const FrameRows&, const FrameRows&) {},
                     [](std::size_t) {}),
                 InputError);
    std::atomic<std::size_t> done{0};
    render_view_pair_rows(
        a, b, views, [](std::size_t, const FrameRows&, const FrameRows&) {},
        [&](std::size_t) { ++done; });
    EXPECT_EQ(done.load(), views.size());
    expect_no_validation_messages(a);
}

TEST_P(PairRowsTest, AMeshReadInPlaceRendersTheFramesOfACopy) {
    const Mesh mesh = make_bumpy_sphere(2);
    auto context = std::make_shared<RenderContext>(test_options(GetParam()).context_options());
    Renderer copy(context, mesh, FrameOptions{.supersample = 2});
    Renderer shared(context, mesh, FrameOptions{.supersample = 2, .share_mesh = true});
    for (const View& v : views_of(mesh))
        expect_frames_equal(shared.render(v), copy.render(v), "view " + std::to_string(v.index));
}

INSTANTIATE_TEST_SUITE_P(Backends, PairRowsTest, testing::ValuesIn(all_backends()), backend_name);

}  // namespace
}  // namespace glint::test
