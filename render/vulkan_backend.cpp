// Vulkan backend: headless rasterisation of the normal pass on a GPU or on lavapipe.
//
// Per context (detail/vk_context.h): one VkInstance, one VkDevice and queue, the render pass,
// the pipeline layout and a pipeline per cull mode. Per renderer (this file): the mesh
// uploaded once into device-local vertex (positions, normals) and index buffers, a command
// pool and the slots below. Per view: push constants (clip_from_world, depth row).
//
// Frames in flight: two slots, each with its own targets, read-back buffers, command buffer
// and fence. View i renders in slot i % 2 while the CPU resolves and hands over view i − 1:
//
//   GPU/lavapipe:  [render 0][render 1][render 2] ...
//   CPU:                     [resolve 0, consume 0][resolve 1, consume 1] ...
//
// Two renderers on one context (render_view_pairs) submit view i of both before either
// waits; the queue runs them in submission order while the CPU resolves.
//
// Image layouts of one slot, per view (render pass + copies, one command buffer):
//
//   normal+depth RGBA32F, id R32_UINT:
//     UNDEFINED ──(render pass, clear)──▶ COLOR_ATTACHMENT ──(final layout)──▶ TRANSFER_SRC
//       ──vkCmdCopyImageToBuffer──▶ host-visible buffer ──(barrier: transfer → host)──▶ CPU
//   depth D32: UNDEFINED ──▶ DEPTH_STENCIL_ATTACHMENT (contents discarded)
//
// With Raster::Compute (render/context.h) the render pass is replaced by the compute
// rasteriser's passes (detail/vk_raster.h), which leave the colour images in GENERAL with the
// same contents; the copies read them from there.
//
// Sub-samples: the target is (w·s) × (h·s); the CPU resolve (detail/resolve.cpp) averages
// s×s blocks. lavapipe offers MSAA 1×/4× only and integer attachments 1× only, so true
#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/detail/vk_check.h"
#include "render/detail/vk_context.h"
#include "render/detail/vk_memory.h"
#include "render/detail/vk_pipeline.h"
#include "render/detail/vk_raster.h"
#include "spirv/bindings.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <deque>

namespace glint::detail {
namespace {

constexpr std::size_t kSlots = 2;

class VulkanBackend final : public RenderBackend {
  public:
    VulkanBackend(std::shared_ptr<VulkanDevice> device, const Mesh& mesh,
                  const FrameOptions& options)
        : options_(options), device_(std::move(device)) {
        try {
            compute_ = device_->raster() == Raster::Compute;
            create_slots();
            upload(mesh);
            if (compute_) {
                raster_ = &device_->raster_pipelines();
                create_raster_sets();
            } else {
                pipeline_ = device_->pipeline(options_.cull_back_faces);
            }
            vulkan_mesh_ = VulkanMesh{
                .device = device_, .buffers = mesh_, .cull_back_faces = options_.cull_back_faces};
        } catch (...) {
            release();  // the destructor does not run for a half-built object
            throw;
        }
    }

    ~VulkanBackend() override { release(); }
    VulkanBackend(const VulkanBackend&) = delete;
    VulkanBackend& operator=(const VulkanBackend&) = delete;

    [[nodiscard]] std::size_t max_in_flight() const override { return kSlots; }

    [[nodiscard]] const VulkanMesh* vulkan_mesh() const override { return &vulkan_mesh_; }

    void submit(const View& view) override {
        // Round robin: the next slot is free (the caller finished its view before).
        Slot& slot = slots_[next_slot_];
        GLINT_ASSERT(!slot.busy, "submit into a slot whose view was not finished");
        const int s = options_.supersample;
        ensure_targets(slot, view.camera.width * s, view.camera.height * s);
        record_and_submit(slot, view);
        slot.out_width = view.camera.width;
        slot.out_height = view.camera.height;
        slot.busy = true;
        pending_.push_back(next_slot_);
        next_slot_ = (next_slot_ + 1) % kSlots;
    }

