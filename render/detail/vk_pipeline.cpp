// The normal pass's render pass and graphics pipeline (see render/vulkan_backend.cpp for the
// image layouts and the frames in flight they serve).
#include "render/detail/vk_pipeline.h"

#include "mesh/mesh.h"
#include "render/detail/vk_check.h"
#include "render/detail/vk_device.h"
#include "spirv/bindings.h"
#include "spirv/shader_ids.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace glint::detail {

VkShaderModule make_shader_module(VkDevice device, ShaderId id) {
    const auto code = spirv(id);
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = code.size_bytes();
    info.pCode = code.data();
    VkShaderModule module = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

namespace {

/// The fixed-function state of the pipeline; pointers into `self` stay valid while it lives.
struct FixedState {
    std::array<VkVertexInputBindingDescription, 2> bindings{};
    std::array<VkVertexInputAttributeDescription, 2> attrs{};
    VkPipelineVertexInputStateCreateInfo vi{};
    VkPipelineInputAssemblyStateCreateInfo ia{};
    VkPipelineViewportStateCreateInfo vp{};
    VkPipelineRasterizationStateCreateInfo rs{};
    VkPipelineMultisampleStateCreateInfo ms{};
    VkPipelineDepthStencilStateCreateInfo ds{};
    std::array<VkPipelineColorBlendAttachmentState, 2> blend{};
    VkPipelineColorBlendStateCreateInfo cb{};
    std::array<VkDynamicState, 2> dyn{};
    VkPipelineDynamicStateCreateInfo dy{};

    explicit FixedState(bool cull_back_faces);
    FixedState(const FixedState&) = delete;
    FixedState& operator=(const FixedState&) = delete;
};

FixedState::FixedState(bool cull_back_faces) {
    bindings = {{
        {GLINT_BINDING_POSITION, sizeof(Vec3f), VK_VERTEX_INPUT_RATE_VERTEX},
        {GLINT_BINDING_NORMAL, sizeof(Vec3f), VK_VERTEX_INPUT_RATE_VERTEX},
    }};
    attrs = {{
        {GLINT_BINDING_POSITION, GLINT_BINDING_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 0},
        {GLINT_BINDING_NORMAL, GLINT_BINDING_NORMAL, VK_FORMAT_R32G32B32_SFLOAT, 0},
    }};
    vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    vi.vertexBindingDescriptionCount = 2;
    vi.pVertexBindingDescriptions = bindings.data();
    vi.vertexAttributeDescriptionCount = 2;
    vi.pVertexAttributeDescriptions = attrs.data();
    ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = cull_back_faces ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
    // note: clip_from_world flips y (Vulkan's framebuffer y points down) and Vulkan's
    // signed-area formula carries a minus sign for that reason, so a triangle that is
    // counter-clockwise seen from outside stays counter-clockwise here (checked by
    // RendererTest.BackFaceCullingLeavesAClosedMeshUnchanged).
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    ds.depthTestEnable = VK_TRUE;
    ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = VK_COMPARE_OP_LESS;
    blend[0].colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                              VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    // note: without the independentBlend feature every attachment's state must be equal;
    // the id attachment simply ignores the components it does not have.
    blend[1] = blend[0];
    cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    cb.attachmentCount = 2;
    cb.pAttachments = blend.data();
    dyn = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dy.dynamicStateCount = static_cast<std::uint32_t>(dyn.size());
    dy.pDynamicStates = dyn.data();
}

}  // namespace

VkRenderPass make_render_pass(VkDevice device, TargetUse use) {
    const bool compute = use == TargetUse::Compute;
    std::array<VkAttachmentDescription, 3> att{};
    for (int i = 0; i < 2; ++i) {
        att[static_cast<std::size_t>(i)].format = i == 0 ? kNormalFormat : kIdFormat;
        att[static_cast<std::size_t>(i)].samples = VK_SAMPLE_COUNT_1_BIT;
        att[static_cast<std::size_t>(i)].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att[static_cast<std::size_t>(i)].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        att[static_cast<std::size_t>(i)].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att[static_cast<std::size_t>(i)].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[static_cast<std::size_t>(i)].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        // Left ready for vkCmdCopyImageToBuffer, or for imageLoad in the compute passes.
        att[static_cast<std::size_t>(i)].finalLayout =
            compute ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    att[2].format = kDepthFormat;
    att[2].samples = VK_SAMPLE_COUNT_1_BIT;
    att[2].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    att[2].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[2].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    att[2].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    att[2].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    att[2].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    std::array<VkAttachmentReference, 2> color_refs{{
        {GLINT_ATTACHMENT_NORMAL_DEPTH, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
        {GLINT_ATTACHMENT_PRIMITIVE, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
    }};
    VkAttachmentReference depth_ref{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 2;
    subpass.pColorAttachments = color_refs.data();
    subpass.pDepthStencilAttachment = &depth_ref;
    const VkPipelineStageFlags reader =
        compute ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT : VK_PIPELINE_STAGE_TRANSFER_BIT;
    std::array<VkSubpassDependency, 2> deps{};
    // In: the previous view in these targets read the colour images (a transfer, or the
    // compute passes) and wrote depth; the clear (and layout transition) must wait for both.
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = reader | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    deps[0].dstStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    deps[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    // Out: colour writes must be complete and visible before the copy to the read-back
    // buffers, or before the compute passes' imageLoad (the transition to the final layout
    // happens inside this dependency).
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].dstStageMask = reader;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstAccessMask = compute ? VK_ACCESS_SHADER_READ_BIT : VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    rp.attachmentCount = static_cast<std::uint32_t>(att.size());
    rp.pAttachments = att.data();
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = static_cast<std::uint32_t>(deps.size());
    rp.pDependencies = deps.data();
    VkRenderPass render_pass = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkCreateRenderPass(device, &rp, nullptr, &render_pass));
    return render_pass;
}

VkPipelineLayout make_pipeline_layout(VkDevice device) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(PushConstants)};
    VkPipelineLayoutCreateInfo pl{};
    pl.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pl.pushConstantRangeCount = 1;
    pl.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkCreatePipelineLayout(device, &pl, nullptr, &layout));
    return layout;
}

VkPipeline make_pipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass render_pass,
                         bool cull_back_faces) {
    VkShaderModule vert = make_shader_module(device, ShaderId::normal_vert);
    VkShaderModule frag = VK_NULL_HANDLE;
    try {
        frag = make_shader_module(device, ShaderId::normal_frag);
    } catch (...) {
        vkDestroyShaderModule(device, vert, nullptr);
        throw;
    }
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1] = stages[0];
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;

    const FixedState f(cull_back_faces);
    VkGraphicsPipelineCreateInfo gp{};
    gp.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    gp.stageCount = 2;
    gp.pStages = stages.data();
    gp.pVertexInputState = &f.vi;
    gp.pInputAssemblyState = &f.ia;
    gp.pViewportState = &f.vp;
    gp.pRasterizationState = &f.rs;
    gp.pMultisampleState = &f.ms;
    gp.pDepthStencilState = &f.ds;
    gp.pColorBlendState = &f.cb;
    gp.pDynamicState = &f.dy;
    gp.layout = layout;
    gp.renderPass = render_pass;
    gp.subpass = 0;
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult r =
        vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &gp, nullptr, &pipeline);
    vkDestroyShaderModule(device, vert, nullptr);
    vkDestroyShaderModule(device, frag, nullptr);
    if (r != VK_SUCCESS) vk_check_failed(r, "vkCreateGraphicsPipelines", __FILE__, __LINE__);
    return pipeline;
}

