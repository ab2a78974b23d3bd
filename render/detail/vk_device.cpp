#include "render/detail/vk_device.h"

#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/detail/vk_check.h"
#include "spirv/bindings.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <sstream>

namespace glint {
namespace detail {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string version_text(std::uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

const char* type_name(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
        default: return "other";
    }
}

int type_score(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
        default: return 0;
    }
}

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* log = static_cast<MessageLog*>(user);
    const char* level =
        (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    std::lock_guard<std::mutex> lock(log->mutex);
    log->messages.push_back(std::string(level) + ": " +
                            (data != nullptr && data->pMessage != nullptr ? data->pMessage : "?"));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messenger_info(MessageLog* log) {
    VkDebugUtilsMessengerCreateInfoEXT info{};
    info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    info.pfnUserCallback = debug_callback;
    info.pUserData = log;
    return info;
}

/// Keeps the drivers that the loader found loaded for the rest of the process: one plain
/// instance, created once after the first instance succeeded and never destroyed.
/// note: the loader unloads a driver when its last instance goes and loads it again at the
/// next vkCreateInstance; NVIDIA's driver (580, H100) stopped loading after ~50 such cycles in
/// one process (vkCreateInstance → VK_ERROR_INCOMPATIBLE_DRIVER), which a batch run of
/// scenarios (two renderers each) reaches. With the anchor the cycles are reference counts.
void keep_drivers_loaded(const VkApplicationInfo& app) {
    static std::once_flag once;
    std::call_once(once, [&] {
        VkInstanceCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
        info.pApplicationInfo = &app;
        VkInstance anchor = VK_NULL_HANDLE;
        // An anchor that cannot be made changes nothing: each renderer still has its own.
        (void)vkCreateInstance(&info, nullptr, &anchor);
    });
}

}  // namespace

Instance::Instance(bool validation, MessageLog* log) {
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
        std::uint32_t count = 0;
        GLINT_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
        std::vector<VkLayerProperties> props(count);
        GLINT_VK_CHECK(vkEnumerateInstanceLayerProperties(&count, props.data()));
        const bool has_layer = std::any_of(props.begin(), props.end(), [](const auto& p) {
            return std::strcmp(p.layerName, kValidationLayer) == 0;
        });
        if (!has_layer) {
            throw DeviceError(std::string("Vulkan validation requested but layer ") +
                              kValidationLayer +
                              " is not installed (Debian package vulkan-validationlayers)");
        }
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);  // provided by the layer
    }
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "glint";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "glint";
    app.apiVersion = kRequiredApi;
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkDebugUtilsMessengerCreateInfoEXT dbg = messenger_info(log);
    // Synchronisation validation too: it checks the barriers and subpass dependencies
    // (hazards between the clear, the draw, the copies and the host reads).
    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{};
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    features.pNext = &dbg;
    if (validation) info.pNext = &features;  // dbg also catches messages of instance creation
    const VkResult r = vkCreateInstance(&info, nullptr, &instance_);
    if (r != VK_SUCCESS) {
        throw DeviceError(std::string("cannot create a Vulkan instance (") + vk_result_name(r) +
                          "): no Vulkan driver found; check the ICD (VK_ICD_FILENAMES, "
                          "mesa-vulkan-drivers for lavapipe) or use --backend embree");
    }
    ++creation_counters().vulkan_instances;
    keep_drivers_loaded(app);
    if (validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (create == nullptr) {
            vkDestroyInstance(instance_, nullptr);
            throw DeviceError("VK_EXT_debug_utils is missing although the validation layer is on");
        }
        const VkResult rm = create(instance_, &dbg, nullptr, &messenger_);
        if (rm != VK_SUCCESS) {
            vkDestroyInstance(instance_, nullptr);
            vk_check_failed(rm, "vkCreateDebugUtilsMessengerEXT", __FILE__, __LINE__);
        }
    }
}

Instance::~Instance() {
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy != nullptr) destroy(instance_, messenger_, nullptr);
    }
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

namespace {

bool has_optimal_features(VkPhysicalDevice pd, VkFormat format, VkFormatFeatureFlags needed) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(pd, format, &props);
    return (props.optimalTilingFeatures & needed) == needed;
}

/// What the GPU atlas needs beyond rendering (render/gpu_atlas.h); `info` receives the verdict.
void evaluate_gpu_atlas(VkPhysicalDevice pd, const VkPhysicalDeviceFeatures& features,
                        const VkQueueFamilyProperties& queue, DeviceInfo& info) {
    VkPhysicalDeviceVulkan12Features v12{};
    v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    VkPhysicalDeviceFeatures2 f2{};
    f2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    f2.pNext = &v12;
    vkGetPhysicalDeviceFeatures2(pd, &f2);
    std::vector<std::string> missing;
    if (!features.shaderFloat64) missing.push_back("shaderFloat64");
    if (!features.shaderInt64) missing.push_back("shaderInt64");
    if (!v12.shaderBufferInt64Atomics) missing.push_back("shaderBufferInt64Atomics");
    if (!(queue.queueFlags & VK_QUEUE_COMPUTE_BIT))
        missing.push_back("compute on the graphics queue");
    const VkFormatFeatureFlags storage =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
    if (!has_optimal_features(pd, kNormalFormat, storage))
        missing.push_back("RGBA32F storage image");
    if (!has_optimal_features(pd, kIdFormat, storage)) missing.push_back("R32_UINT storage image");
    info.supports_gpu_atlas = missing.empty();
    for (std::size_t i = 0; i < missing.size(); ++i)
        info.gpu_atlas_reason += (i == 0 ? "lacks " : ", ") + missing[i];
}

