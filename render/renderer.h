// The renderer: a mesh uploaded once to a backend, rendered from any number of views into
// Frames (render/frame.h).
//
// Backends
// - Vulkan: rasterisation on a GPU or on Mesa's lavapipe (CPU). Normals into RGBA32F with
//   linear depth, gl_PrimitiveID into R32_UINT, rendered at s× the size and resolved on the
//   CPU into s×s sub-sample means. Headless (no window, no swapchain).
// - Embree: one primary ray per sub-sample (rtcIntersect16 on 4×4 tiles), barycentric
//   interpolation of the vertex normals: the same Frame, the same conventions.
// - Auto: Vulkan when a hardware GPU (discrete, integrated or virtual) is present, else
//   Embree, which measured faster than lavapipe on CPU-only machines (see bench/). A machine
//   without a GPU device node (gpu_device_nodes) is not probed: asking the Vulkan loader
//   loads every installed driver, lavapipe with LLVM among them (60 MB resident, for a
//   device Auto never picks). GLINT_PROBE_VULKAN=1 probes anyway.
//
// Usage
//   Renderer renderer(mesh, RenderOptions{.supersample = 2});
//   Frame f = renderer.render(view);
//   renderer.render_views(views, [&](std::size_t i, const Frame& frame) { ... });
//
// Many meshes on one device (render/context.h):
//   auto context = shared_render_context(options.context_options());
//   Renderer a(context, mesh_a, options.frame_options()), b(context, mesh_b, ...);
//   render_view_pairs(a, b, views, [&](std::size_t i, const Frame& fa, const Frame& fb) { ... });
#pragma once

#include "mesh/mesh.h"
#include "render/context.h"
#include "render/frame.h"
#include "render/view.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint {

/// Context and frame options in one (the convenience constructor's): see ContextOptions and
/// FrameOptions (render/context.h) for the fields.
struct RenderOptions {
    Backend backend = Backend::Auto;
    /// Vulkan device: case-insensitive substring of the device name ("llvmpipe", "NVIDIA").
    /// Empty: the GLINT_DEVICE environment variable, else the best device (discrete GPU >
    /// integrated > virtual > CPU).
    std::string device{};
    NormalSpace normal_space = NormalSpace::World;
    /// s: each output pixel resolves s×s sub-samples (1 = one sample at the pixel centre).
    int supersample = 1;
    /// Pixels whose coverage is below this share are reported uncovered (masked). 0 keeps
    /// every pixel with at least one covered sub-sample (its normal is normalised by
    /// coverage); 1 keeps only fully covered pixels.
    float min_coverage = 0.0f;
    /// Discard triangles facing away from the camera. Only correct for closed meshes, so it
    /// is turned off (with a warning in RendererInfo::warnings) for an open or non-manifold
    /// mesh; off by default.
    bool cull_back_faces = false;
    /// Vulkan: enable VK_LAYER_KHRONOS_validation and collect its messages
    /// (Renderer::validation_messages). Also on when GLINT_VK_VALIDATION=1.
    /// \throw DeviceError at creation when the layer is not installed.
    bool validation = false;
    /// CPU threads for the Embree backend and the Vulkan resolve; 0 = hardware concurrency.
    int threads = 0;
    /// Vulkan: how the normal pass is rasterised (render/context.h Raster).
    Raster raster = Raster::Auto;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;

    [[nodiscard]] ContextOptions context_options() const;
    [[nodiscard]] FrameOptions frame_options() const;
};

/// What a renderer runs on, and anything it noticed on the way (STYLE.md: nothing is lost).
struct RendererInfo {
    Backend backend = Backend::Vulkan;  ///< resolved (never Auto)
    std::string device_name;  ///< "llvmpipe (LLVM 15.0.6, 256 bits)", "embree 3.13.5 (CPU)"
    std::string device_type;  ///< "discrete", "integrated", "virtual", "cpu"
    /// Vulkan: the rasteriser of the normal pass (resolved, never Auto); Embree: Auto.
    Raster raster = Raster::Auto;
    std::size_t triangle_count = 0;
    std::size_t vertex_count = 0;
    bool computed_normals = false;  ///< the mesh had no normals: angle-weighted ones were computed
    std::vector<std::string> warnings;  ///< e.g. why Auto chose a backend
};

/// Receives each frame as it completes. The frame reference is valid only during the call.
using FrameConsumer = std::function<void(std::size_t view_index, const Frame& frame)>;

namespace detail {
class RenderBackend;
}

/// Receives both frames of view `view_index` (valid only during the call).
using PairConsumer =
    std::function<void(std::size_t view_index, const Frame& first, const Frame& second)>;

/// Receives rows [rows.y0, rows.y0 + rows.height) of both frames of view `view_index` (valid
/// only during the call). Called on worker threads, concurrently for disjoint bands of rows of
/// one view; every band of a view is handed on before the next view's first.
using PairRowsConsumer =
    std::function<void(std::size_t view_index, const FrameRows& first, const FrameRows& second)>;

