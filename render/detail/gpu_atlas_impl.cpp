#include "render/detail/gpu_atlas_impl.h"

#include "mesh/error.h"
#include "render/detail/vk_check.h"
#include "spirv/bindings.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

namespace glint::detail {
namespace {

constexpr VkMemoryPropertyFlags kDeviceMemory = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;

}  // namespace

GpuAtlasImpl::GpuAtlasImpl(const VulkanMesh& reference, const VulkanMesh& examined,
                           const FrameOptions& frame, const GpuAtlasOptions& options)
    : reference_(reference),
      examined_(examined),
      device_(reference.device),
      supersample_(frame.supersample),
      options_(options) {
    // render/renderer.cpp finish_frame: pixels below the frame's min_coverage are uncovered.
    if (frame.min_coverage > 0.0f) mask_threshold_ = frame.min_coverage - 1e-6f;
    slots_.resize(static_cast<std::size_t>(options.in_flight));
    try {
        pipelines_ = &device_->atlas_pipelines();
        if (device_->raster() == Raster::Compute) raster_ = &device_->raster_pipelines();
        create_shared();
        for (auto& slot : slots_) create_slot(slot);
    } catch (...) {
        release();  // the destructor does not run for a half-built object
        throw;
    }
}

GpuAtlasImpl::~GpuAtlasImpl() { release(); }

void GpuAtlasImpl::create_shared() {
    const VkDevice dev = device_->device();
    const VkPhysicalDevice phys = device_->physical();
    VkCommandPoolCreateInfo pool{};
    pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = device_->queue_family();
    GLINT_VK_CHECK(vkCreateCommandPool(dev, &pool, nullptr, &pool_));
    const auto slots = static_cast<std::uint32_t>(slots_.size());
    // Per slot the passes' set and, with the compute rasteriser, one set per target.
    const std::uint32_t raster_sets = raster_ != nullptr ? 2 * slots : 0;
    const std::array<VkDescriptorPoolSize, 3> sizes{{
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, slots},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 4 * slots + kRasterStorageImages * raster_sets},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         (GLINT_ATLAS_BINDING_COUNT - 5) * slots + kRasterStorageBuffers * raster_sets},
    }};
    VkDescriptorPoolCreateInfo dp{};
    dp.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    dp.maxSets = slots + raster_sets;
    dp.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
    dp.pPoolSizes = sizes.data();
    GLINT_VK_CHECK(vkCreateDescriptorPool(dev, &dp, nullptr, &descriptor_pool_));
    const VkDeviceSize vertices = reference_.buffers.vertex_count;
    const auto zooms = static_cast<VkDeviceSize>(options_.zoom_count);
    sums_ =
        make_buffer(dev, phys, zooms * GLINT_SUM_FIELDS * vertices * 8, kStorage, kDeviceMemory, 0);
    words_ = make_buffer(dev, phys, zooms * GLINT_WORD_FIELDS * vertices * 4, kStorage,
                         kDeviceMemory, 0);
    scratch_key_ = make_buffer(dev, phys, vertices * 8, kStorage, kDeviceMemory, 0);
    scratch_cos_ = make_buffer(dev, phys, vertices * 4, kStorage, kDeviceMemory, 0);
}