/// What glint needs of a device; `reason` collects every missing piece.
Candidate evaluate(VkPhysicalDevice pd) {
    Candidate c;
    c.physical = pd;
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 props2{};
    props2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(pd, &props);
    if (props.apiVersion >= VK_API_VERSION_1_2) {
        props2.pNext = &driver;
        vkGetPhysicalDeviceProperties2(pd, &props2);
        c.info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    }
    c.info.name = props.deviceName;
    c.info.type = type_name(props.deviceType);
    c.info.api_version = props.apiVersion;
    c.info.api_version_text = version_text(props.apiVersion);
    c.score = type_score(props.deviceType);

    std::vector<std::string> missing;
    if (props.apiVersion < kRequiredApi)
        missing.push_back("Vulkan 1.2 (has " + c.info.api_version_text + ")");
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(pd, &features);
    if (!features.geometryShader) missing.push_back("geometryShader feature (gl_PrimitiveID)");
    std::uint32_t qcount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, nullptr);
    std::vector<VkQueueFamilyProperties> queues(qcount);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, queues.data());
    // The first graphics family that also computes (the GPU atlas runs its passes on the same
    // queue), else the first graphics family.
    bool has_graphics = false;
    const std::array<VkQueueFlags, 2> preferences{VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT,
                                                  VK_QUEUE_GRAPHICS_BIT};
    for (const VkQueueFlags wanted : preferences) {
        for (std::uint32_t i = 0; i < qcount && !has_graphics; ++i) {
            if ((queues[i].queueFlags & wanted) == wanted) {
                c.queue_family = i;
                has_graphics = true;
            }
        }
    }
    if (!has_graphics) missing.push_back("a graphics queue");
    const VkFormatFeatureFlags color =
        VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (!has_optimal_features(pd, kNormalFormat, color))
        missing.push_back("RGBA32F colour attachment");
    if (!has_optimal_features(pd, kIdFormat, color))
        missing.push_back("R32_UINT colour attachment");
    if (!has_optimal_features(pd, kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) {
        missing.push_back("D32 depth attachment");
    }
    if (props.limits.maxPushConstantsSize < GLINT_PUSH_CONSTANT_BYTES)
        missing.push_back("80 bytes of push constants");
    c.info.is_usable = missing.empty();
    for (std::size_t i = 0; i < missing.size(); ++i) {
        c.info.reason += (i == 0 ? "lacks " : ", ") + missing[i];
    }
    if (c.info.is_usable) {
        evaluate_gpu_atlas(pd, features, queues[c.queue_family], c.info);
    } else {
        c.info.gpu_atlas_reason = "the device is not usable";
    }
    return c;
}

}  // namespace

std::vector<Candidate> enumerate(VkInstance instance) {
    std::uint32_t count = 0;
    GLINT_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    GLINT_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    std::vector<Candidate> out;
    for (auto pd : devices) out.push_back(evaluate(pd));
    return out;
}

/// Best usable candidate (highest score, first on ties), optionally filtered by name.
/// Returns -1 when none; `why` explains.
int choose(const std::vector<Candidate>& cands, const std::string& name, std::string& why) {
    int best = -1;
    const std::string wanted = lower(name);
    for (std::size_t i = 0; i < cands.size(); ++i) {
        const auto& c = cands[i];
        if (!wanted.empty() && lower(c.info.name).find(wanted) == std::string::npos) continue;
        if (!c.info.is_usable) continue;
        if (best < 0 || c.score > cands[static_cast<std::size_t>(best)].score)
            best = static_cast<int>(i);
    }
    if (best < 0) {
        std::ostringstream s;
        if (cands.empty()) {
            s << "no Vulkan device found (the driver lists none)";
        } else {
            s << "no usable Vulkan device" << (wanted.empty() ? "" : " matching \"" + name + "\"")
              << "; devices:";
            for (const auto& c : cands) {
                s << " [" << c.info.name << " (" << c.info.type << ")"
                  << (c.info.is_usable ? ": usable" : ": " + c.info.reason) << "]";
            }
        }
        why = s.str();
    }
    return best;
}

}  // namespace detail

std::vector<DeviceInfo> list_devices() {
    detail::MessageLog log;
    detail::Instance instance(false, &log);
    auto cands = detail::enumerate(instance.get());
    std::string why;
    const int best = detail::choose(cands, std::string(), why);
    std::vector<DeviceInfo> out;
    for (std::size_t i = 0; i < cands.size(); ++i) {
        DeviceInfo d = cands[i].info;
        d.is_preferred = static_cast<int>(i) == best;
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace glint
