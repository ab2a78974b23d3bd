// The GPU atlas: compare and back-projection on the device, so that a sweep's frames never
// leave it (DESIGN.md "back-projection"; issue 13).
//
// Per view, one command buffer renders the reference and the examined mesh into sub-sample
// targets that stay in device memory, then two compute passes do what the read-back path does
// on the CPU (render/detail/resolve.cpp, scanner/compare.*, scanner/metric.*,
// scanner/backproject.*, scanner/atlas.*):
//
//   atlas_pixels.comp    per output pixel: the s×s resolve of both frames (mean normal,
//                        renormalised; depth; coverage; centre primitive), the comparison
//                        (silhouette, angle, signed depth, the metric), and the scatter of the
//                        pixel's value onto its reference triangle's vertices (barycentric
//                        weights of the pixel-centre ray, incidence rule) with atomics; the
//                        view's numbers (ViewNumbers) reduced per workgroup.
//   atlas_vertices.comp  per reference vertex: the gather of vertices that no pixel centre fell
//                        on, and the fold of this view's per-vertex maximum and most frontal
//                        observation into the sweep's (first view wins ties, as on the CPU).
//
// Only the per-view summary (32 bytes) crosses the bus per view, and the per-vertex totals
// once per sweep (read_totals).
//
// Measured on an NVIDIA H100 (driver 580, bench/render_gpu_atlas_bench.cpp: bumpy sphere pair,
// 60-view sweeps, s = 1, medians of 7), views/s of run() + read_totals(), graphics pipeline →
// compute rasteriser (render/context.h Raster): 100k triangles 512² 1668 → 10054, 1024² 612 →
// 5441; 1M 512² 382 → 5798, 1024² 282 → 4082 (4803 for run() alone). Device time per view at
// 1M, 1024², compute: normal passes 0.108 ms, pixel pass 0.063, vertex pass 0.015; the rest of
// a view's 0.208 ms (0.022: submission, the summary's copy, barriers) lies between the stages'
// timestamps. read_totals() at 1M triangles: 2.3 ms per sweep (copy 0.66, conversion 1.58).
//
// Precision (what differs from the CPU path, and by how much):
// - sums (weight, weight·value, missing weight, weight·signed depth) are 64-bit fixed point
//   accumulated with integer atomics, so they do not depend on the order the device runs in;
//   the scale is the largest power of two for which no sum can overflow (AtlasTotals::
//   *_resolution give the step: each observation is rounded to half a step, where the CPU
//   rounds its double sums to half an ulp);
// - everything else is computed with the CPU path's operations in the same order (float where
//   it uses float, double where it uses double, no fused multiply-add), so on an IEEE device
//   (lavapipe) the per-pixel angles, weights, counts, maxima and views equal the CPU's; the
//   one function written differently is acos (a series in double, within 2 ulp of libm's), so a
//   pixel angle may differ from the CPU's by one float ulp. Devices whose double division and
//   square root are not correctly rounded differ by a few more ulps.
//
// Requirements: the Vulkan backend, both renderers on one context, world-space normals, a metric
// with a kernel here (has_gpu_kernel), and a device with shaderFloat64, shaderInt64 and
// shaderBufferInt64Atomics (GpuAtlas::supported()).
#pragma once

#include "render/atlas_totals.h"
#include "render/renderer.h"
#include "render/view.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint {

/// Whether the passes compute `metric` on the device (a metric without a kernel here makes
/// GpuAtlas::supported() refuse, naming it, rather than fold another metric).
[[nodiscard]] bool has_gpu_kernel(Metric metric);