    /// Waits for the oldest view, resolves it and returns its frame.
    Frame& finish() override {
        GLINT_ASSERT(!pending_.empty(), "finish without a submitted view");
        Slot& slot = slots_[pending_.front()];
        pending_.pop_front();
        const VkDevice dev = device_->device();
        GLINT_VK_CHECK(vkWaitForFences(dev, 1, &slot.fence, VK_TRUE, UINT64_MAX));
        GLINT_VK_CHECK(vkResetFences(dev, 1, &slot.fence));
        slot.busy = false;
        Frame& frame = slot.frame;
        if (frame.width != slot.out_width || frame.height != slot.out_height ||
            frame.coverage.size() != frame.pixel_count()) {
            frame = make_empty_frame(slot.out_width, slot.out_height);
        }
        frame.normal_space = NormalSpace::World;
        resolve_samples(static_cast<const float*>(slot.normal_readback.mapped),
                        static_cast<const std::uint32_t*>(slot.id_readback.mapped),
                        options_.supersample, device_->threads(), frame);
        return frame;
    }

    void abandon() noexcept override {
        // Wait for this renderer's own views only: the device and its queue are shared.
        wait_idle();
        pending_.clear();
        next_slot_ = 0;
    }

  private:
    struct Slot {
        int width = 0;  // target size in sub-samples
        int height = 0;
        Image normal, id, depth;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        Buffer normal_readback, id_readback;
        RasterTarget raster;  // Raster::Compute: visibility buffer, large list, set
        VkDescriptorSet raster_set = VK_NULL_HANDLE;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        bool busy = false;
        int out_width = 0;
        int out_height = 0;
        Frame frame;
    };

    void wait_idle() noexcept {
        const VkDevice dev = device_->device();
        for (auto& slot : slots_) {
            if (!slot.busy) continue;
            vkWaitForFences(dev, 1, &slot.fence, VK_TRUE, UINT64_MAX);
            vkResetFences(dev, 1, &slot.fence);
            slot.busy = false;
        }
    }

    void release() noexcept {
        const VkDevice dev = device_->device();
        wait_idle();
        for (auto& slot : slots_) {
            destroy_targets(slot);
            if (slot.fence != VK_NULL_HANDLE) vkDestroyFence(dev, slot.fence, nullptr);
            slot.fence = VK_NULL_HANDLE;
        }
        for (auto& b : mesh_buffers_) destroy_buffer(dev, b);
        if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(dev, pool_, nullptr);
        pool_ = VK_NULL_HANDLE;
        // Destroying the pool frees the slots' raster sets.
        if (descriptor_pool_ != VK_NULL_HANDLE)
            vkDestroyDescriptorPool(dev, descriptor_pool_, nullptr);
        descriptor_pool_ = VK_NULL_HANDLE;
    }

    /// Raster::Compute: one descriptor set per slot (bound to its targets in ensure_targets).
    void create_raster_sets() {
        const VkDevice dev = device_->device();
        const std::array<VkDescriptorPoolSize, 2> sizes{{
            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kRasterStorageBuffers * kSlots},
            {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kRasterStorageImages * kSlots},
        }};
        VkDescriptorPoolCreateInfo dp{};
        dp.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        dp.maxSets = kSlots;
        dp.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
        dp.pPoolSizes = sizes.data();
        GLINT_VK_CHECK(vkCreateDescriptorPool(dev, &dp, nullptr, &descriptor_pool_));
        for (auto& slot : slots_) {
            VkDescriptorSetAllocateInfo set{};
            set.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
            set.descriptorPool = descriptor_pool_;
            set.descriptorSetCount = 1;
            set.pSetLayouts = &raster_->set_layout;
            GLINT_VK_CHECK(vkAllocateDescriptorSets(dev, &set, &slot.raster_set));
        }
    }

    void create_slots() {
        const VkDevice dev = device_->device();
        VkCommandPoolCreateInfo pool{};
        pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = device_->queue_family();
        GLINT_VK_CHECK(vkCreateCommandPool(dev, &pool, nullptr, &pool_));
        for (auto& slot : slots_) {
            VkCommandBufferAllocateInfo alloc{};
            alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
            alloc.commandPool = pool_;
            alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
            alloc.commandBufferCount = 1;
            GLINT_VK_CHECK(vkAllocateCommandBuffers(dev, &alloc, &slot.cmd));
            VkFenceCreateInfo f{};
            f.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
            GLINT_VK_CHECK(vkCreateFence(dev, &f, nullptr, &slot.fence));
        }
    }

    void destroy_targets(Slot& slot) noexcept {
        const VkDevice dev = device_->device();
        if (slot.framebuffer != VK_NULL_HANDLE)
            vkDestroyFramebuffer(dev, slot.framebuffer, nullptr);
        slot.framebuffer = VK_NULL_HANDLE;
        destroy_image(dev, slot.normal);
        destroy_image(dev, slot.id);
        destroy_image(dev, slot.depth);
        destroy_buffer(dev, slot.normal_readback);
        destroy_buffer(dev, slot.id_readback);
        destroy_raster_target(dev, slot.raster);
        slot.width = slot.height = 0;
    }

