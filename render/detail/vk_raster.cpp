#include "render/detail/vk_raster.h"

#include "render/detail/vk_check.h"
#include "render/detail/vk_compute.h"
#include "render/detail/vk_device.h"
#include "spirv/bindings.h"
#include "spirv/shader_ids.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

namespace glint::detail {

RasterPipelines make_raster_pipelines(VkDevice device, const VkPhysicalDeviceLimits& limits) {
    RasterPipelines p;
    p.max_groups_x = limits.maxComputeWorkGroupCount[0];
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        for (std::uint32_t b = 0; b < GLINT_RASTER_BINDING_COUNT; ++b) {
            VkDescriptorSetLayoutBinding d{};
            d.binding = b;
            d.descriptorCount = 1;
            d.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
            d.descriptorType = b >= GLINT_RASTER_BINDING_NORMAL_DEPTH
                                   ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
                                   : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            bindings.push_back(d);
        }
        VkDescriptorSetLayoutCreateInfo set{};
        set.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        set.bindingCount = static_cast<std::uint32_t>(bindings.size());
        set.pBindings = bindings.data();
        GLINT_VK_CHECK(vkCreateDescriptorSetLayout(device, &set, nullptr, &p.set_layout));
        const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                        sizeof(RasterPushConstants)};
        VkPipelineLayoutCreateInfo layout{};
        layout.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        layout.setLayoutCount = 1;
        layout.pSetLayouts = &p.set_layout;
        layout.pushConstantRangeCount = 1;
        layout.pPushConstantRanges = &range;
        GLINT_VK_CHECK(vkCreatePipelineLayout(device, &layout, nullptr, &p.layout));
        p.triangles = make_compute_pipeline(device, p.layout, ShaderId::raster_triangles_comp);
        p.large = make_compute_pipeline(device, p.layout, ShaderId::raster_large_comp);
        p.attributes = make_compute_pipeline(device, p.layout, ShaderId::raster_attributes_comp);
    } catch (...) {
        destroy_raster_pipelines(device, p);
        throw;
    }
    return p;
}

void destroy_raster_pipelines(VkDevice device, RasterPipelines& p) noexcept {
    for (VkPipeline q : {p.triangles, p.large, p.attributes}) {
        if (q != VK_NULL_HANDLE) vkDestroyPipeline(device, q, nullptr);
    }
    if (p.layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device, p.layout, nullptr);
    if (p.set_layout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device, p.set_layout, nullptr);
    p = RasterPipelines{};
}

