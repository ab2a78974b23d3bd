// One device, many meshes (render/context.h) and both frames of a view in flight together
// (render_view_pairs): devices created, frames bitwise equal to standalone and sequential
// rendering, lifetimes, errors.
#include "render/context.h"

#include "mesh/error.h"
#include "render/renderer.h"
#include "render/view.h"
#include "tests/render/render_test_util.h"
#include "tests/render/test_meshes.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint::test {
namespace {

class RenderContextTest : public testing::TestWithParam<Backend> {};

ContextOptions context_options(Backend backend) { return test_options(backend).context_options(); }

std::vector<Mesh> four_meshes() {
    std::vector<Mesh> meshes;
    meshes.push_back(make_icosphere(2));
    meshes.push_back(make_uv_sphere(12));
    meshes.push_back(make_bumpy_sphere(2));
    meshes.push_back(make_corrugated_plane(12, 1.0, 0.1, 0.5));
    return meshes;
}

/// Views of changing size (so targets are re-created) and direction.
std::vector<View> some_views(const Mesh& mesh) {
    std::vector<View> views;
    for (int i = 0; i < 5; ++i) {
        views.push_back(make_view(mesh, ViewSpec{.azimuth_deg = 40.0 * i,
                                                 .elevation_deg = 10.0 * i - 20,
                                                 .width = 24 + 8 * (i % 3),
                                                 .height = 24 + 4 * i,
                                                 .index = i}));
    }
    return views;
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_bitwise_equal(const Frame& a, const Frame& b, const std::string& what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    EXPECT_EQ(a.normal_space, b.normal_space) << what;
    EXPECT_TRUE(same_bits(a.normal, b.normal)) << what << ": normals differ";
    EXPECT_TRUE(same_bits(a.depth, b.depth)) << what << ": depths differ";
    EXPECT_TRUE(same_bits(a.coverage, b.coverage)) << what << ": coverage differs";
    EXPECT_TRUE(same_bits(a.primitive_id, b.primitive_id)) << what << ": primitive ids differ";
    EXPECT_GT(a.covered_count(), 0u) << what << ": nothing rendered";
}

std::vector<Frame> render_all(Renderer& renderer, const std::vector<View>& views) {
    std::vector<Frame> frames;
    renderer.render_views(views, [&](std::size_t i, const Frame& f) {
        EXPECT_EQ(i, frames.size());
        frames.push_back(f);
    });
    return frames;
}

TEST_P(RenderContextTest, OneDeviceServesManyRenderers) {
    const auto meshes = four_meshes();
    const RenderContextStats before = render_context_stats();
    auto context = std::make_shared<RenderContext>(context_options(GetParam()));
    std::vector<Renderer> renderers;
    for (const auto& m : meshes) renderers.emplace_back(context, m, FrameOptions{.supersample = 2});
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        EXPECT_GT(renderers[k].render(some_views(meshes[k])[1]).covered_count(), 0u);
    }
    const RenderContextStats after = render_context_stats();
    EXPECT_EQ(after.contexts - before.contexts, 1u);
    if (GetParam() == Backend::Vulkan) {
        EXPECT_EQ(after.vulkan_devices - before.vulkan_devices, 1u);
        EXPECT_EQ(after.vulkan_instances - before.vulkan_instances, 1u);
        EXPECT_EQ(after.embree_devices, before.embree_devices);
    } else {
        EXPECT_EQ(after.embree_devices - before.embree_devices, 1u);
        EXPECT_EQ(after.vulkan_devices, before.vulkan_devices);
    }
    for (const auto& r : renderers) {
        EXPECT_EQ(r.context(), context);
        EXPECT_EQ(r.info().backend, GetParam());
        expect_no_validation_messages(r);
    }
}

TEST_P(RenderContextTest, SharedContextIsOnePerOptions) {
    const ContextOptions options = context_options(GetParam());
    const auto a = shared_render_context(options);
    const RenderContextStats before = render_context_stats();
    const auto b = shared_render_context(options);
    EXPECT_EQ(a, b);
    EXPECT_EQ(render_context_stats().contexts, before.contexts);
    ContextOptions other = options;
    other.threads = 1;
    EXPECT_NE(shared_render_context(other), a);
}

TEST_P(RenderContextTest, RenderersOnOneContextGiveTheFramesOfStandaloneRenderers) {
    const auto meshes = four_meshes();
    auto context = std::make_shared<RenderContext>(context_options(GetParam()));
    // A closed and an open mesh; each standalone renderer costs a device of its own.
    for (const std::size_t k : {std::size_t{0}, std::size_t{3}}) {
        const RenderOptions options = test_options(GetParam(), 2);
        Renderer standalone(meshes[k], options);
        Renderer shared(context, meshes[k], options.frame_options());
        const auto views = some_views(meshes[k]);
        const auto expected = render_all(standalone, views);
        const auto got = render_all(shared, views);
        ASSERT_EQ(got.size(), expected.size());
        for (std::size_t i = 0; i < views.size(); ++i) {
            expect_bitwise_equal(got[i], expected[i],
                                 "mesh " + std::to_string(k) + " view " + std::to_string(i));
        }
        expect_no_validation_messages(shared);
    }
}

TEST_P(RenderContextTest, PairsAreBitwiseTheSequentialFrames) {
    const auto meshes = four_meshes();
    auto context = std::make_shared<RenderContext>(context_options(GetParam()));
    // Different frame options on the two sides: each frame is finished with its own.
    Renderer first(context, meshes[2], FrameOptions{.supersample = 2});
    Renderer second(
        context, meshes[0],
        FrameOptions{.normal_space = NormalSpace::View, .supersample = 3, .min_coverage = 1.0f});
    const auto views = some_views(meshes[2]);
    const auto expected_first = render_all(first, views);
    const auto expected_second = render_all(second, views);
    std::size_t calls = 0;
    render_view_pairs(first, second, views, [&](std::size_t i, const Frame& a, const Frame& b) {
        ASSERT_EQ(i, calls++);
        expect_bitwise_equal(a, expected_first[i], "first, view " + std::to_string(i));
        expect_bitwise_equal(b, expected_second[i], "second, view " + std::to_string(i));
    });
    EXPECT_EQ(calls, views.size());
    // Again after the pairs: the renderers' slots are left as render_views expects them.
    expect_bitwise_equal(first.render(views[3]), expected_first[3], "first after pairs");
    expect_no_validation_messages(first);
}

TEST_P(RenderContextTest, PairsAcrossTwoContextsMatchToo) {
    const Mesh mesh = make_bumpy_sphere(2);
    Renderer first(mesh, test_options(GetParam(), 2));
    Renderer second(mesh, test_options(GetParam(), 2));
    const auto views = some_views(mesh);
    const auto expected = render_all(first, views);
    render_view_pairs(first, second, views, [&](std::size_t i, const Frame& a, const Frame& b) {
        expect_bitwise_equal(a, expected[i], "first");
        expect_bitwise_equal(b, expected[i], "second");
    });
    EXPECT_THROW(
        render_view_pairs(first, first, views, [](std::size_t, const Frame&, const Frame&) {}),
        InputError);
}

TEST_P(RenderContextTest, PairConsumerExceptionPropagatesAndBothStayUsable) {
    const Mesh mesh = make_icosphere(2);
    auto context = std::make_shared<RenderContext>(context_options(GetParam()));
    Renderer first(context, mesh);
    Renderer second(context, mesh);
    const auto views = some_views(mesh);
    EXPECT_THROW(render_view_pairs(first, second, views,
                                   [](std::size_t i, const Frame&, const Frame&) {
                                       if (i == 1) throw std::runtime_error("stop");
                                   }),
                 std::runtime_error);
    std::size_t calls = 0;
    render_view_pairs(first, second, views,
                      [&](std::size_t, const Frame&, const Frame&) { ++calls; });
    EXPECT_EQ(calls, views.size());
    expect_no_validation_messages(first);
}

TEST_P(RenderContextTest, ContextAndRenderersMayEndInAnyOrder) {
    const Mesh mesh = make_icosphere(2);
    const View view = some_views(mesh)[0];
    auto context = std::make_shared<RenderContext>(context_options(GetParam()));
    std::optional<Renderer> early(std::in_place, context, mesh);
    auto late = std::make_unique<Renderer>(context, mesh);
    const Frame expected = early->render(view);
    early.reset();    // a renderer ends before its context
    context.reset();  // the context's last outside owner goes; the renderer keeps it alive
    expect_bitwise_equal(late->render(view), expected, "after the context was released");
    late.reset();  // the device goes with the last renderer
}

TEST(RenderContext, RejectsANullContextAndBadOptions) {
    const Mesh mesh = make_icosphere(1);
    EXPECT_THROW(Renderer(nullptr, mesh), InputError);
    EXPECT_THROW(RenderContext(ContextOptions{.backend = Backend::Embree, .device = "llvmpipe"}),
                 InputError);
    auto context = std::make_shared<RenderContext>(ContextOptions{.backend = Backend::Embree});
    EXPECT_THROW(Renderer(context, mesh, FrameOptions{.supersample = 0}), InputError);
    EXPECT_THROW(Renderer(context, Mesh{}), InputError);
}

TEST(RenderContext, NoVulkanDriverIsOneLineDeviceError) {
    // See VulkanDevice.NoDriverThrowsDeviceError for why all three variables.
    const char* names[] = {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES"};
    std::optional<std::string> saved[3];
    for (int k = 0; k < 3; ++k) {
        if (const char* old = std::getenv(names[k])) saved[k] = old;
    }
    ::setenv(names[0], "/nonexistent/icd.json", 1);
    ::setenv(names[1], "/nonexistent/icd.json", 1);
    ::unsetenv(names[2]);
    std::string message;
    try {
        RenderContext context(ContextOptions{.backend = Backend::Vulkan});
    } catch (const DeviceError& e) {
        message = e.what();
    }
    for (int k = 0; k < 3; ++k) {
        if (saved[k]) ::setenv(names[k], saved[k]->c_str(), 1);
        else ::unsetenv(names[k]);
    }
    EXPECT_NE(message.find("Vulkan"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderContextTest, testing::ValuesIn(all_backends()),
                         backend_name);

}  // namespace
}  // namespace glint::test
