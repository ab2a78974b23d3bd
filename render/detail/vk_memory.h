// Vulkan buffers and images with their own memory (internal). One allocation path for both:
// the resource's requirements → a memory type with the required (and, when there is one,
// the preferred) properties → vkAllocateMemory → bind.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace glint::detail {

/// Memory the host maps and reads without flushes.
inline constexpr VkMemoryPropertyFlags kHostMemory =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;  ///< host-visible buffers stay mapped
    VkDeviceSize size = 0;
};

struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

/// A memory type allowed by type_bits with `required | preferred`, else with `required`.
/// \throw DeviceError none.
std::uint32_t find_memory_type(VkPhysicalDevice physical, std::uint32_t type_bits,
                               VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred);

/// A buffer in its own memory, mapped when `required` includes HOST_VISIBLE.
/// \throw DeviceError (the buffer is released first).
Buffer make_buffer(VkDevice device, VkPhysicalDevice physical, VkDeviceSize size,
                   VkBufferUsageFlags usage, VkMemoryPropertyFlags required,
                   VkMemoryPropertyFlags preferred);

/// A 2D device-local image (one mip, one layer, optimal tiling) in its own memory, with a view.
/// \throw DeviceError (the image is released first).
Image make_image(VkDevice device, VkPhysicalDevice physical, int width, int height, VkFormat format,
                 VkImageUsageFlags usage, VkImageAspectFlags aspect);

/// Release and reset; null handles are skipped.
void destroy_buffer(VkDevice device, Buffer& buffer) noexcept;
void destroy_image(VkDevice device, Image& image) noexcept;

}  // namespace glint::detail