void GpuAtlasImpl::create_slot(Slot& slot) {
    const VkDevice dev = device_->device();
    const VkPhysicalDevice phys = device_->physical();
    VkCommandBufferAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    GLINT_VK_CHECK(vkAllocateCommandBuffers(dev, &alloc, &slot.cmd));
    VkFenceCreateInfo fence{};
    fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    GLINT_VK_CHECK(vkCreateFence(dev, &fence, nullptr, &slot.fence));
    slot.params = make_buffer(dev, phys, sizeof(AtlasParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              kHostMemory, 0);
    slot.summary = make_buffer(dev, phys, sizeof(ViewTotals), kStorage, kDeviceMemory, 0);
    slot.summary_host = make_buffer(dev, phys, sizeof(ViewTotals), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    kHostMemory, VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (device_->timestamp_bits() > 0) {
        VkQueryPoolCreateInfo q{};
        q.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
        q.queryType = VK_QUERY_TYPE_TIMESTAMP;
        q.queryCount = 4;
        GLINT_VK_CHECK(vkCreateQueryPool(dev, &q, nullptr, &slot.timestamps));
    }
    VkDescriptorSetAllocateInfo set{};
    set.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    set.descriptorPool = descriptor_pool_;
    set.descriptorSetCount = 1;
    set.pSetLayouts = &pipelines_->set_layout;
    GLINT_VK_CHECK(vkAllocateDescriptorSets(dev, &set, &slot.set));
    if (raster_ != nullptr) {
        set.pSetLayouts = &raster_->set_layout;
        GLINT_VK_CHECK(vkAllocateDescriptorSets(dev, &set, &slot.reference.raster_set));
        GLINT_VK_CHECK(vkAllocateDescriptorSets(dev, &set, &slot.examined.raster_set));
    }
}

void GpuAtlasImpl::wait_all() noexcept {
    const VkDevice dev = device_->device();
    for (auto& slot : slots_) {
        if (!slot.busy) continue;
        vkWaitForFences(dev, 1, &slot.fence, VK_TRUE, UINT64_MAX);
        vkResetFences(dev, 1, &slot.fence);
        slot.busy = false;
    }
}

void GpuAtlasImpl::destroy_target(Target& t) noexcept {
    const VkDevice dev = device_->device();
    if (t.framebuffer != VK_NULL_HANDLE) vkDestroyFramebuffer(dev, t.framebuffer, nullptr);
    t.framebuffer = VK_NULL_HANDLE;
    destroy_image(dev, t.normal_depth);
    destroy_image(dev, t.primitive);
    destroy_image(dev, t.depth);
    destroy_raster_target(dev, t.raster);
}

/// A target's images (and framebuffer, or compute rasteriser buffers) for `mesh`.
void GpuAtlasImpl::make_target(Target& t, const MeshBuffers& mesh, int width, int height) {
    const VkDevice dev = device_->device();
    const VkPhysicalDevice phys = device_->physical();
    // Colour targets: attachments of the render pass, or storage images the compute
    // rasteriser writes; the atlas's passes read them as storage images either way.
    const VkImageUsageFlags color =
        VK_IMAGE_USAGE_STORAGE_BIT |
        (raster_ != nullptr ? VkImageUsageFlags{0}
                            : VkImageUsageFlags{VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT});
    t.normal_depth =
        make_image(dev, phys, width, height, kNormalFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
    t.primitive = make_image(dev, phys, width, height, kIdFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
    if (raster_ != nullptr) {
        const VkDescriptorSet set = t.raster_set;  // kept: make_raster_target resets it first
        make_raster_target(dev, phys, t.raster, set, mesh, width, height, t.normal_depth.view,
                           t.primitive.view);
        return;
    }
    t.depth = make_image(dev, phys, width, height, kDepthFormat,
                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    const std::array<VkImageView, 3> views{t.normal_depth.view, t.primitive.view, t.depth.view};
    VkFramebufferCreateInfo fb{};
    fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fb.renderPass = pipelines_->render_pass;
    fb.attachmentCount = static_cast<std::uint32_t>(views.size());
    fb.pAttachments = views.data();
    fb.width = static_cast<std::uint32_t>(width);
    fb.height = static_cast<std::uint32_t>(height);
    fb.layers = 1;
    GLINT_VK_CHECK(vkCreateFramebuffer(dev, &fb, nullptr, &t.framebuffer));
}

void GpuAtlasImpl::release() noexcept {
    if (device_ == nullptr) return;
    const VkDevice dev = device_->device();
    wait_all();
    for (auto& slot : slots_) {
        destroy_target(slot.reference);
        destroy_target(slot.examined);
        destroy_buffer(dev, slot.params);
        destroy_buffer(dev, slot.summary);
        destroy_buffer(dev, slot.summary_host);
        if (slot.fence != VK_NULL_HANDLE) vkDestroyFence(dev, slot.fence, nullptr);
        if (slot.timestamps != VK_NULL_HANDLE) vkDestroyQueryPool(dev, slot.timestamps, nullptr);
        slot.fence = VK_NULL_HANDLE;
        slot.timestamps = VK_NULL_HANDLE;
    }
    for (Buffer* b : {&sums_, &words_, &scratch_key_, &scratch_cos_, &pixels_, &staging_})
        destroy_buffer(dev, *b);
    // Destroying the pools frees their command buffers and descriptor sets.
    if (descriptor_pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(dev, descriptor_pool_, nullptr);
    if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(dev, pool_, nullptr);
    descriptor_pool_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

/// (Re)creates a slot's two targets for a sub-sample size; the slot is idle here.
void GpuAtlasImpl::ensure_targets(Slot& slot, int width, int height) {
    if (slot.width == width && slot.height == height) return;
    destroy_target(slot.reference);
    destroy_target(slot.examined);
    slot.width = slot.height = 0;
    make_target(slot.reference, reference_.buffers, width, height);
    make_target(slot.examined, examined_.buffers, width, height);
    slot.width = width;
    slot.height = height;
    slot.set_current = false;
}

/// The per-pixel comparison buffer for the largest view; every slot is idle here.
void GpuAtlasImpl::ensure_pixels(std::size_t pixel_count) {
    const VkDeviceSize bytes = static_cast<VkDeviceSize>(pixel_count) * sizeof(PixelDeviation);
    if (pixels_.buffer != VK_NULL_HANDLE && pixels_.size >= bytes) return;
    destroy_buffer(device_->device(), pixels_);
    pixels_ =
        make_buffer(device_->device(), device_->physical(), bytes, kStorage, kDeviceMemory, 0);
    for (auto& slot : slots_) slot.set_current = false;
}

void GpuAtlasImpl::write_set(Slot& slot) {
    const std::array<std::pair<std::uint32_t, VkImageView>, 4> images{{
        {GLINT_ATLAS_BINDING_REF_NORMAL_DEPTH, slot.reference.normal_depth.view},
        {GLINT_ATLAS_BINDING_REF_PRIMITIVE, slot.reference.primitive.view},
        {GLINT_ATLAS_BINDING_EXA_NORMAL_DEPTH, slot.examined.normal_depth.view},
        {GLINT_ATLAS_BINDING_EXA_PRIMITIVE, slot.examined.primitive.view},
    }};
    const std::array<std::pair<std::uint32_t, VkBuffer>, GLINT_ATLAS_BINDING_COUNT - 4> buffers{{
        {GLINT_ATLAS_BINDING_PARAMS, slot.params.buffer},
        {GLINT_ATLAS_BINDING_POSITIONS, reference_.buffers.positions},
        {GLINT_ATLAS_BINDING_NORMALS, reference_.buffers.normals},
        {GLINT_ATLAS_BINDING_INDICES, reference_.buffers.indices},
        {GLINT_ATLAS_BINDING_SUMS, sums_.buffer},
        {GLINT_ATLAS_BINDING_WORDS, words_.buffer},
        {GLINT_ATLAS_BINDING_SCRATCH_KEY, scratch_key_.buffer},
        {GLINT_ATLAS_BINDING_SCRATCH_COS, scratch_cos_.buffer},
        {GLINT_ATLAS_BINDING_PIXELS, pixels_.buffer},
        {GLINT_ATLAS_BINDING_SUMMARY, slot.summary.buffer},
    }};
    std::array<VkDescriptorImageInfo, images.size()> image_infos{};
    std::array<VkDescriptorBufferInfo, buffers.size()> buffer_infos{};
    std::array<VkWriteDescriptorSet, GLINT_ATLAS_BINDING_COUNT> writes{};
    for (std::size_t i = 0; i < writes.size(); ++i) {
        writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        writes[i].dstSet = slot.set;
        writes[i].descriptorCount = 1;
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        image_infos[i] = {VK_NULL_HANDLE, images[i].second, VK_IMAGE_LAYOUT_GENERAL};
        writes[i].dstBinding = images[i].first;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        writes[i].pImageInfo = &image_infos[i];
    }
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        buffer_infos[i] = {buffers[i].second, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet& w = writes[images.size() + i];
        w.dstBinding = buffers[i].first;
        w.descriptorType = buffers[i].first == GLINT_ATLAS_BINDING_PARAMS
                               ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                               : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w.pBufferInfo = &buffer_infos[i];
    }
    vkUpdateDescriptorSets(device_->device(), static_cast<std::uint32_t>(writes.size()),
                           writes.data(), 0, nullptr);
    slot.set_current = true;
}

/// Per zoom, the largest power-of-two scales at which no sum can overflow an int64: a vertex
/// is observed at most once per pixel of a view (scatter) or once per view (gather), so N, the
/// zoom's pixels over all its views, bounds its observations; |w| ≤ 1, |w·value| ≤ max(255,
/// missing value), |w·signed depth| < far − near.
std::vector<GpuAtlasImpl::Scales> GpuAtlasImpl::scales_for(std::span<const View> views) const {
    std::vector<double> pixels(static_cast<std::size_t>(options_.zoom_count), 1.0);
    std::vector<double> depth_range(pixels.size(), 1e-30);
    for (const View& v : views) {
        const auto z = static_cast<std::size_t>(v.zoom_index);
        pixels[z] += static_cast<double>(v.camera.width) * static_cast<double>(v.camera.height);
        depth_range[z] = std::max(depth_range[z], v.camera.far_plane - v.camera.near_plane);
    }
    const int value_bits = bits_for(std::max(255.0, static_cast<double>(options_.missing_value)));
    std::vector<Scales> scales(pixels.size());
    for (std::size_t z = 0; z < pixels.size(); ++z) {
        const int n = bits_for(pixels[z]);
        scales[z] = Scales{.weight = std::ldexp(1.0, 62 - n),
                           .value = std::ldexp(1.0, 62 - n - value_bits),
                           .depth = std::ldexp(1.0, 62 - n - bits_for(depth_range[z]))};
    }
    return scales;
}

}  // namespace glint::detail
