// Vulkan instance and physical-device choice (internal): what glint needs of a device, why
// one is rejected, the debug messenger of the validation layer, the anchor instance.
#pragma once

#include "render/renderer.h"

#include <vulkan/vulkan.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace glint::detail {

constexpr VkFormat kNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
// note: the shaders are compiled for --target-env vulkan1.2 (SPIR-V 1.5).
constexpr std::uint32_t kRequiredApi = VK_API_VERSION_1_2;

/// Collected validation messages; the debug messenger writes here from any thread.
struct MessageLog {
    std::mutex mutex;
    std::vector<std::string> messages;
};

/// Owns a VkInstance (and the debug messenger when validation is on).
class Instance {
  public:
    /// \throw DeviceError no driver, validation layer missing.
    Instance(bool validation, MessageLog* log);
    ~Instance();
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;
    [[nodiscard]] VkInstance get() const { return instance_; }

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

/// A physical device as evaluated against what glint needs.
struct Candidate {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    DeviceInfo info;
    std::uint32_t queue_family = 0;
    int score = 0;
};

std::vector<Candidate> enumerate(VkInstance instance);

/// Best usable candidate (highest score, first on ties), optionally filtered by name
/// (case-insensitive substring). Returns -1 when none; `why` explains.
int choose(const std::vector<Candidate>& cands, const std::string& name, std::string& why);

}  // namespace glint::detail
