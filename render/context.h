// The render context: what a process needs once, whatever the number of meshes — the Vulkan
// instance, device, queue, render pass and pipelines, or the Embree device. Renderers
// (render/renderer.h) bind one mesh each to a context and share its device.
//
//   auto context = shared_render_context(ContextOptions{.backend = Backend::Vulkan});
//   Renderer reference(context, reference_mesh, FrameOptions{.supersample = 2});
//   Renderer examined(context, examined_mesh, FrameOptions{.supersample = 2});
//
// A context may outlive or be outlived by its renderers: each renderer holds a shared_ptr.
// Renderers of one context may render on different threads (queue submissions are
// serialised inside the context); one renderer is still used by one thread at a time.
#pragma once

#include "mesh/surface_index.h"
#include "render/frame.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace glint {

enum class Backend { Auto, Vulkan, Embree };

/// "auto" / "vulkan" / "embree". \throw InputError.
[[nodiscard]] Backend parse_backend(const std::string& text);
[[nodiscard]] std::string to_string(Backend backend);

/// How the Vulkan backend rasterises the normal pass.
///   Graphics  the fixed-function graphics pipeline (render pass, normal.vert / normal.frag);
///   Compute   compute passes (shaders/raster_*.comp: a 64-bit depth·triangle visibility buffer
///             written with atomics, then the attributes per sub-sample). Same rules (pixel
///             centres, top-left fill, 8 sub-pixel bits, depth test LESS, culling, near / far
///             clipping), so the frames agree with the pipeline's up to ties at edges and float
///             rounding (tests/render/compute_raster_test.cpp states by how much). It exists
///             for data-centre GPUs, whose few graphics units make the pipeline the bound of the
///             GPU sweep: on an H100 the two normal passes of a 1M-triangle view at 1024² took
///             3.39 ms in the pipeline and 0.11 ms in compute (render/gpu_atlas.h);
///   Auto      Compute on NVIDIA data-centre GPUs (A100, H100, H200, B200 and kin) that have the
///             GPU atlas's features, Graphics elsewhere (GPUs with full graphics units, lavapipe:
///             not measured faster in compute).
enum class Raster { Auto, Graphics, Compute };

/// "auto" / "graphics" / "compute". \throw InputError.
[[nodiscard]] Raster parse_raster(const std::string& text);
[[nodiscard]] std::string to_string(Raster raster);

/// What selects and configures the device (RenderOptions' device half).
struct ContextOptions {
    Backend backend = Backend::Auto;
    /// Vulkan device: case-insensitive substring of the device name ("llvmpipe", "NVIDIA").
    /// Empty: the GLINT_DEVICE environment variable, else the best device (discrete GPU >
    /// integrated > virtual > CPU).
    std::string device{};
    /// Vulkan: enable VK_LAYER_KHRONOS_validation and collect its messages. Also on when
    /// GLINT_VK_VALIDATION=1. \throw DeviceError at creation when the layer is not installed.
    bool validation = false;
    /// CPU threads for the Embree backend and the Vulkan resolve; 0 = hardware concurrency.
    int threads = 0;
    /// Vulkan: how the normal pass is rasterised (see Raster). Auto: the GLINT_RASTER
    /// environment variable ("graphics", "compute") when set, else as Raster::Auto says.
    Raster raster = Raster::Auto;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
    bool operator==(const ContextOptions&) const = default;
};

/// What one renderer does with its frames (RenderOptions' per-mesh half).
struct FrameOptions {
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
    /// CPU ray casting (Embree) reads the mesh's triangles and normals in place instead of
    /// copying them: the mesh must then outlive the renderer, unchanged. (A mesh without
    /// normals is copied anyway; the GPU uploads the mesh either way.)
    bool share_mesh = false;
    /// CPU ray casting (Embree) at supersample 1 also returns each pixel's barycentric weights
    /// in its triangle (Frame::barycentric), for pictures that interpolate per-vertex values.
    /// Ignored by the GPU and at s > 1 (the frame's barycentric stays empty).
    bool barycentrics = false;
    /// CPU ray casting (Embree) casts its rays into this BVH of the mesh, built already and
    /// shared with the run's other users of the surface (mesh/surface_index.h), instead of
    /// building its own. Ignored by the GPU and with cull_back_faces (which filters hits).
    /// \pre it indexes the renderer's mesh.
    std::shared_ptr<const SurfaceIndex> surface_index;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

namespace detail {
class ContextImpl;
}

/// Counts of what the process created so far (tests, diagnostics).
struct RenderContextStats {
    std::size_t contexts = 0;
    std::size_t vulkan_instances = 0;  ///< including list_devices()'s
    std::size_t vulkan_devices = 0;
    std::size_t embree_devices = 0;
    std::size_t embree_scenes = 0;  ///< BVHs the Embree renderers built of their own
};
[[nodiscard]] RenderContextStats render_context_stats();

/// One device (Vulkan or Embree) and what every renderer on it shares. Not copyable.
class RenderContext {
  public:
    /// Resolves Auto, picks and creates the device.
    /// \throw InputError invalid options; DeviceError no usable device (the message lists
    ///        every device and why it was rejected), no Vulkan driver, a failed device call.
    explicit RenderContext(const ContextOptions& options);
    ~RenderContext();
    RenderContext(const RenderContext&) = delete;
    RenderContext& operator=(const RenderContext&) = delete;

    /// As created: the device named by GLINT_DEVICE and validation from
    /// GLINT_VK_VALIDATION folded in; backend never Auto, raster resolved for Vulkan.
    [[nodiscard]] const ContextOptions& options() const { return options_; }
    [[nodiscard]] Backend backend() const { return options_.backend; }
    [[nodiscard]] const std::string& device_name() const { return device_name_; }
    [[nodiscard]] const std::string& device_type() const { return device_type_; }
    /// Why Auto chose the backend; empty when it was named.
    [[nodiscard]] const std::vector<std::string>& warnings() const { return warnings_; }
    /// Vulkan validation-layer messages of every renderer on this context so far.
    [[nodiscard]] std::vector<std::string> validation_messages() const;

    [[nodiscard]] detail::ContextImpl& impl() const { return *impl_; }

  private:
    ContextOptions options_;
    std::string device_name_;
    std::string device_type_;
    std::vector<std::string> warnings_;
    std::unique_ptr<detail::ContextImpl> impl_;
};

/// The process's context for these options: created at the first call, then the same one
/// for every call with equal options (after folding in GLINT_DEVICE / GLINT_VK_VALIDATION),
/// kept to the end of the process. A failed creation is not remembered.
/// note: environment changes that select drivers (VK_ICD_FILENAMES) after the first call
/// do not reach a context that already exists; construct a RenderContext for that.
[[nodiscard]] std::shared_ptr<RenderContext> shared_render_context(
    const ContextOptions& options = {});

}  // namespace glint