/// A mesh uploaded to a device. Move-only. Not thread-safe: use one renderer per thread
/// (renderers of one context may run on different threads).
class Renderer {
  public:
    /// Uploads the mesh (normals computed when absent) to the context's device.
    /// \throw InputError invalid options, empty mesh, null context.
    /// \throw DeviceError a failed device call.
    Renderer(std::shared_ptr<RenderContext> context, const Mesh& mesh,
             const FrameOptions& options = {});
    /// Convenience: a context of its own (one device per renderer), created from `options`.
    /// \throw as RenderContext's constructor and the constructor above.
    explicit Renderer(const Mesh& mesh, const RenderOptions& options = {});
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Renders one view. \throw InputError invalid camera (size ≤ 0, too large);
    /// \throw DeviceError on device failure.
    [[nodiscard]] Frame render(const View& view);

    /// Renders views in order and hands each frame to `consumer` as soon as it is resolved.
    /// Memory stays bounded (two frames in flight) whatever the number of views; the Vulkan
    /// backend renders view i+1 while the consumer handles view i. Exceptions thrown by the
    /// consumer stop the run and propagate.
    void render_views(std::span<const View> views, const FrameConsumer& consumer);

    [[nodiscard]] const RendererInfo& info() const;
    /// The context's options and this renderer's frame options (culling as applied).
    [[nodiscard]] const RenderOptions& options() const;
    [[nodiscard]] const std::shared_ptr<RenderContext>& context() const;

    /// Vulkan validation-layer messages (warnings and errors) collected so far on this
    /// renderer's context; empty for Embree or when validation is off.
    [[nodiscard]] std::vector<std::string> validation_messages() const;

  private:
    friend void render_view_pairs(Renderer&, Renderer&, std::span<const View>, const PairConsumer&);
    friend class GpuAtlas;  // draws with the backends' device buffers (render/gpu_atlas.h)
    friend void render_view_pair_rows(Renderer&, Renderer&, std::span<const View>,
                                      const PairRowsConsumer&,
                                      const std::function<void(std::size_t)>&);
    std::shared_ptr<RenderContext> context_;
    std::unique_ptr<detail::RenderBackend> backend_;
    RenderOptions options_;
    RendererInfo info_;
};

/// Renders every view with both renderers, the two frames of a view in flight together
/// (Vulkan: both submitted before either is waited for, and the next view's pair submitted
/// while the consumer handles this one; Embree: the two frames as two tasks), and hands
/// the consumer each pair in view order. The frames are bitwise those that render_views of
/// each renderer gives. The renderers must be distinct; they may have different contexts.
/// Exceptions (the consumer's or a device's) stop the run and propagate; both renderers
/// stay usable.
void render_view_pairs(Renderer& first, Renderer& second, std::span<const View> views,
                       const PairConsumer& consumer);

/// render_view_pairs streamed by bands of rows, for work that reads a frame pair pixel by pixel
/// as it is produced (the sweep's comparison and back-projection, scanner/sweep.h).
/// CPU ray casting (Embree on both renderers): a worker traces and resolves one band of both
/// frames and hands it on at once, so no frame is ever whole in memory and the consumer works
/// while the band is still in cache. Other backends (Vulkan): each pair is rendered as
/// render_view_pairs renders it, then handed on by bands on the workers. Either way the rows
/// are bitwise those of render_view_pairs' frames, and `done(i)` runs on the calling thread
/// after the last band of view i, in view order. Workers: the first renderer's
/// RenderOptions::threads. Exceptions (the callbacks' or a device's) stop the run and
/// propagate; both renderers stay usable.
void render_view_pair_rows(Renderer& first, Renderer& second, std::span<const View> views,
                           const PairRowsConsumer& rows,
                           const std::function<void(std::size_t view_index)>& done);

/// One Vulkan physical device as glint sees it.
struct DeviceInfo {
    std::string name;
    std::string type;    ///< "discrete", "integrated", "virtual", "cpu", "other"
    std::string driver;  ///< driver name / info when reported
    std::uint32_t api_version = 0;
    std::string api_version_text;  ///< "1.3.230"
    bool is_usable = false;
    std::string reason;         ///< why it is not usable (missing feature, …); empty if usable
    bool is_preferred = false;  ///< the device a default Vulkan renderer would pick
    /// Whether compare and back-projection can run on it (render/gpu_atlas.h: 64-bit floats,
    /// integers and buffer atomics, compute on the graphics queue, storage images).
    bool supports_gpu_atlas = false;
    std::string gpu_atlas_reason;  ///< what it lacks for that; empty if it supports it
};

/// Enumerates the Vulkan devices and checks each for what glint needs (graphics queue,
/// geometryShader feature for gl_PrimitiveID, RGBA32F / R32_UINT / D32 attachments).
/// \throw DeviceError when no Vulkan instance can be created (no loader or no driver).
[[nodiscard]] std::vector<DeviceInfo> list_devices();

/// The device nodes through which Linux GPU drivers are reached, those present: render nodes
/// /dev/dri/renderD* (Mesa, virtio-gpu), /dev/nvidiactl (NVIDIA), /dev/dxg (WSL).
[[nodiscard]] std::vector<std::string> gpu_device_nodes();

/// The backend Auto resolves to for a mesh of that size on this machine (see file comment);
/// `reason` receives why.
[[nodiscard]] Backend resolve_backend(const RenderOptions& options, std::size_t triangle_count,
                                      std::string* reason = nullptr);

}  // namespace glint
