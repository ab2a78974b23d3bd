#include "render/detail/vk_compute.h"

#include "render/detail/vk_check.h"
#include "render/detail/vk_pipeline.h"
#include "spirv/bindings.h"
#include "spirv/shader_ids.h"

#include <cstdint>
#include <vector>

namespace glint::detail {
namespace {

VkDescriptorSetLayout make_set_layout(VkDevice device) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (std::uint32_t b = 0; b < GLINT_ATLAS_BINDING_COUNT; ++b) {
        VkDescriptorSetLayoutBinding d{};
        d.binding = b;
        d.descriptorCount = 1;
        d.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        if (b == GLINT_ATLAS_BINDING_PARAMS) {
            d.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        } else if (b <= GLINT_ATLAS_BINDING_EXA_PRIMITIVE) {
            d.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        } else {
            d.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        }
        bindings.push_back(d);
    }
    VkDescriptorSetLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    info.bindingCount = static_cast<std::uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &layout));
    return layout;
}

VkPipelineLayout make_compute_layout(VkDevice device, VkDescriptorSetLayout set_layout) {
    VkPipelineLayoutCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    info.setLayoutCount = 1;
    info.pSetLayouts = &set_layout;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkCreatePipelineLayout(device, &info, nullptr, &layout));
    return layout;
}

}  // namespace

VkPipeline make_compute_pipeline(VkDevice device, VkPipelineLayout layout, ShaderId shader) {
    VkShaderModule module = make_shader_module(device, shader);
    VkComputePipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult r =
        vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(device, module, nullptr);
    if (r != VK_SUCCESS) vk_check_failed(r, "vkCreateComputePipelines", __FILE__, __LINE__);
    return pipeline;
}

AtlasPipelines make_atlas_pipelines(VkDevice device, VkPipelineLayout graphics_layout) {
    AtlasPipelines p;
    try {
        p.set_layout = make_set_layout(device);
        p.layout = make_compute_layout(device, p.set_layout);
        p.pixels = make_compute_pipeline(device, p.layout, ShaderId::atlas_pixels_comp);
        p.vertices = make_compute_pipeline(device, p.layout, ShaderId::atlas_vertices_comp);
        p.render_pass = make_render_pass(device, TargetUse::Compute);
        for (int cull = 0; cull < 2; ++cull) {
            p.graphics[static_cast<std::size_t>(cull)] =
                make_pipeline(device, graphics_layout, p.render_pass, cull == 1);
        }
    } catch (...) {
        destroy_atlas_pipelines(device, p);
        throw;
    }
    return p;
}

void destroy_atlas_pipelines(VkDevice device, AtlasPipelines& p) noexcept {
    for (VkPipeline g : p.graphics) {
        if (g != VK_NULL_HANDLE) vkDestroyPipeline(device, g, nullptr);
    }
    if (p.render_pass != VK_NULL_HANDLE) vkDestroyRenderPass(device, p.render_pass, nullptr);
    if (p.vertices != VK_NULL_HANDLE) vkDestroyPipeline(device, p.vertices, nullptr);
    if (p.pixels != VK_NULL_HANDLE) vkDestroyPipeline(device, p.pixels, nullptr);
    if (p.layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, p.layout, nullptr);
    if (p.set_layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, p.set_layout, nullptr);
    p = AtlasPipelines{};
}

void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags src_access,
             VkPipelineStageFlags dst, VkAccessFlags dst_access) {
    VkMemoryBarrier b{};
    b.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    b.srcAccessMask = src_access;
    b.dstAccessMask = dst_access;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace glint::detail