    /// Copies the mesh into device-local buffers through one staging buffer.
    void upload(const Mesh& mesh) {
        const VkDevice dev = device_->device();
        const VkPhysicalDevice phys = device_->physical();
        static_assert(sizeof(Vec3f) == 12, "Mesh::positions must be tightly packed float3");
        static_assert(sizeof(Triangle) == 12, "Mesh::triangles must be tightly packed uint3");
        const VkDeviceSize pos_bytes = mesh.positions.size() * sizeof(Vec3f);
        const VkDeviceSize nrm_bytes = mesh.normals.size() * sizeof(Vec3f);
        const VkDeviceSize idx_bytes = mesh.triangles.size() * sizeof(Triangle);
        mesh_.index_count = static_cast<std::uint32_t>(mesh.triangles.size() * 3);
        mesh_.vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
        const VkMemoryPropertyFlags host =
            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        Buffer staging = make_buffer(dev, phys, pos_bytes + nrm_bytes + idx_bytes,
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT, host, 0);
        auto* dst = static_cast<unsigned char*>(staging.mapped);
        std::memcpy(dst, mesh.positions.data(), pos_bytes);
        std::memcpy(dst + pos_bytes, mesh.normals.data(), nrm_bytes);
        std::memcpy(dst + pos_bytes + nrm_bytes, mesh.triangles.data(), idx_bytes);
        // Storage too: the GPU atlas's compute passes read the reference mesh (render/gpu_atlas.h).
        const VkBufferUsageFlags vtx = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        mesh_buffers_[0] =
            make_buffer(dev, phys, pos_bytes, vtx, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        mesh_buffers_[1] =
            make_buffer(dev, phys, nrm_bytes, vtx, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        mesh_buffers_[2] =
            make_buffer(dev, phys, idx_bytes,
                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        mesh_.positions = mesh_buffers_[0].buffer;
        mesh_.normals = mesh_buffers_[1].buffer;
        mesh_.indices = mesh_buffers_[2].buffer;
        VkCommandBuffer cmd = slots_[0].cmd;
        VkCommandBufferBeginInfo begin{};
        begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        GLINT_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
        VkBufferCopy copy{0, 0, pos_bytes};
        vkCmdCopyBuffer(cmd, staging.buffer, mesh_buffers_[0].buffer, 1, &copy);
        copy = {pos_bytes, 0, nrm_bytes};
        vkCmdCopyBuffer(cmd, staging.buffer, mesh_buffers_[1].buffer, 1, &copy);
        copy = {pos_bytes + nrm_bytes, 0, idx_bytes};
        vkCmdCopyBuffer(cmd, staging.buffer, mesh_buffers_[2].buffer, 1, &copy);
        // Barrier: the copies' writes must be visible to vertex input (attribute and index
        // reads) of every later draw, and to the compute passes that read the mesh (the
        // compute rasteriser, the GPU atlas).
        VkMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT |
                                VK_ACCESS_SHADER_READ_BIT;
        vkCmdPipelineBarrier(
            cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
            &barrier, 0, nullptr, 0, nullptr);
        GLINT_VK_CHECK(vkEndCommandBuffer(cmd));
        device_->submit(cmd, slots_[0].fence);
        GLINT_VK_CHECK(vkWaitForFences(dev, 1, &slots_[0].fence, VK_TRUE, UINT64_MAX));
        GLINT_VK_CHECK(vkResetFences(dev, 1, &slots_[0].fence));
        destroy_buffer(dev, staging);
    }

    /// (Re)creates a slot's targets for a sub-sample size; the slot is idle here.
    void ensure_targets(Slot& slot, int w, int h) {
        const VkDevice dev = device_->device();
        const VkPhysicalDevice phys = device_->physical();
        if (slot.width == w && slot.height == h) return;
        if (static_cast<std::uint32_t>(std::max(w, h)) > device_->max_dimension()) {
            throw InputError("render target " + std::to_string(w) + "x" + std::to_string(h) +
                             " (size × supersample) exceeds the device limit of " +
                             std::to_string(device_->max_dimension()) + " pixels per side");
        }
        destroy_targets(slot);
        // Colour targets: attachments of the render pass, or storage images the compute
        // rasteriser writes.
        const VkImageUsageFlags color =
            VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
            (compute_ ? VK_IMAGE_USAGE_STORAGE_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        slot.normal = make_image(dev, phys, w, h, kNormalFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
        slot.id = make_image(dev, phys, w, h, kIdFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
        if (compute_) {
            make_raster_target(dev, phys, slot.raster, slot.raster_set, mesh_, w, h,
                               slot.normal.view, slot.id.view);
        } else {
            slot.depth =
                make_image(dev, phys, w, h, kDepthFormat,
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
            std::array<VkImageView, 3> views{slot.normal.view, slot.id.view, slot.depth.view};
            VkFramebufferCreateInfo fb{};
            fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
            fb.renderPass = device_->render_pass();
            fb.attachmentCount = 3;
            fb.pAttachments = views.data();
            fb.width = static_cast<std::uint32_t>(w);
            fb.height = static_cast<std::uint32_t>(h);
            fb.layers = 1;
            GLINT_VK_CHECK(vkCreateFramebuffer(dev, &fb, nullptr, &slot.framebuffer));
        }
        const VkDeviceSize pixels = static_cast<VkDeviceSize>(w) * static_cast<VkDeviceSize>(h);
        // Read-back: host-visible and coherent (no flush/invalidate needed), cached when the
        // device offers it (CPU reads of uncached memory are slow on discrete GPUs).
        const VkMemoryPropertyFlags host =
            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        slot.normal_readback = make_buffer(dev, phys, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           host, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        slot.id_readback = make_buffer(dev, phys, pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       host, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        slot.width = w;
        slot.height = h;
    }

    void record_and_submit(Slot& slot, const View& view) {
        VkCommandBuffer cmd = slot.cmd;
        GLINT_VK_CHECK(vkResetCommandBuffer(cmd, 0));
        VkCommandBufferBeginInfo begin{};
        begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        GLINT_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
        VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        if (compute_) {
            // The previous frame in this slot was read by its copies (earlier: transfer).
            const RasterJob job{.target = &slot.raster,
                                .mesh = &mesh_,
                                .normal_depth = slot.normal.image,
                                .primitive = slot.id.image,
                                .cull_back_faces = options_.cull_back_faces};
            record_compute_normal_passes(cmd, *raster_, {&job, 1}, slot.width, slot.height, view,
                                         VK_PIPELINE_STAGE_TRANSFER_BIT, {},
                                         VK_PIPELINE_STAGE_TRANSFER_BIT,
                                         VK_ACCESS_TRANSFER_READ_BIT);
            layout = VK_IMAGE_LAYOUT_GENERAL;
        } else {
            record_normal_pass(cmd, device_->render_pass(), slot.framebuffer, slot.width,
                               slot.height, pipeline_, device_->layout(), mesh_, view);
        }

        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {static_cast<std::uint32_t>(slot.width),
                              static_cast<std::uint32_t>(slot.height), 1};
        vkCmdCopyImageToBuffer(cmd, slot.normal.image, layout, slot.normal_readback.buffer, 1,
                               &region);
        vkCmdCopyImageToBuffer(cmd, slot.id.image, layout, slot.id_readback.buffer, 1, &region);
        // Barrier: the copies' writes must be visible to the host reads after the fence.
        VkMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                             &barrier, 0, nullptr, 0, nullptr);
        GLINT_VK_CHECK(vkEndCommandBuffer(cmd));
        device_->submit(cmd, slot.fence);
    }

    FrameOptions options_;
    std::shared_ptr<VulkanDevice> device_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<Buffer, 3> mesh_buffers_{};  // positions, normals, indices
    MeshBuffers mesh_{};                    // their handles and counts
    VkPipeline pipeline_ = VK_NULL_HANDLE;  // the device's, for this cull mode (Graphics)
    bool compute_ = false;                  // Raster::Compute: the compute rasteriser's passes
    const RasterPipelines* raster_ = nullptr;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;  // the slots' raster sets
    VulkanMesh vulkan_mesh_;                             // what the GPU atlas draws and reads
    std::array<Slot, kSlots> slots_{};
    std::deque<std::size_t> pending_;  // slots in submission order
    std::size_t next_slot_ = 0;
};

}  // namespace

std::unique_ptr<RenderBackend> make_vulkan_backend(std::shared_ptr<VulkanDevice> device,
                                                   const Mesh& mesh, const FrameOptions& options) {
    return std::make_unique<VulkanBackend>(std::move(device), mesh, options);
}

}  // namespace glint::detail
