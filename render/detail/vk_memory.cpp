#include "render/detail/vk_memory.h"

#include "mesh/error.h"
#include "render/detail/vk_check.h"

#include <string>

namespace glint::detail {

std::uint32_t find_memory_type(VkPhysicalDevice physical, std::uint32_t type_bits,
                               VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
    VkPhysicalDeviceMemoryProperties mem{};
    vkGetPhysicalDeviceMemoryProperties(physical, &mem);
    for (const VkMemoryPropertyFlags want : {required | preferred, required}) {
        for (std::uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
            if ((type_bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want)
                return i;
        }
    }
    throw DeviceError("no Vulkan memory type with the required properties (flags " +
                      std::to_string(required) + ")");
}

namespace {

/// The one allocation path: memory for `req` with the properties asked for.
VkDeviceMemory allocate(VkDevice device, VkPhysicalDevice physical, const VkMemoryRequirements& req,
                        VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
    VkMemoryAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = find_memory_type(physical, req.memoryTypeBits, required, preferred);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    GLINT_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory));
    return memory;
}

}  // namespace

Buffer make_buffer(VkDevice device, VkPhysicalDevice physical, VkDeviceSize size,
                   VkBufferUsageFlags usage, VkMemoryPropertyFlags required,
                   VkMemoryPropertyFlags preferred) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    try {
        GLINT_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &b.buffer));
        VkMemoryRequirements req{};
        vkGetBufferMemoryRequirements(device, b.buffer, &req);
        b.memory = allocate(device, physical, req, required, preferred);
        GLINT_VK_CHECK(vkBindBufferMemory(device, b.buffer, b.memory, 0));
        if (required & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
            GLINT_VK_CHECK(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
        }
    } catch (...) {
        destroy_buffer(device, b);
        throw;
    }
    return b;
}

Image make_image(VkDevice device, VkPhysicalDevice physical, int width, int height, VkFormat format,
                 VkImageUsageFlags usage, VkImageAspectFlags aspect) {
    Image img;
    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    try {
        GLINT_VK_CHECK(vkCreateImage(device, &info, nullptr, &img.image));
        VkMemoryRequirements req{};
        vkGetImageMemoryRequirements(device, img.image, &req);
        img.memory = allocate(device, physical, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        GLINT_VK_CHECK(vkBindImageMemory(device, img.image, img.memory, 0));
        VkImageViewCreateInfo v{};
        v.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        v.image = img.image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = format;
        v.subresourceRange = {aspect, 0, 1, 0, 1};
        GLINT_VK_CHECK(vkCreateImageView(device, &v, nullptr, &img.view));
    } catch (...) {
        destroy_image(device, img);
        throw;
    }
    return img;
}

void destroy_buffer(VkDevice device, Buffer& b) noexcept {
    if (b.mapped != nullptr) vkUnmapMemory(device, b.memory);
    if (b.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device, b.memory, nullptr);
    b = Buffer{};
}

void destroy_image(VkDevice device, Image& img) noexcept {
    if (img.view != VK_NULL_HANDLE) vkDestroyImageView(device, img.view, nullptr);
    if (img.image != VK_NULL_HANDLE) vkDestroyImage(device, img.image, nullptr);
    if (img.memory != VK_NULL_HANDLE) vkFreeMemory(device, img.memory, nullptr);
    img = Image{};
}

}  // namespace glint::detail
