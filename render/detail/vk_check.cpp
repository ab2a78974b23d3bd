#include "render/detail/vk_check.h"

#include "mesh/error.h"

#include <sstream>

namespace glint::detail {

const char* vk_result_name(VkResult result) {
    switch (result) {
#define GLINT_CASE(x) \
    case x: return #x;
        GLINT_CASE(VK_SUCCESS)
        GLINT_CASE(VK_NOT_READY)
        GLINT_CASE(VK_TIMEOUT)
        GLINT_CASE(VK_EVENT_SET)
        GLINT_CASE(VK_EVENT_RESET)
        GLINT_CASE(VK_INCOMPLETE)
        GLINT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
        GLINT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        GLINT_CASE(VK_ERROR_INITIALIZATION_FAILED)
        GLINT_CASE(VK_ERROR_DEVICE_LOST)
        GLINT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
        GLINT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
        GLINT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
        GLINT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
        GLINT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
        GLINT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
        GLINT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
        GLINT_CASE(VK_ERROR_FRAGMENTED_POOL)
        GLINT_CASE(VK_ERROR_UNKNOWN)
        GLINT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
#undef GLINT_CASE
        default: return "VkResult(unknown)";
    }
}

void vk_check_failed(VkResult result, const char* call, const char* file, int line) {
    std::ostringstream s;
    s << "Vulkan call " << call << " failed with " << vk_result_name(result) << " ("
      << static_cast<int>(result) << ") at " << file << ":" << line;
    throw DeviceError(s.str());
}

}  // namespace glint::detail