void make_raster_target(VkDevice device, VkPhysicalDevice physical, RasterTarget& target,
                        VkDescriptorSet set, const MeshBuffers& mesh, int width, int height,
                        VkImageView normal_depth, VkImageView primitive) {
    destroy_raster_target(device, target);
    try {
        const VkDeviceSize samples =
            static_cast<VkDeviceSize>(width) * static_cast<VkDeviceSize>(height);
        target.visibility =
            make_buffer(device, physical, samples * 8,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        const VkDeviceSize triangles = mesh.index_count / 3;
        target.large =
            make_buffer(device, physical, 16 + 4 * triangles,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                            VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    } catch (...) {
        destroy_raster_target(device, target);
        throw;
    }
    target.set = set;
    const std::array<VkBuffer, kRasterStorageBuffers> buffers{
        mesh.positions, mesh.normals, mesh.indices, target.visibility.buffer, target.large.buffer};
    static_assert(GLINT_RASTER_BINDING_POSITIONS == 0 && GLINT_RASTER_BINDING_NORMALS == 1 &&
                      GLINT_RASTER_BINDING_INDICES == 2 && GLINT_RASTER_BINDING_VISIBILITY == 3 &&
                      GLINT_RASTER_BINDING_LARGE == 4,
                  "the buffers above are in binding order");
    std::array<VkDescriptorBufferInfo, kRasterStorageBuffers> buffer_infos{};
    std::array<VkDescriptorImageInfo, kRasterStorageImages> image_infos{{
        {VK_NULL_HANDLE, normal_depth, VK_IMAGE_LAYOUT_GENERAL},
        {VK_NULL_HANDLE, primitive, VK_IMAGE_LAYOUT_GENERAL},
    }};
    std::array<VkWriteDescriptorSet, GLINT_RASTER_BINDING_COUNT> writes{};
    for (std::uint32_t i = 0; i < writes.size(); ++i) {
        VkWriteDescriptorSet& w = writes[i];
        w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        w.dstSet = set;
        w.dstBinding = i;
        w.descriptorCount = 1;
        if (i < kRasterStorageBuffers) {
            buffer_infos[i] = {buffers[i], 0, VK_WHOLE_SIZE};
            w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            w.pBufferInfo = &buffer_infos[i];
        } else {
            w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            w.pImageInfo = &image_infos[i - kRasterStorageBuffers];
        }
    }
    vkUpdateDescriptorSets(device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                           nullptr);
}

void destroy_raster_target(VkDevice device, RasterTarget& target) noexcept {
    destroy_buffer(device, target.visibility);
    destroy_buffer(device, target.large);
    target.set = VK_NULL_HANDLE;
}

namespace {

// Barrier: the previous frame's passes wrote and read the buffers, and `earlier` read the
// images, before the fills and the attribute pass overwrite them, and what `earlier` wrote is
// visible to this frame's passes; the images' contents are discarded (UNDEFINED → GENERAL) since
// the attribute pass writes every sub-sample. Then the visibility buffers are cleared, the large
// passes' indirect dispatches reset and the caller's `zero` buffers zeroed.
void record_clear_targets(VkCommandBuffer cmd, std::span<const RasterJob> jobs,
                          VkPipelineStageFlags earlier, std::span<const VkBuffer> zero) {
    std::vector<VkImageMemoryBarrier> images;
    for (const RasterJob& job : jobs) {
        for (VkImage image : {job.normal_depth, job.primitive}) {
            VkImageMemoryBarrier b{};
            b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
            b.srcAccessMask = 0;
            b.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
            b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = image;
            b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            images.push_back(b);
        }
    }
    VkMemoryBarrier before{};
    before.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    before.dstAccessMask =
        VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, earlier | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                         1, &before, 0, nullptr, static_cast<std::uint32_t>(images.size()),
                         images.data());
    for (const RasterJob& job : jobs) {
        const RasterTarget& t = *job.target;
        vkCmdFillBuffer(cmd, t.visibility.buffer, 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);
        // The large pass's indirect dispatch (0, split, 1) and the list's count 0.
        vkCmdFillBuffer(cmd, t.large.buffer, 0, 4, 0u);
        vkCmdFillBuffer(cmd, t.large.buffer, 4, 4, GLINT_RASTER_LARGE_SPLIT);
        vkCmdFillBuffer(cmd, t.large.buffer, 8, 4, 1u);
        vkCmdFillBuffer(cmd, t.large.buffer, 12, 4, 0u);
    }
    for (VkBuffer b : zero) vkCmdFillBuffer(cmd, b, 0, VK_WHOLE_SIZE, 0u);
}

}  // namespace

void record_compute_normal_passes(VkCommandBuffer cmd, const RasterPipelines& pipelines,
                                  std::span<const RasterJob> jobs, int width, int height,
                                  const View& view, VkPipelineStageFlags earlier,
                                  std::span<const VkBuffer> zero, VkPipelineStageFlags later_stages,
                                  VkAccessFlags later_access) {
    const PushConstants normal = normal_push_constants(view);
    RasterPushConstants pc{};
    std::memcpy(pc.clip_from_world, normal.clip_from_world, sizeof(pc.clip_from_world));
    std::memcpy(pc.depth_row, normal.depth_row, sizeof(pc.depth_row));
    pc.size[0] = static_cast<std::uint32_t>(width);
    pc.size[1] = static_cast<std::uint32_t>(height);
    const auto push = [&](const RasterJob& job) {
        pc.size[2] = job.mesh->index_count / 3;
        pc.size[3] = job.cull_back_faces ? GLINT_RASTER_CULL : 0u;
        vkCmdPushConstants(cmd, pipelines.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.layout, 0, 1,
                                &job.target->set, 0, nullptr);
    };

    record_clear_targets(cmd, jobs, earlier, zero);
    // Barrier: the fills before the small pass's atomics on both buffers (and before the
    // caller's shaders that use the buffers in `zero`).
    barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.triangles);
    for (const RasterJob& job : jobs) {
        push(job);
        vkCmdDispatch(
            cmd,
            std::min(groups(job.mesh->index_count / 3, GLINT_RASTER_GROUP), pipelines.max_groups_x),
            1, 1);
    }
    // Barrier: the small pass's list (read as the indirect dispatch and by the large pass) and
    // its visibility writes (the large pass's atomics follow them).
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.large);
    for (const RasterJob& job : jobs) {
        push(job);
        vkCmdDispatchIndirect(cmd, job.target->large.buffer, 0);
    }
    // Barrier: the visibility buffer complete before the attribute pass reads it.
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.attributes);
    for (const RasterJob& job : jobs) {
        push(job);
        vkCmdDispatch(cmd, groups(static_cast<std::uint32_t>(width), GLINT_RASTER_TILE),
                      groups(static_cast<std::uint32_t>(height), GLINT_RASTER_TILE), 1);
    }
    // Barrier: the images' writes before whoever reads the frame.
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, later_stages,
            later_access);
}

}  // namespace glint::detail
