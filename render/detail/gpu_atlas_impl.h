// The GPU atlas's device half (internal; render/gpu_atlas.h is the interface).
//
// Resources: per-vertex accumulators for every zoom (sums: int64 fixed point; words: 32-bit
// fields), this view's per-vertex scratch (maximum key, best incidence) and per-pixel
// comparison, and two slots, each with its own targets (reference and examined sub-samples),
// view parameters, summary buffers, descriptor set, command buffer and fence.
//
// One command buffer per view (slot i % 2), in this order:
//   [first view: clear the accumulators]
//   barrier   previous view's passes and copies → this view's fill and passes
//   fill      the slot's summary ← 0; barrier → the pixel pass
//   draw      reference, examined (render pass TargetUse::Compute: its dependencies order the
//             colour writes before the passes' imageLoad, and the previous reads of these
//             targets before the clear); with Raster::Compute the compute rasteriser's passes
//             of both meshes instead (detail/vk_raster.h), with the same ordering
//   dispatch  atlas_pixels.comp; barrier → atlas_vertices.comp
//   dispatch  atlas_vertices.comp; barrier → transfer
//   copy      summary → host-visible summary; barrier → host
// The CPU records view i + 1 while the device runs view i; it reads view i's 32-byte summary
// once view i's fence signals.
#pragma once

#include "render/detail/gpu_atlas_layout.h"
#include "render/detail/vk_context.h"
#include "render/detail/vk_memory.h"
#include "render/gpu_atlas.h"

#include <vulkan/vulkan.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace glint::detail {

/// The smallest b with 2^b ≥ x (x > 0).
inline int bits_for(double x) {
    int e = 0;
    const double m = std::frexp(x, &e);
    return m == 0.5 ? e - 1 : e;
}

class GpuAtlasImpl {
  public:
    /// \throw DeviceError (what was created is released first).
    GpuAtlasImpl(const VulkanMesh& reference, const VulkanMesh& examined, const FrameOptions& frame,
                 const GpuAtlasOptions& options);
    ~GpuAtlasImpl();
    GpuAtlasImpl(const GpuAtlasImpl&) = delete;
    GpuAtlasImpl& operator=(const GpuAtlasImpl&) = delete;

    void run(std::span<const View> views, const GpuViewConsumer& consumer);
    [[nodiscard]] std::vector<AtlasTotals> read_totals();
    [[nodiscard]] const GpuAtlasTimings& timings() const { return timings_; }

  private:
    struct Target {
        Image normal_depth, primitive, depth;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;  // Raster::Graphics
        RasterTarget raster;                         // Raster::Compute
        VkDescriptorSet raster_set = VK_NULL_HANDLE;
    };
    struct Slot {
        int width = 0;  // target size in sub-samples
        int height = 0;
        Target reference, examined;
        Buffer params;        // AtlasParams, host-visible
        Buffer summary;       // ViewTotals, device-local (atomics)
        Buffer summary_host;  // ViewTotals, host-visible copy
        VkDescriptorSet set = VK_NULL_HANDLE;
        bool set_current = false;  // the set names this slot's targets and the pixel buffer
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        VkQueryPool timestamps = VK_NULL_HANDLE;  // 4: start, rendered, pixels, vertices
        bool busy = false;
        std::size_t view = 0;      // index into run()'s span
        double angle_scale = 1.0;  // of the view in flight
    };
    /// Fixed-point scales of one zoom (powers of two; render/gpu_atlas.h "precision").
    struct Scales {
        double weight = 1.0;
        double value = 1.0;
        double depth = 1.0;
    };

    void create_shared();
    void create_slot(Slot& slot);
    void release() noexcept;
    void destroy_target(Target& target) noexcept;
    void make_target(Target& target, const MeshBuffers& mesh, int width, int height);
    void ensure_targets(Slot& slot, int width, int height);
    void ensure_pixels(std::size_t pixel_count);
    void write_set(Slot& slot);
    [[nodiscard]] std::vector<Scales> scales_for(std::span<const View> views) const;
    void write_params(Slot& slot, const View& view, const Scales& scales);
    void record(Slot& slot, const View& view, bool clear_first);
    void record_clear(VkCommandBuffer cmd);
    void record_frames(Slot& slot, const View& view);
    void wait(Slot& slot);
    [[nodiscard]] ViewNumbers finish(Slot& slot);
    void add_timings(const Slot& slot);
    [[nodiscard]] std::vector<AtlasTotals> totals_from(const std::int64_t* sums,
                                                       const std::uint32_t* words) const;
    void wait_all() noexcept;

    VulkanMesh reference_;
    VulkanMesh examined_;
    std::shared_ptr<VulkanDevice> device_;
    const AtlasPipelines* pipelines_ = nullptr;
    const RasterPipelines* raster_ = nullptr;  // Raster::Compute: the normal passes in compute
    int supersample_ = 1;
    GpuAtlasOptions options_;
    float mask_threshold_ = 0.0f;  // the frame options' coverage mask (render/renderer.cpp)
    std::vector<Scales> scales_;   // of the last run, per zoom
    bool has_run_ = false;
    GpuAtlasTimings timings_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    Buffer sums_, words_, scratch_key_, scratch_cos_, pixels_;
    // read_totals()'s host-visible copy, made at its first call and kept: a fresh 28 MB
    // allocation (1M triangles) per sweep is pinned and mapped anew each time.
    Buffer staging_;
    std::vector<Slot> slots_;  // GpuAtlasOptions::in_flight
};

}  // namespace glint::detail