PushConstants normal_push_constants(const View& view) {
    const Camera& cam = view.camera;
    PushConstants pc{};
    const Eigen::Matrix4f clip = cam.clip_from_world().cast<float>();
    std::memcpy(pc.clip_from_world, clip.data(), sizeof(pc.clip_from_world));
    // depth = −z_camera = −(row 2 of camera_from_world) · (p, 1)
    const Eigen::Matrix4d camera_from_world = cam.world_from_camera.inverse().matrix();
    for (int k = 0; k < 4; ++k) pc.depth_row[k] = static_cast<float>(-camera_from_world(2, k));
    return pc;
}

void record_normal_pass(VkCommandBuffer cmd, VkRenderPass render_pass, VkFramebuffer framebuffer,
                        int width, int height, VkPipeline pipeline, VkPipelineLayout layout,
                        const MeshBuffers& mesh, const View& view) {
    const PushConstants pc = normal_push_constants(view);

    std::array<VkClearValue, 3> clears{};
    clears[0].color.float32[0] = clears[0].color.float32[1] = clears[0].color.float32[2] = 0.0f;
    clears[0].color.float32[3] = 0.0f;
    clears[1].color.uint32[0] = GLINT_NO_PRIMITIVE;
    clears[2].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = render_pass;
    rp.framebuffer = framebuffer;
    rp.renderArea = {{0, 0},
                     {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)}};
    rp.clearValueCount = static_cast<std::uint32_t>(clears.size());
    rp.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height),
                        0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &rp.renderArea);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(pc), &pc);
    std::array<VkBuffer, 2> vbs{mesh.positions, mesh.normals};
    std::array<VkDeviceSize, 2> offsets{0, 0};
    vkCmdBindVertexBuffers(cmd, 0, 2, vbs.data(), offsets.data());
    vkCmdBindIndexBuffer(cmd, mesh.indices, 0, VK_INDEX_TYPE_UINT32);
    // One draw of every triangle from index 0, so gl_PrimitiveID is the triangle index.
    vkCmdDrawIndexed(cmd, mesh.index_count, 1, 0, 0, 0);
    vkCmdEndRenderPass(cmd);
}

}  // namespace glint::detail
