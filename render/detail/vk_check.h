// GLINT_VK_CHECK: every VkResult is checked and turned into a DeviceError naming the call,
// the result and file:line (STYLE.md §5). Internal: includes vulkan.h.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

namespace glint::detail {

/// "VK_ERROR_DEVICE_LOST" etc.
[[nodiscard]] const char* vk_result_name(VkResult result);

[[noreturn]] void vk_check_failed(VkResult result, const char* call, const char* file, int line);

}  // namespace glint::detail

#define GLINT_VK_CHECK(call)                                                               \
    do {                                                                                   \
        const VkResult glint_vk_result_ = (call);                                          \
        if (glint_vk_result_ != VK_SUCCESS) {                                              \
            ::glint::detail::vk_check_failed(glint_vk_result_, #call, __FILE__, __LINE__); \
        }                                                                                  \
    } while (false)
