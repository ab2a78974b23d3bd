// The normal pass's Vulkan objects shared by every mesh on a device (internal): render pass,
// pipeline layout (push constants only) and the graphics pipeline per cull mode.
#pragma once

#include "spirv/bindings.h"

#include <vulkan/vulkan.h>

#include <cstddef>

namespace glint::detail {

struct PushConstants {
    float clip_from_world[16];  // column-major, as GLSL mat4
    float depth_row[4];
};
static_assert(sizeof(PushConstants) == GLINT_PUSH_CONSTANT_BYTES,
              "PushConstants must match shaders/bindings.h and normal.vert");
static_assert(offsetof(PushConstants, depth_row) == 64, "std430 push constant layout");

/// Attachments: normal+depth RGBA32F and id R32_UINT (cleared, left in TRANSFER_SRC for the
/// read-back copy), depth D32 (cleared, discarded). \throw DeviceError.
VkRenderPass make_render_pass(VkDevice device);
VkPipelineLayout make_pipeline_layout(VkDevice device);
/// normal.vert / normal.frag, two vertex streams (positions, normals), depth test LESS.
VkPipeline make_pipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass render_pass, bool cull_back_faces);

}  // namespace glint::detail
