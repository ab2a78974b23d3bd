#include "render/renderer.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/validate.h"
#include "render/detail/backend.h"

#include <tbb/task_group.h>

#include <atomic>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <limits>
#include <sstream>
#include <utility>

namespace glint {

void RenderOptions::validate() const {
    frame_options().validate();
    context_options().validate();
}

ContextOptions RenderOptions::context_options() const {
    return ContextOptions{.backend = backend,
                          .device = device,
                          .validation = validation,
                          .threads = threads,
                          .raster = raster};
}

FrameOptions RenderOptions::frame_options() const {
    return FrameOptions{.normal_space = normal_space,
                        .supersample = supersample,
                        .min_coverage = min_coverage,
                        .cull_back_faces = cull_back_faces};
}

namespace {

void check_view(const View& view, int supersample) {
    const Camera& c = view.camera;
    const long long limit = 16384;
    if (c.width < 1 || c.height < 1 || c.width * static_cast<long long>(supersample) > limit ||
        c.height * static_cast<long long>(supersample) > limit) {
        std::ostringstream s;
        s << "view " << view.index << ": size " << c.width << "x" << c.height
          << " with supersample " << supersample << ", expected 1.." << limit
          << " sub-samples per side";
        throw InputError(s.str());
    }
    if (!(c.near_plane > 0.0 && c.far_plane > c.near_plane)) {
        std::ostringstream s;
        s << "view " << view.index << ": near " << c.near_plane << ", far " << c.far_plane
          << ", expected 0 < near < far";
        throw InputError(s.str());
    }
    if (c.projection == Projection::Orthographic && !(c.ortho_half_height > 0.0)) {
        throw InputError("view " + std::to_string(view.index) + ": ortho_half_height must be > 0");
    }
}

}  // namespace

std::vector<std::string> gpu_device_nodes() {
    namespace fs = std::filesystem;
    std::vector<std::string> nodes;
    std::error_code ec;
    for (fs::directory_iterator it("/dev/dri", ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().starts_with("renderD"))
            nodes.push_back(it->path().string());
    for (const char* node : {"/dev/nvidiactl", "/dev/dxg"})
        if (fs::exists(node, ec)) nodes.emplace_back(node);
    std::sort(nodes.begin(), nodes.end());
    return nodes;
}

Backend resolve_backend(const RenderOptions& options, std::size_t triangle_count,
                        std::string* reason) {
    const auto say = [&](std::string text) {
        if (reason != nullptr) *reason = std::move(text);
    };
    if (options.backend != Backend::Auto) {
        say("backend chosen explicitly");
        return options.backend;
    }
    if (!options.device.empty() || std::getenv("GLINT_DEVICE") != nullptr) {
        say("a Vulkan device was named");
        return Backend::Vulkan;
    }
    const char* probe = std::getenv("GLINT_PROBE_VULKAN");
    // As the other GLINT_ flags: set to anything but empty or "0".
    const bool probe_anyway = probe != nullptr && *probe != '\0' && std::string(probe) != "0";
    if (gpu_device_nodes().empty() && !probe_anyway) {
        say("auto: no GPU device node (/dev/dri/renderD*, /dev/nvidiactl, /dev/dxg), using "
            "Embree without starting Vulkan");
        return Backend::Embree;
    }
    std::vector<DeviceInfo> devices;
    try {
        devices = list_devices();
    } catch (const DeviceError& e) {
        say(std::string("auto: no Vulkan (") + e.what() + "), using Embree");
        return Backend::Embree;
    }
    for (const auto& d : devices) {
        if (d.is_usable && d.type != "cpu") {
            say("auto: GPU \"" + d.name + "\" present, using Vulkan");
            return Backend::Vulkan;
        }
    }
    // note: on CPU-only machines Embree's ray casting beats lavapipe's single-threaded
    // triangle setup at every mesh size we measured (bench/render_bench.cpp).
    say(triangle_count > 0
            ? "auto: no GPU, " + std::to_string(triangle_count) +
                  " triangles on the CPU: Embree is faster than lavapipe"
            : std::string("auto: no GPU: on the CPU Embree is faster than lavapipe"));
    return Backend::Embree;
}

namespace {

/// A context for one renderer; bad input is refused before a device is made.
std::shared_ptr<RenderContext> own_context(const RenderOptions& options, const Mesh& mesh) {
    options.validate();
    if (mesh.triangles.empty()) throw InputError("renderer: mesh has no triangles");
    return std::make_shared<RenderContext>(options.context_options());
}

/// The context's options with a renderer's frame options.
RenderOptions combined(const ContextOptions& c, const FrameOptions& f) {
    return RenderOptions{.backend = c.backend,
                         .device = c.device,
                         .normal_space = f.normal_space,
                         .supersample = f.supersample,
                         .min_coverage = f.min_coverage,
                         .cull_back_faces = f.cull_back_faces,
                         .validation = c.validation,
                         .threads = c.threads,
                         .raster = c.raster};
}

}  // namespace

Renderer::Renderer(const Mesh& mesh, const RenderOptions& options)
    : Renderer(own_context(options, mesh), mesh, options.frame_options()) {}

Renderer::Renderer(std::shared_ptr<RenderContext> context, const Mesh& mesh,
                   const FrameOptions& options)
    : context_(std::move(context)) {
    if (context_ == nullptr) throw InputError("renderer: no render context (null)");
    options.validate();
    options_ = combined(context_->options(), options);
    if (mesh.triangles.empty()) throw InputError("renderer: mesh has no triangles");
    info_.triangle_count = mesh.triangle_count();
    info_.vertex_count = mesh.vertex_count();
    info_.backend = context_->backend();
    info_.device_name = context_->device_name();
    info_.device_type = context_->device_type();
    info_.raster = context_->options().raster;
    info_.warnings = context_->warnings();
    if (options_.cull_back_faces) {
        // Culling is only correct for a closed surface: an open one would lose its back side
        // (seen through a hole or from behind). It is turned off, and the warnings say so.
        const ValidationReport report = validate_mesh(mesh, "renderer");
        if (!report.is_closed) {
            options_.cull_back_faces = false;
            info_.warnings.push_back("back-face culling turned off: the mesh is not closed (" +
                                     std::to_string(report.boundary_edges) + " boundary, " +
                                     std::to_string(report.non_manifold_edges) +
                                     " non-manifold edges)");
        }
    }

    const Mesh* source = &mesh;
    Mesh with_normals;
    if (!mesh.has_normals()) {
        with_normals.positions = mesh.positions;
        with_normals.triangles = mesh.triangles;
        compute_vertex_normals(with_normals);
        info_.computed_normals = true;
        info_.warnings.push_back("mesh had no vertex normals: angle-weighted normals computed");
        source = &with_normals;
    }
    FrameOptions frame = options_.frame_options();
    frame.share_mesh = options.share_mesh && source == &mesh;  // never a copy made here
    frame.barycentrics = options.barycentrics;
    // The surface's shared BVH indexes the mesh as given, not a copy with computed normals
    // (the same positions and triangles either way).
    frame.surface_index = options.surface_index;
    backend_ = context_->impl().make_backend(*source, frame);
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

const RendererInfo& Renderer::info() const { return info_; }
const RenderOptions& Renderer::options() const { return options_; }
const std::shared_ptr<RenderContext>& Renderer::context() const { return context_; }

std::vector<std::string> Renderer::validation_messages() const {
    return context_ ? context_->validation_messages() : std::vector<std::string>{};
}

namespace {

/// Applies the options that do not depend on the backend: coverage mask, normal space.
void finish_frame(Frame& frame, const View& view, const RenderOptions& options) {
    const std::size_t n = frame.pixel_count();
    if (options.min_coverage > 0.0f) {
        // note: coverage is a multiple of 1/s²; the 1e-6 slack keeps min_coverage = 1 from
        // rejecting fully covered pixels through float rounding.
        const float threshold = options.min_coverage - 1e-6f;
        for (std::size_t p = 0; p < n; ++p) {
            if (frame.coverage[p] > 0.0f && frame.coverage[p] < threshold) {
                frame.normal[3 * p] = frame.normal[3 * p + 1] = frame.normal[3 * p + 2] = 0.0f;
                frame.primitive_id[p] = kNoPrimitive;
                frame.depth[p] = kNoDepth;
                frame.coverage[p] = 0.0f;
                if (!frame.barycentric.empty())
                    frame.barycentric[2 * p] = frame.barycentric[2 * p + 1] =
                        std::numeric_limits<float>::quiet_NaN();
            }
        }
    }
    if (options.normal_space == NormalSpace::View) {
        const Eigen::Matrix3f camera_from_world =
            view.camera.world_from_camera.linear().transpose().cast<float>();
        for (std::size_t p = 0; p < n; ++p) {
            Eigen::Map<Eigen::Vector3f> nrm(&frame.normal[3 * p]);
            nrm = camera_from_world * Eigen::Vector3f(nrm);
        }
    }
    frame.normal_space = options.normal_space;
}

}  // namespace

namespace {

/// Streams views through one or two backends in lockstep: every backend gets view i before
/// any waits, up to the smallest max_in_flight views ahead; consume(i, frames) runs in view
/// order. On an exception every backend drops its views in flight and it propagates.
void stream_views(std::span<detail::RenderBackend* const> backends, std::span<const View> views,
                  const std::function<void(std::size_t, std::span<Frame* const>)>& consume) {
    std::size_t depth = backends.front()->max_in_flight();
    bool tasks = backends.size() > 1;
    for (auto* b : backends) {
        depth = std::min(depth, b->max_in_flight());
        tasks = tasks && b->works_in_finish();
    }
    std::array<Frame*, 2> frames{};
    std::deque<std::size_t> pending;
    const auto finish_oldest = [&] {
        const std::size_t i = pending.front();
        pending.pop_front();
        if (tasks) {
            // Two CPU renders as two tasks; the second on a TBB worker while this thread
            // does the first.
            tbb::task_group group;
            group.run([&] { frames[1] = &backends[1]->finish(); });
            frames[0] = &backends[0]->finish();
            group.wait();
        } else {
            for (std::size_t k = 0; k < backends.size(); ++k) frames[k] = &backends[k]->finish();
        }
        consume(i, std::span<Frame* const>(frames.data(), backends.size()));
    };
    try {
        for (std::size_t i = 0; i < views.size(); ++i) {
            if (pending.size() == depth) finish_oldest();
            for (auto* b : backends) b->submit(views[i]);
            pending.push_back(i);
        }
        while (!pending.empty()) finish_oldest();
    } catch (...) {
        for (auto* b : backends) b->abandon();
        throw;
    }
}

}  // namespace

void Renderer::render_views(std::span<const View> views, const FrameConsumer& consumer) {
    GLINT_ASSERT(backend_ != nullptr, "render_views on a moved-from Renderer");
    for (const View& v : views) check_view(v, options_.supersample);
    detail::RenderBackend* const backends[] = {backend_.get()};
    stream_views(backends, views, [&](std::size_t i, std::span<Frame* const> frames) {
        finish_frame(*frames[0], views[i], options_);
        consumer(i, *frames[0]);
    });
}

Frame Renderer::render(const View& view) {
    GLINT_ASSERT(backend_ != nullptr, "render on a moved-from Renderer");
    check_view(view, options_.supersample);
    Frame result;
    detail::RenderBackend* const backends[] = {backend_.get()};
    stream_views(backends, std::span<const View>(&view, 1),
                 [&](std::size_t, std::span<Frame* const> frames) {
                     finish_frame(*frames[0], view, options_);
                     result = std::move(*frames[0]);
                 });
    return result;
}

void detail::RenderBackend::trace_rows(const View&, int, int, RowScratch&, Frame&) const {
    GLINT_ASSERT(false, "trace_rows on a backend that renders whole frames only");
}

namespace {

/// body(worker, y0, y1) over the bands of `band` rows of a `height`-row frame, on up to
/// `threads` workers taking bands from a shared counter (surface is slower than empty sky).
void for_each_band(int height, int band, int threads,
                   const std::function<void(int, int, int)>& body) {
    const int bands = (height + band - 1) / band;
    const int workers = std::clamp(threads, 1, std::max(1, bands));
    std::atomic<int> next{0};
    detail::parallel_for(workers, workers, [&](int t0, int t1) {
        for (int t = t0; t < t1; ++t)
            for (int b = next++; b < bands; b = next++)
                body(t, b * band, std::min(height, (b + 1) * band));
    });
}

// note: bands of 8 rows when whole frames are split: 32 bands at 256², enough for 16 workers.
constexpr int kWholeFrameBand = 8;

}  // namespace

void render_view_pair_rows(Renderer& first, Renderer& second, std::span<const View> views,
                           const PairRowsConsumer& rows,
                           const std::function<void(std::size_t)>& done) {
    GLINT_ASSERT(first.backend_ != nullptr && second.backend_ != nullptr,
                 "render_view_pair_rows on a moved-from Renderer");
    if (&first == &second)
        throw InputError("render_view_pair_rows: the two renderers must be distinct");
    const int threads = detail::worker_count(first.options_.threads);
    const detail::RenderBackend* a = first.backend_.get();
    const detail::RenderBackend* b = second.backend_.get();
    const int band = a->band_rows();
    if (band == 0 || b->band_rows() != band) {
        render_view_pairs(
            first, second, views, [&](std::size_t i, const Frame& fa, const Frame& fb) {
                for_each_band(fa.height, kWholeFrameBand, threads, [&](int, int y0, int y1) {
                    rows(i, frame_rows(fa, y0, y1), frame_rows(fb, y0, y1));
                });
                done(i);
            });
        return;
    }
    for (const View& v : views) {
        check_view(v, first.options_.supersample);
        check_view(v, second.options_.supersample);
    }
    struct Worker {
        std::unique_ptr<detail::RenderBackend::RowScratch> scratch_a, scratch_b;
        Frame a, b;  // the band's rows
    };
    std::vector<Worker> workers(static_cast<std::size_t>(threads));
    for (auto& w : workers) {
        w.scratch_a = a->make_row_scratch();
        w.scratch_b = b->make_row_scratch();
    }
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& v = views[i];
        for_each_band(v.camera.height, band, threads, [&](int t, int y0, int y1) {
            Worker& w = workers[static_cast<std::size_t>(t)];
            a->trace_rows(v, y0, y1, *w.scratch_a, w.a);
            b->trace_rows(v, y0, y1, *w.scratch_b, w.b);
            finish_frame(w.a, v, first.options_);
            finish_frame(w.b, v, second.options_);
            FrameRows ra = frame_rows(w.a, 0, y1 - y0), rb = frame_rows(w.b, 0, y1 - y0);
            ra.y0 = rb.y0 = y0;
            rows(i, ra, rb);
        });
        done(i);
    }
}

void render_view_pairs(Renderer& first, Renderer& second, std::span<const View> views,
                       const PairConsumer& consumer) {
    GLINT_ASSERT(first.backend_ != nullptr && second.backend_ != nullptr,
                 "render_view_pairs on a moved-from Renderer");
    if (&first == &second)
        throw InputError("render_view_pairs: the two renderers must be distinct");
    for (const View& v : views) {
        check_view(v, first.options_.supersample);
        check_view(v, second.options_.supersample);
    }
    detail::RenderBackend* const backends[] = {first.backend_.get(), second.backend_.get()};
    stream_views(backends, views, [&](std::size_t i, std::span<Frame* const> frames) {
        finish_frame(*frames[0], views[i], first.options_);
        finish_frame(*frames[1], views[i], second.options_);
        consumer(i, *frames[0], *frames[1]);
    });
}

}  // namespace glint
