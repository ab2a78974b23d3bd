// The compute rasteriser (internal; render/context.h Raster::Compute): its Vulkan objects shared
// on a device, one target's buffers, and the recording of one or more meshes' normal passes
// into colour images that the read-back copies or the GPU atlas's passes read, as the render
// pass would have left them.
//
// Per target: a visibility buffer (8 bytes per sub-sample: window depth bits << 32 | triangle)
// and the large-triangle list (16 bytes + 4 per triangle). Per frame, in one command buffer:
//   fill      visibility ← ~0 (no triangle), the large list's dispatch ← (0, split, 1), count ← 0
//   dispatch  raster_triangles.comp over the triangles (atomicMin into the visibility buffer)
//   dispatch  raster_large.comp, indirect (the triangles the first pass listed)
//   dispatch  raster_attributes.comp over the sub-samples → normal+depth, primitive images
// with a barrier between each; the meshes of one call share the barriers, so their dispatches
// run side by side.
#pragma once

#include "render/detail/vk_memory.h"
#include "render/detail/vk_pipeline.h"
#include "render/view.h"
#include "spirv/bindings.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace glint::detail {

/// The push constants of shaders/raster_common.glsl.
struct RasterPushConstants {
    float clip_from_world[16];  ///< column-major, as normal.vert's
    float depth_row[4];         ///< as normal.vert's
    std::uint32_t size[4];      ///< width, height (sub-samples), triangle count, GLINT_RASTER_*
};
static_assert(sizeof(RasterPushConstants) == GLINT_RASTER_PUSH_CONSTANT_BYTES,
              "RasterPushConstants must match shaders/raster_common.glsl");
static_assert(offsetof(RasterPushConstants, size) == 80, "std430 push constant layout");

struct RasterPipelines {
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;  ///< GLINT_RASTER_BINDING_*
    VkPipelineLayout layout = VK_NULL_HANDLE;           ///< one set + the push constants
    VkPipeline triangles = VK_NULL_HANDLE;              ///< raster_triangles.comp
    VkPipeline large = VK_NULL_HANDLE;                  ///< raster_large.comp
    VkPipeline attributes = VK_NULL_HANDLE;             ///< raster_attributes.comp
    std::uint32_t max_groups_x = 65535;  ///< the device's maxComputeWorkGroupCount[0]
};

/// \throw DeviceError (what was created is destroyed first).
RasterPipelines make_raster_pipelines(VkDevice device, const VkPhysicalDeviceLimits& limits);
/// Destroys and resets; null handles are skipped.
void destroy_raster_pipelines(VkDevice device, RasterPipelines& pipelines) noexcept;

/// Descriptors one target's set takes from a pool (VkDescriptorPoolSize counts).
constexpr std::uint32_t kRasterStorageBuffers = 5;
constexpr std::uint32_t kRasterStorageImages = 2;

/// One target of the compute rasteriser for one mesh.
struct RasterTarget {
    Buffer visibility;                     ///< uint64 per sub-sample
    Buffer large;                          ///< dispatch (3 × uint), count, triangles
    VkDescriptorSet set = VK_NULL_HANDLE;  ///< from the owner's pool (freed with it)
};

/// Creates the target's buffers for width × height sub-samples of `mesh` and points `set`
/// (allocated by the caller with RasterPipelines::set_layout) at them, the mesh and the
/// colour images. \throw DeviceError (the buffers are released first).
void make_raster_target(VkDevice device, VkPhysicalDevice physical, RasterTarget& target,
                        VkDescriptorSet set, const MeshBuffers& mesh, int width, int height,
                        VkImageView normal_depth, VkImageView primitive);
/// Releases the buffers (the set goes with its pool).
void destroy_raster_target(VkDevice device, RasterTarget& target) noexcept;

/// One mesh's frame in a recording.
struct RasterJob {
    const RasterTarget* target = nullptr;
    const MeshBuffers* mesh = nullptr;
    VkImage normal_depth = VK_NULL_HANDLE;  ///< kNormalFormat, storage usage
    VkImage primitive = VK_NULL_HANDLE;     ///< kIdFormat, storage usage
    bool cull_back_faces = false;
};

/// Records the normal pass of every job seen from `view` into its width × height target.
/// `earlier` are the stages that read or wrote the targets' images and buffers before (the
/// previous frame's read-back copy, or the GPU atlas's passes and copies): the clears wait for
/// them, and their writes are made visible to the passes after. `zero` are the caller's buffers
/// to clear to 0 along with the targets' (the GPU atlas's view summary), ready for the compute
/// shaders after the passes: one barrier serves both. The images end in
/// VK_IMAGE_LAYOUT_GENERAL with their writes visible to `later_stages` / `later_access`.
void record_compute_normal_passes(VkCommandBuffer cmd, const RasterPipelines& pipelines,
                                  std::span<const RasterJob> jobs, int width, int height,
                                  const View& view, VkPipelineStageFlags earlier,
                                  std::span<const VkBuffer> zero, VkPipelineStageFlags later_stages,
                                  VkAccessFlags later_access);

}  // namespace glint::detail
