// Internal interfaces of the render module (not part of the public API): a context's
// device-specific half (ContextImpl) and a mesh bound to it (RenderBackend).
#pragma once

#include "mesh/mesh.h"
#include "render/context.h"
#include "render/frame.h"
#include "render/view.h"

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint::detail {

struct VulkanMesh;

/// A mesh on a device. Views are submitted, then finished in submission order:
///   submit(v0) submit(v1) finish()→frame 0 submit(v2) finish()→frame 1 …
/// with at most max_in_flight() views submitted and not finished.
class RenderBackend {
  public:
    virtual ~RenderBackend() = default;
    [[nodiscard]] virtual std::size_t max_in_flight() const = 0;
    /// Starts rendering a view (size already checked against the options).
    virtual void submit(const View& view) = 0;
    /// Waits for the oldest submitted view and resolves its s×s sub-samples (world-space
    /// normals, unmasked). The frame stays valid (and may be modified) until the next submit.
    virtual Frame& finish() = 0;
    /// Drops every view in flight (after an exception); the backend stays usable.
    virtual void abandon() noexcept = 0;
    /// True when the work happens in finish() (CPU ray casting): a pair then runs its two
    /// finishes as two tasks. False when finish() only waits and resolves (Vulkan).
    [[nodiscard]] virtual bool works_in_finish() const { return false; }
    /// The mesh's device buffers when the backend is Vulkan (the GPU atlas draws and reads
    /// them: render/gpu_atlas.cpp); null otherwise. Valid while the backend lives.
    [[nodiscard]] virtual const VulkanMesh* vulkan_mesh() const { return nullptr; }

    /// Band tracing (CPU ray casting): any band of output rows of a view can be traced and
    /// resolved on its own, on any thread, so a frame can be streamed by bands without ever
    /// being whole (render_view_pair_rows). 0: the backend renders whole frames only.
    [[nodiscard]] virtual int band_rows() const { return 0; }
    /// Per-thread working memory of trace_rows (nullptr when band_rows() is 0).
    struct RowScratch {
        virtual ~RowScratch() = default;
    };
    [[nodiscard]] virtual std::unique_ptr<RowScratch> make_row_scratch() const { return nullptr; }
    /// Traces and resolves output rows [y0, y1) of `view` (y0 a multiple of band_rows()) into
    /// `rows`, a frame of width × (y1 − y0) pixels whose row 0 is row y0 (world normals,
    /// unmasked, bitwise as finish() gives them). Thread-safe for distinct scratch and rows.
    virtual void trace_rows(const View& view, int y0, int y1, RowScratch& scratch,
                            Frame& rows) const;
};

/// The device half of a RenderContext.
class ContextImpl {
  public:
    virtual ~ContextImpl() = default;
    /// Uploads a mesh (with normals) for frames rendered with `options` (culling final).
    virtual std::unique_ptr<RenderBackend> make_backend(const Mesh& mesh,
                                                        const FrameOptions& options) = 0;
    [[nodiscard]] virtual std::vector<std::string> validation_messages() const { return {}; }
};

/// Creates the Vulkan device of a context; fills device_name / device_type and the raster
/// (options.raster resolved).
std::unique_ptr<ContextImpl> make_vulkan_context(const ContextOptions& options,
                                                 std::string& device_name, std::string& device_type,
                                                 Raster& raster);
/// Creates the Embree device of a context; fills device_name / device_type.
std::unique_ptr<ContextImpl> make_embree_context(const ContextOptions& options,
                                                 std::string& device_name,
                                                 std::string& device_type);

/// Process-wide creation counts (render_context_stats()).
struct CreationCounters {
    std::atomic<std::size_t> contexts{0};
    std::atomic<std::size_t> vulkan_instances{0};
    std::atomic<std::size_t> vulkan_devices{0};
    std::atomic<std::size_t> embree_devices{0};
    std::atomic<std::size_t> embree_scenes{0};
};
CreationCounters& creation_counters();

/// Threads to use for CPU work given ContextOptions::threads (0 = hardware concurrency).
int worker_count(int requested);

/// Runs body(begin, end) over [0, count) split into `threads` contiguous chunks.
void parallel_for(int count, int threads, const std::function<void(int begin, int end)>& body);

/// Resolves sub-sample buffers of a (width·s) × (height·s) image into `frame` (sized
/// width × height). normal_depth: 4 floats per sub-sample (unit normal xyz, linear depth);
/// ids: one per sub-sample, kNoPrimitive where uncovered. See render/frame.h for the rules.
void resolve_samples(const float* normal_depth, const std::uint32_t* ids, int s, int threads,
                     Frame& frame);

/// Resolves output rows [y0, y1) of `frame`; the buffers start at sub-sample row y0·s.
void resolve_rows(const float* normal_depth, const std::uint32_t* ids, int s, int y0, int y1,
                  Frame& frame);

}  // namespace glint::detail