struct GpuAtlasOptions {
    Metric metric = Metric::AngleDeg;
    /// Value of a reference pixel with no examined surface behind it.
    float missing_value = 90.0f;
    /// A pixel counts as covered (compared, scattered) at this share of its sub-samples.
    float min_coverage = 0.999f;
    /// cos of the largest incidence at which a pixel or vertex is an observation (> 0).
    double min_cos_incidence = 0.2588;
    /// Radius of the sweep's framed sphere (the gather pass's depth tolerance).
    double framed_radius = 1.0;
    /// Atlases kept: View::zoom_index selects one, 0 … zoom_count − 1.
    int zoom_count = 1;
    /// Views submitted ahead of the one whose summary is awaited (1..8), each with its own
    /// targets: more hide the host's latency between views at the cost of target memory
    /// ((8 + 20) bytes per sub-sample and mesh per view with the compute rasteriser).
    int in_flight = 2;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// Device time of the last run() by stage, from timestamps written between them (each stage
/// from the end of the one before, so waits on the previous view are not counted). Zero and
/// measured = false when the queue writes no timestamps.
struct GpuAtlasTimings {
    bool measured = false;
    std::size_t views = 0;
    double render_s = 0.0;    ///< both normal passes
    double pixels_s = 0.0;    ///< atlas_pixels.comp: resolve, compare, scatter
    double vertices_s = 0.0;  ///< atlas_vertices.comp: gather, fold
    /// Wall time of the last read_totals(): the copy to host memory (submit to fence) and the
    /// conversion into AtlasTotals (host clock, measured whether or not timestamps are).
    double totals_copy_s = 0.0;
    double totals_convert_s = 0.0;
    /// Host wall time of the last run() waiting for views' fences, and the rest of it (view
    /// parameters, recording, submission, timestamps, the consumer).
    double host_wait_s = 0.0;
    double host_work_s = 0.0;
};

/// Called in view order after the device finished a view: its index in the span given to
/// run() and its numbers. May throw to stop the run (the device is drained first).
using GpuViewConsumer = std::function<void(std::size_t view_index, const ViewNumbers& summary)>;

namespace detail {
class GpuAtlasImpl;
struct VulkanMesh;
}  // namespace detail

/// The per-vertex accumulators of a sweep on the reference renderer's device. Move-only; the
/// renderers must outlive it (it draws with their meshes) and stay on one thread with it.
class GpuAtlas {
  public:
    /// Whether the GPU atlas can run for this pair of renderers and options; `why` receives
    /// the reason when it cannot (Embree backend, two contexts, view-space normals, different
    /// supersampling, a device without the features, buffers beyond the device's limits).
    [[nodiscard]] static bool supported(const Renderer& reference, const Renderer& examined,
                                        const GpuAtlasOptions& options, std::string* why = nullptr);

    /// Allocates the per-vertex buffers (zoom_count × 64 bytes per reference vertex) and
    /// compiles the passes at the first use on a device.
    /// \throw InputError invalid options, renderers that supported() refuses;
    /// \throw DeviceError a failed device call.
    GpuAtlas(Renderer& reference, Renderer& examined, const GpuAtlasOptions& options);
    ~GpuAtlas();
    GpuAtlas(GpuAtlas&&) noexcept;
    GpuAtlas& operator=(GpuAtlas&&) noexcept;
    GpuAtlas(const GpuAtlas&) = delete;
    GpuAtlas& operator=(const GpuAtlas&) = delete;

    /// Clears the accumulators, then renders and folds every view (in_flight at a time), handing
    /// each view's summary to `consumer` in order. View::index is the view id recorded in
    /// max_view / best_view; View::zoom_index selects the atlas.
    /// \throw InputError a view's size or zoom; DeviceError; whatever the consumer throws.
    void run(std::span<const View> views, const GpuViewConsumer& consumer = {});

    /// Reads the totals of every zoom level back (once per sweep). \throw DeviceError.
    [[nodiscard]] std::vector<AtlasTotals> read_totals();

    /// Where the device spent the last run()'s time (benchmarks; see GpuAtlasTimings).
    [[nodiscard]] const GpuAtlasTimings& timings() const;

  private:
    /// The renderer's device buffers; null for a non-Vulkan (or moved-from) renderer.
    static const detail::VulkanMesh* vulkan_mesh(const Renderer& renderer);

    std::unique_ptr<detail::GpuAtlasImpl> impl_;
};

}  // namespace glint
