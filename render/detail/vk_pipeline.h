// The normal pass's Vulkan objects shared by every mesh on a device (internal): render pass,
// pipeline layout (push constants only) and the graphics pipeline per cull mode, and the
// recording of one mesh's normal pass.
#pragma once

#include "render/view.h"
#include "spirv/bindings.h"
#include "spirv/shader_ids.h"

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>

namespace glint::detail {

struct PushConstants {
    float clip_from_world[16];  // column-major, as GLSL mat4
    float depth_row[4];
};
static_assert(sizeof(PushConstants) == GLINT_PUSH_CONSTANT_BYTES,
              "PushConstants must match shaders/bindings.h and normal.vert");
static_assert(offsetof(PushConstants, depth_row) == 64, "std430 push constant layout");

/// A shader module of SPIR-V compiled into the binary. \throw DeviceError.
VkShaderModule make_shader_module(VkDevice device, ShaderId id);

/// Who reads the colour attachments after the pass.
enum class TargetUse {
    ReadBack,  ///< copies to host buffers: left in TRANSFER_SRC (render/vulkan_backend.cpp)
    Compute,   ///< compute shaders as storage images: left in GENERAL (render/gpu_atlas.cpp)
};

/// Attachments: normal+depth RGBA32F and id R32_UINT (cleared, then read as `use` says),
/// depth D32 (cleared, discarded). \throw DeviceError.
VkRenderPass make_render_pass(VkDevice device, TargetUse use = TargetUse::ReadBack);
VkPipelineLayout make_pipeline_layout(VkDevice device);
/// normal.vert / normal.frag, two vertex streams (positions, normals), depth test LESS.
VkPipeline make_pipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass render_pass,
                         bool cull_back_faces);

/// A mesh's buffers on the device (vertex streams and indices of render/vulkan_backend.cpp).
struct MeshBuffers {
    VkBuffer positions = VK_NULL_HANDLE;  ///< float3 per vertex
    VkBuffer normals = VK_NULL_HANDLE;    ///< float3 per vertex
    VkBuffer indices = VK_NULL_HANDLE;    ///< uint3 per triangle
    std::uint32_t vertex_count = 0;
    std::uint32_t index_count = 0;  ///< 3 per triangle
};

/// normal.vert's push constants for a view: clip_from_world and the linear-depth row.
PushConstants normal_push_constants(const View& view);

/// Records the normal pass of one mesh seen from `view` into `framebuffer` (w × h sub-samples):
/// clear, one indexed draw of every triangle (gl_PrimitiveID = triangle index).
void record_normal_pass(VkCommandBuffer cmd, VkRenderPass render_pass, VkFramebuffer framebuffer,
                        int width, int height, VkPipeline pipeline, VkPipelineLayout layout,
                        const MeshBuffers& mesh, const View& view);

}  // namespace glint::detail
