#include "render/detail/vk_context.h"

#include "mesh/error.h"
#include "render/detail/vk_check.h"
#include "render/detail/vk_pipeline.h"

#include <algorithm>
#include <vector>

namespace glint::detail {
namespace {

/// NVIDIA's data-centre GPUs: full compute, graphics units on only a few of their clusters.
/// Measured on an H100 (driver 580, 2026-11): the two normal passes of a 1M-triangle view at
/// 1024² took 3.4 ms in the graphics pipeline (≈ 0.85 G triangles/s, 1.4 G fragments/s, a
/// hundredth of a desktop GPU's), while the compute passes of the GPU atlas took 0.08 ms.
bool few_graphics_units(const DeviceInfo& info) {
    if (info.name.find("NVIDIA") == std::string::npos) return false;
    for (const char* part : {"A100", "A800", "H100", "H800", "H200", "B100", "B200"}) {
        if (info.name.find(part) != std::string::npos) return true;
    }
    return false;
}

/// ContextOptions::raster for the chosen device. \throw DeviceError Compute on a device
/// without the 64-bit atomics (and float64) the passes use.
Raster resolve_raster(Raster asked, const DeviceInfo& info) {
    if (asked == Raster::Compute && !info.supports_gpu_atlas)
        throw DeviceError("raster = compute: device \"" + info.name + "\" " +
                          info.gpu_atlas_reason + " (the compute rasteriser needs them)");
    if (asked != Raster::Auto) return asked;
    return info.supports_gpu_atlas && few_graphics_units(info) ? Raster::Compute : Raster::Graphics;
}

}  // namespace

VulkanDevice::VulkanDevice(const ContextOptions& options)
    : threads_(worker_count(options.threads)) {
    instance_ = std::make_unique<Instance>(options.validation, &log_);
    auto cands = enumerate(instance_->get());
    std::string why;
    const int chosen = choose(cands, options.device, why);
    if (chosen < 0) throw DeviceError(why);
    const Candidate& c = cands[static_cast<std::size_t>(chosen)];
    physical_ = c.physical;
    queue_family_ = c.queue_family;
    info_ = c.info;
    raster_ = resolve_raster(options.raster, info_);
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(physical_, &props);
    limits_ = props.limits;
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, nullptr);
    std::vector<VkQueueFamilyProperties> family_props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, family_props.data());
    timestamp_bits_ = queue_family_ < families ? family_props[queue_family_].timestampValidBits : 0;
    max_dimension_ =
        std::min(props.limits.maxImageDimension2D,
                 std::min(props.limits.maxFramebufferWidth, props.limits.maxFramebufferHeight));
    try {
        create_device();
        render_pass_ = make_render_pass(device_);
        layout_ = make_pipeline_layout(device_);
    } catch (...) {
        release();  // the destructor does not run for a half-built object
        throw;
    }
}

VulkanDevice::~VulkanDevice() { release(); }

void VulkanDevice::release() noexcept {
    if (device_ == VK_NULL_HANDLE) return;
    // Every renderer on the device is gone (they hold it): nothing is in flight.
    vkDeviceWaitIdle(device_);
    for (VkPipeline p : pipelines_) {
        if (p != VK_NULL_HANDLE) vkDestroyPipeline(device_, p, nullptr);
    }
    destroy_atlas_pipelines(device_, atlas_);
    destroy_raster_pipelines(device_, raster_pipelines_);
    if (layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, layout_, nullptr);
    if (render_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(device_, render_pass_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
}

void VulkanDevice::create_device() {
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo q{};
    q.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    q.queueFamilyIndex = queue_family_;
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan12Features v12{};
    v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    VkPhysicalDeviceFeatures2 features{};
    features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    features.features.geometryShader = VK_TRUE;  // gl_PrimitiveID in the fragment shader
    if (info_.supports_gpu_atlas) {
        // The GPU atlas (render/gpu_atlas.h): the CPU path's double arithmetic, 64-bit
        // fixed-point sums and maxima with buffer atomics.
        features.features.shaderFloat64 = VK_TRUE;
        features.features.shaderInt64 = VK_TRUE;
        v12.shaderBufferInt64Atomics = VK_TRUE;
        features.pNext = &v12;
    }
    VkDeviceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &q;
    GLINT_VK_CHECK(vkCreateDevice(physical_, &info, nullptr, &device_));
    ++creation_counters().vulkan_devices;
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

VkPipeline VulkanDevice::pipeline(bool cull_back_faces) {
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    VkPipeline& p = pipelines_[cull_back_faces ? 1 : 0];
    if (p == VK_NULL_HANDLE) p = make_pipeline(device_, layout_, render_pass_, cull_back_faces);
    return p;
}

const AtlasPipelines& VulkanDevice::atlas_pipelines() {
    GLINT_ASSERT(has_gpu_atlas(), "GPU atlas passes on a device without its features");
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    if (atlas_.pixels == VK_NULL_HANDLE) atlas_ = make_atlas_pipelines(device_, layout_);
    return atlas_;
}

const RasterPipelines& VulkanDevice::raster_pipelines() {
    GLINT_ASSERT(raster_ == Raster::Compute, "compute raster passes on a graphics-raster device");
    std::lock_guard<std::mutex> lock(pipeline_mutex_);
    if (raster_pipelines_.triangles == VK_NULL_HANDLE)
        raster_pipelines_ = make_raster_pipelines(device_, limits_);
    return raster_pipelines_;
}

void VulkanDevice::submit(VkCommandBuffer cmd, VkFence fence) {
    VkSubmitInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    info.commandBufferCount = 1;
    info.pCommandBuffers = &cmd;
    std::lock_guard<std::mutex> lock(queue_mutex_);
    GLINT_VK_CHECK(vkQueueSubmit(queue_, 1, &info, fence));
}

std::vector<std::string> VulkanDevice::validation_messages() const {
    std::lock_guard<std::mutex> lock(log_.mutex);
    return log_.messages;
}

namespace {

class VulkanContext final : public ContextImpl {
  public:
    explicit VulkanContext(const ContextOptions& options)
        : device_(std::make_shared<VulkanDevice>(options)) {}
    std::unique_ptr<RenderBackend> make_backend(const Mesh& mesh,
                                                const FrameOptions& options) override {
        return make_vulkan_backend(device_, mesh, options);
    }
    [[nodiscard]] std::vector<std::string> validation_messages() const override {
        return device_->validation_messages();
    }
    [[nodiscard]] const DeviceInfo& info() const { return device_->info(); }
    [[nodiscard]] Raster raster() const { return device_->raster(); }

  private:
    std::shared_ptr<VulkanDevice> device_;
};

}  // namespace

std::unique_ptr<ContextImpl> make_vulkan_context(const ContextOptions& options,
                                                 std::string& device_name, std::string& device_type,
                                                 Raster& raster) {
    auto context = std::make_unique<VulkanContext>(options);
    device_name = context->info().name;
    device_type = context->info().type;
    raster = context->raster();
    return context;
}

}  // namespace glint::detail
