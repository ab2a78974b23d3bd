// The Vulkan half of a RenderContext (internal): one instance, one logical device with one
// graphics queue, the render pass, the pipeline layout and the pipelines, shared by every
// mesh (render/vulkan_backend.cpp) on the context. Backends hold a shared_ptr to it, so it
// lives as long as the last of the context and its renderers.
#pragma once

#include "render/context.h"
#include "render/detail/backend.h"
#include "render/detail/vk_compute.h"
#include "render/detail/vk_device.h"
#include "render/detail/vk_pipeline.h"
#include "render/detail/vk_raster.h"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace glint::detail {

class VulkanDevice {
  public:
    /// \throw DeviceError no driver, no usable device (listing them), a failed call.
    explicit VulkanDevice(const ContextOptions& options);
    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    [[nodiscard]] VkDevice device() const { return device_; }
    [[nodiscard]] VkPhysicalDevice physical() const { return physical_; }
    [[nodiscard]] std::uint32_t queue_family() const { return queue_family_; }
    [[nodiscard]] std::uint32_t max_dimension() const { return max_dimension_; }
    [[nodiscard]] VkRenderPass render_pass() const { return render_pass_; }
    [[nodiscard]] VkPipelineLayout layout() const { return layout_; }
    [[nodiscard]] const DeviceInfo& info() const { return info_; }
    [[nodiscard]] int threads() const { return threads_; }
    [[nodiscard]] const VkPhysicalDeviceLimits& limits() const { return limits_; }
    /// Valid bits of the queue's timestamps (0: the queue writes none).
    [[nodiscard]] std::uint32_t timestamp_bits() const { return timestamp_bits_; }
    /// Whether the GPU atlas's features were found and enabled (render/gpu_atlas.h);
    /// info().gpu_atlas_reason says why not.
    [[nodiscard]] bool has_gpu_atlas() const { return info_.supports_gpu_atlas; }
    /// The GPU atlas's passes, created at their first use. \pre has_gpu_atlas().
    [[nodiscard]] const AtlasPipelines& atlas_pipelines();
    /// The graphics pipeline for a cull mode, created at its first use.
    [[nodiscard]] VkPipeline pipeline(bool cull_back_faces);
    /// How the normal pass is rasterised on this device (ContextOptions::raster resolved).
    [[nodiscard]] Raster raster() const { return raster_; }
    /// The compute rasteriser's passes, created at their first use. \pre raster() is Compute.
    [[nodiscard]] const RasterPipelines& raster_pipelines();
    /// vkQueueSubmit of one command buffer signalling `fence`; the queue is shared by every
    /// renderer on the device, so submissions are serialised here.
    void submit(VkCommandBuffer cmd, VkFence fence);
    [[nodiscard]] std::vector<std::string> validation_messages() const;

  private:
    void create_device();
    void release() noexcept;

    int threads_ = 1;
    mutable MessageLog log_;
    std::unique_ptr<Instance> instance_;
    DeviceInfo info_;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    std::uint32_t max_dimension_ = 4096;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::mutex queue_mutex_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    std::mutex pipeline_mutex_;
    std::array<VkPipeline, 2> pipelines_{};  // [cull_back_faces]
    VkPhysicalDeviceLimits limits_{};
    std::uint32_t timestamp_bits_ = 0;
    AtlasPipelines atlas_{};              // created by atlas_pipelines() (pipeline_mutex_)
    RasterPipelines raster_pipelines_{};  // created by raster_pipelines() (pipeline_mutex_)
    Raster raster_ = Raster::Graphics;
};

/// A renderer's mesh as the GPU atlas uses it: its device, buffers and cull mode.
struct VulkanMesh {
    std::shared_ptr<VulkanDevice> device;
    MeshBuffers buffers;
    bool cull_back_faces = false;
};

/// A mesh on a shared device (render/vulkan_backend.cpp).
std::unique_ptr<RenderBackend> make_vulkan_backend(std::shared_ptr<VulkanDevice> device,
                                                   const Mesh& mesh, const FrameOptions& options);

}  // namespace glint::detail
