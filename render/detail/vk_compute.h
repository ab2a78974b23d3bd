// The GPU atlas's Vulkan objects shared by every atlas on a device (internal): the descriptor
// set layout and the two compute passes (shaders/atlas_pixels.comp, atlas_vertices.comp), and
// the normal pass drawn into targets the compute passes read (render pass + graphics pipeline
// per cull mode). See render/gpu_atlas.cpp for the per-view command buffer they form.
#pragma once

#include "spirv/shader_ids.h"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

namespace glint::detail {

struct AtlasPipelines {
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;  ///< bindings of shaders/bindings.h
    VkPipelineLayout layout = VK_NULL_HANDLE;           ///< the compute passes' (one set)
    VkPipeline pixels = VK_NULL_HANDLE;                 ///< atlas_pixels.comp
    VkPipeline vertices = VK_NULL_HANDLE;               ///< atlas_vertices.comp
    VkRenderPass render_pass = VK_NULL_HANDLE;          ///< colour targets left in GENERAL
    std::array<VkPipeline, 2> graphics{};  ///< normal pass on render_pass, [cull_back_faces]
};

/// Creates them all; `graphics_layout` is the normal pass's push-constant layout.
/// \throw DeviceError (what was created is destroyed first).
AtlasPipelines make_atlas_pipelines(VkDevice device, VkPipelineLayout graphics_layout);

/// Destroys and resets; null handles are skipped.
void destroy_atlas_pipelines(VkDevice device, AtlasPipelines& pipelines) noexcept;

/// One global memory barrier (the call sites say what it protects).
void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access,
             VkPipelineStageFlags dst, VkAccessFlags dst_access);

/// Work groups of `size` invocations that cover `count` items.
inline std::uint32_t groups(std::uint32_t count, std::uint32_t size) {
    return (count + size - 1) / size;
}

/// A compute pipeline of one embedded shader (entry point main). \throw DeviceError.
VkPipeline make_compute_pipeline(VkDevice device, VkPipelineLayout layout, ShaderId shader);

}  // namespace glint::detail
