// Vulkan backend: headless rasterisation of the normal pass on a GPU or on lavapipe.
//
// Per renderer: one VkInstance, one VkDevice, the mesh uploaded once into device-local
// vertex (positions, normals) and index buffers, one render pass and pipeline. Per view: push
// constants (clip_from_world, depth row), nothing else changes.
//
// Frames in flight: two slots, each with its own targets, read-back buffers, command buffer
// and fence. View i renders in slot i % 2 while the CPU resolves and hands over view i − 1:
//
//   GPU/lavapipe:  [render 0][render 1][render 2] ...
//   CPU:                     [resolve 0, consume 0][resolve 1, consume 1] ...
//
// Image layouts of one slot, per view (render pass + copies, one command buffer):
//
//   normal+depth RGBA32F, id R32_UINT:
//     UNDEFINED ──(render pass, clear)──▶ COLOR_ATTACHMENT ──(final layout)──▶ TRANSFER_SRC
//       ──vkCmdCopyImageToBuffer──▶ host-visible buffer ──(barrier: transfer → host)──▶ CPU
//   depth D32: UNDEFINED ──▶ DEPTH_STENCIL_ATTACHMENT (contents discarded)
//
// Sub-samples: the target is (w·s) × (h·s); the CPU resolve (detail/resolve.cpp) averages
// s×s blocks. lavapipe offers MSAA 1×/4× only and integer attachments 1× only, so true
// supersampling is the one way that is exact for any s and for the primitive id.
#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/detail/vk_check.h"
#include "render/renderer.h"
#include "spirv/bindings.h"
#include "spirv/shader_ids.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <sstream>

namespace glint {
namespace detail {
namespace {

constexpr VkFormat kNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
// note: the shaders are compiled for --target-env vulkan1.2 (SPIR-V 1.5).
constexpr std::uint32_t kRequiredApi = VK_API_VERSION_1_2;
constexpr int kSlots = 2;

struct PushConstants {
    float clip_from_world[16];  // column-major, as GLSL mat4
    float depth_row[4];
};
static_assert(sizeof(PushConstants) == GLINT_PUSH_CONSTANT_BYTES,
              "PushConstants must match shaders/bindings.h and normal.vert");
static_assert(offsetof(PushConstants, depth_row) == 64, "std430 push constant layout");

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

/// Collected validation messages; the debug messenger writes here from any thread.
struct MessageLog {
    std::mutex mutex;
    std::vector<std::string> messages;
};

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
    auto* log = static_cast<MessageLog*>(user);
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
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

/// Owns a VkInstance (and the debug messenger when validation is on).
class Instance {
public:
    Instance(bool validation, MessageLog* log) {
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
        const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
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
    ~Instance() {
        if (messenger_ != VK_NULL_HANDLE) {
            auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
            if (destroy != nullptr) destroy(instance_, messenger_, nullptr);
        }
        if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
    }
    Instance(const Instance&) = delete;
    Instance& operator=(const Instance&) = delete;
    [[nodiscard]] VkInstance get() const { return instance_; }

private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

struct Candidate {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    DeviceInfo info;
    std::uint32_t queue_family = 0;
    int score = 0;
};

bool has_optimal_features(VkPhysicalDevice pd, VkFormat format, VkFormatFeatureFlags needed) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(pd, format, &props);
    return (props.optimalTilingFeatures & needed) == needed;
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
    if (props.apiVersion < kRequiredApi) missing.push_back("Vulkan 1.2 (has " + c.info.api_version_text + ")");
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(pd, &features);
    if (!features.geometryShader) missing.push_back("geometryShader feature (gl_PrimitiveID)");
    std::uint32_t qcount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, nullptr);
    std::vector<VkQueueFamilyProperties> queues(qcount);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &qcount, queues.data());
    bool has_graphics = false;
    for (std::uint32_t i = 0; i < qcount; ++i) {
        if (queues[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
            c.queue_family = i;
            has_graphics = true;
            break;
        }
    }
    if (!has_graphics) missing.push_back("a graphics queue");
    const VkFormatFeatureFlags color = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if (!has_optimal_features(pd, kNormalFormat, color)) missing.push_back("RGBA32F colour attachment");
    if (!has_optimal_features(pd, kIdFormat, color)) missing.push_back("R32_UINT colour attachment");
    if (!has_optimal_features(pd, kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT)) {
        missing.push_back("D32 depth attachment");
    }
    if (props.limits.maxPushConstantsSize < GLINT_PUSH_CONSTANT_BYTES) missing.push_back("80 bytes of push constants");
    c.info.is_usable = missing.empty();
    for (std::size_t i = 0; i < missing.size(); ++i) {
        c.info.reason += (i == 0 ? "lacks " : ", ") + missing[i];
    }
    return c;
}

std::vector<Candidate> enumerate(VkInstance instance) {
    std::uint32_t count = 0;
    GLINT_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    GLINT_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    std::vector<Candidate> out;
    for (auto pd : devices) out.push_back(evaluate(pd));
    return out;
}

std::string requested_device(const RenderOptions& options) {
    if (!options.device.empty()) return options.device;
    const char* env = std::getenv("GLINT_DEVICE");
    return env != nullptr ? std::string(env) : std::string();
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
        if (best < 0 || c.score > cands[static_cast<std::size_t>(best)].score) best = static_cast<int>(i);
    }
    if (best < 0) {
        std::ostringstream s;
        if (cands.empty()) {
            s << "no Vulkan device found (the driver lists none)";
        } else {
            s << "no usable Vulkan device" << (wanted.empty() ? "" : " matching \"" + name + "\"") << "; devices:";
            for (const auto& c : cands) {
                s << " [" << c.info.name << " (" << c.info.type << ")"
                  << (c.info.is_usable ? ": usable" : ": " + c.info.reason) << "]";
            }
        }
        why = s.str();
    }
    return best;
}

std::uint32_t find_memory_type(VkPhysicalDevice pd, std::uint32_t type_bits,
                               VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) {
    VkPhysicalDeviceMemoryProperties mem{};
    vkGetPhysicalDeviceMemoryProperties(pd, &mem);
    for (const VkMemoryPropertyFlags want : {required | preferred, required}) {
        for (std::uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
            if ((type_bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return i;
        }
    }
    throw DeviceError("no Vulkan memory type with the required properties (flags " +
                      std::to_string(required) + ")");
}

class VulkanBackend final : public RenderBackend {
public:
    VulkanBackend(const Mesh& mesh, const RenderOptions& options, RendererInfo& info)
        : options_(options), threads_(worker_count(options.threads)) {
        instance_ = std::make_unique<Instance>(options.validation, &log_);
        auto cands = enumerate(instance_->get());
        std::string why;
        const int chosen = choose(cands, requested_device(options), why);
        if (chosen < 0) throw DeviceError(why);
        const Candidate& c = cands[static_cast<std::size_t>(chosen)];
        physical_ = c.physical;
        queue_family_ = c.queue_family;
        info.device_name = c.info.name;
        info.device_type = c.info.type;
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(physical_, &props);
        max_dimension_ = std::min(props.limits.maxImageDimension2D,
                                  std::min(props.limits.maxFramebufferWidth, props.limits.maxFramebufferHeight));
        try {
            create_device();
            upload(mesh);
            create_pipeline();
        } catch (...) {
            release();  // the destructor does not run for a half-built object
            throw;
        }
    }

    ~VulkanBackend() override { release(); }

    void release() noexcept {
        if (device_ != VK_NULL_HANDLE) {
            vkDeviceWaitIdle(device_);
            for (auto& slot : slots_) destroy_slot(slot);
            vkDestroyPipeline(device_, pipeline_, nullptr);
            vkDestroyPipelineLayout(device_, layout_, nullptr);
            vkDestroyRenderPass(device_, render_pass_, nullptr);
            for (auto& b : mesh_buffers_) destroy_buffer(b);
            vkDestroyCommandPool(device_, pool_, nullptr);
            vkDestroyDevice(device_, nullptr);
            device_ = VK_NULL_HANDLE;
        }
    }

    std::vector<std::string> validation_messages() const override {
        std::lock_guard<std::mutex> lock(log_.mutex);
        return log_.messages;
    }

    void render_views(std::span<const View> views, const MutableFrameConsumer& consumer) override {
        const int s = options_.supersample;
        std::deque<int> pending;  // slots in submission order
        try {
            for (std::size_t i = 0; i < views.size(); ++i) {
                const int slot_index = static_cast<int>(i % kSlots);
                Slot& slot = slots_[static_cast<std::size_t>(slot_index)];
                if (slot.busy) {
                    // Oldest in-flight view is in this slot (round robin): finish it first.
                    GLINT_ASSERT(pending.front() == slot_index, "frames in flight out of order");
                    pending.pop_front();
                    finish(slot, consumer);
                }
                const View& view = views[i];
                ensure_targets(slot, view.camera.width * s, view.camera.height * s);
                record_and_submit(slot, view);
                slot.view_index = i;
                slot.out_width = view.camera.width;
                slot.out_height = view.camera.height;
                slot.busy = true;
                pending.push_back(slot_index);
            }
            while (!pending.empty()) {
                Slot& slot = slots_[static_cast<std::size_t>(pending.front())];
                pending.pop_front();
                finish(slot, consumer);
            }
        } catch (...) {
            // Leave the device idle and the slots free so the renderer stays usable; the
            // exception (consumer's or ours) propagates unchanged.
            vkDeviceWaitIdle(device_);
            for (auto& slot : slots_) {
                if (slot.busy) vkResetFences(device_, 1, &slot.fence);
                slot.busy = false;
            }
            throw;
        }
    }

private:
    struct Buffer {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        void* mapped = nullptr;
        VkDeviceSize size = 0;
    };
    struct Image {
        VkImage image = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkImageView view = VK_NULL_HANDLE;
    };
    struct Slot {
        int width = 0;  // target size in sub-samples
        int height = 0;
        Image normal, id, depth;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        Buffer normal_readback, id_readback;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        bool busy = false;
        std::size_t view_index = 0;
        int out_width = 0;
        int out_height = 0;
        Frame frame;
    };

    void create_device() {
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo q{};
        q.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
        q.queueFamilyIndex = queue_family_;
        q.queueCount = 1;
        q.pQueuePriorities = &priority;
        VkPhysicalDeviceFeatures features{};
        features.geometryShader = VK_TRUE;  // gl_PrimitiveID in the fragment shader
        VkDeviceCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
        info.queueCreateInfoCount = 1;
        info.pQueueCreateInfos = &q;
        info.pEnabledFeatures = &features;
        GLINT_VK_CHECK(vkCreateDevice(physical_, &info, nullptr, &device_));
        vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
        VkCommandPoolCreateInfo pool{};
        pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = queue_family_;
        GLINT_VK_CHECK(vkCreateCommandPool(device_, &pool, nullptr, &pool_));
        for (auto& slot : slots_) {
            VkCommandBufferAllocateInfo alloc{};
            alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
            alloc.commandPool = pool_;
            alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
            alloc.commandBufferCount = 1;
            GLINT_VK_CHECK(vkAllocateCommandBuffers(device_, &alloc, &slot.cmd));
            VkFenceCreateInfo f{};
            f.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
            GLINT_VK_CHECK(vkCreateFence(device_, &f, nullptr, &slot.fence));
        }
    }

    Buffer make_buffer(VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags required,
                       VkMemoryPropertyFlags preferred) {
        Buffer b;
        b.size = size;
        VkBufferCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
        info.size = size;
        info.usage = usage;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        GLINT_VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &b.buffer));
        VkMemoryRequirements req{};
        vkGetBufferMemoryRequirements(device_, b.buffer, &req);
        VkMemoryAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = find_memory_type(physical_, req.memoryTypeBits, required, preferred);
        GLINT_VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &b.memory));
        GLINT_VK_CHECK(vkBindBufferMemory(device_, b.buffer, b.memory, 0));
        if (required & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
            GLINT_VK_CHECK(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
        }
        return b;
    }

    void destroy_buffer(Buffer& b) {
        if (b.mapped != nullptr) vkUnmapMemory(device_, b.memory);
        if (b.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device_, b.buffer, nullptr);
        if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory, nullptr);
        b = Buffer{};
    }

    /// Copies the mesh into device-local buffers through one staging buffer.
    void upload(const Mesh& mesh) {
        static_assert(sizeof(Vec3f) == 12, "Mesh::positions must be tightly packed float3");
        static_assert(sizeof(Triangle) == 12, "Mesh::triangles must be tightly packed uint3");
        const VkDeviceSize pos_bytes = mesh.positions.size() * sizeof(Vec3f);
        const VkDeviceSize nrm_bytes = mesh.normals.size() * sizeof(Vec3f);
        const VkDeviceSize idx_bytes = mesh.triangles.size() * sizeof(Triangle);
        index_count_ = static_cast<std::uint32_t>(mesh.triangles.size() * 3);
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        Buffer staging = make_buffer(pos_bytes + nrm_bytes + idx_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, host, 0);
        auto* dst = static_cast<unsigned char*>(staging.mapped);
        std::memcpy(dst, mesh.positions.data(), pos_bytes);
        std::memcpy(dst + pos_bytes, mesh.normals.data(), nrm_bytes);
        std::memcpy(dst + pos_bytes + nrm_bytes, mesh.triangles.data(), idx_bytes);
        const VkBufferUsageFlags vtx = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        mesh_buffers_[0] = make_buffer(pos_bytes, vtx, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        mesh_buffers_[1] = make_buffer(nrm_bytes, vtx, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        mesh_buffers_[2] = make_buffer(idx_bytes, VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                       VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
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
        // reads) of every later draw.
        VkMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_INDEX_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, 0, 1,
                             &barrier, 0, nullptr, 0, nullptr);
        GLINT_VK_CHECK(vkEndCommandBuffer(cmd));
        submit_and_wait(cmd, slots_[0].fence);
        destroy_buffer(staging);
    }

    void submit_and_wait(VkCommandBuffer cmd, VkFence fence) {
        VkSubmitInfo submit{};
        submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        GLINT_VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence));
        GLINT_VK_CHECK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
        GLINT_VK_CHECK(vkResetFences(device_, 1, &fence));
    }

    VkShaderModule make_module(ShaderId id) {
        const auto code = spirv(id);
        VkShaderModuleCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
        info.codeSize = code.size_bytes();
        info.pCode = code.data();
        VkShaderModule module = VK_NULL_HANDLE;
        GLINT_VK_CHECK(vkCreateShaderModule(device_, &info, nullptr, &module));
        return module;
    }

    void create_pipeline() {
        std::array<VkAttachmentDescription, 3> att{};
        for (int i = 0; i < 2; ++i) {
            att[static_cast<std::size_t>(i)].format = i == 0 ? kNormalFormat : kIdFormat;
            att[static_cast<std::size_t>(i)].samples = VK_SAMPLE_COUNT_1_BIT;
            att[static_cast<std::size_t>(i)].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            att[static_cast<std::size_t>(i)].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            att[static_cast<std::size_t>(i)].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
            att[static_cast<std::size_t>(i)].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            att[static_cast<std::size_t>(i)].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            // Left ready for vkCmdCopyImageToBuffer.
            att[static_cast<std::size_t>(i)].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        }
        att[2].format = kDepthFormat;
        att[2].samples = VK_SAMPLE_COUNT_1_BIT;
        att[2].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        att[2].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[2].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        att[2].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        att[2].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        att[2].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        std::array<VkAttachmentReference, 2> color_refs{{
            {GLINT_ATTACHMENT_NORMAL_DEPTH, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
            {GLINT_ATTACHMENT_PRIMITIVE, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
        }};
        VkAttachmentReference depth_ref{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
        VkSubpassDescription subpass{};
        subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
        subpass.colorAttachmentCount = 2;
        subpass.pColorAttachments = color_refs.data();
        subpass.pDepthStencilAttachment = &depth_ref;
        std::array<VkSubpassDependency, 2> deps{};
        // In: the previous view in this slot read the colour images with a transfer and
        // wrote depth; the clear (and layout transition) must wait for both.
        deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
        deps[0].dstSubpass = 0;
        deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
        deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                               VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
        deps[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
        deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
        // Out: colour writes must be complete and visible before the copy to the read-back
        // buffers (the transition to TRANSFER_SRC happens inside this dependency).
        deps[1].srcSubpass = 0;
        deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
        deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
        deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
        deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
        deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        VkRenderPassCreateInfo rp{};
        rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
        rp.attachmentCount = static_cast<std::uint32_t>(att.size());
        rp.pAttachments = att.data();
        rp.subpassCount = 1;
        rp.pSubpasses = &subpass;
        rp.dependencyCount = static_cast<std::uint32_t>(deps.size());
        rp.pDependencies = deps.data();
        GLINT_VK_CHECK(vkCreateRenderPass(device_, &rp, nullptr, &render_pass_));

        VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(PushConstants)};
        VkPipelineLayoutCreateInfo pl{};
        pl.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        pl.pushConstantRangeCount = 1;
        pl.pPushConstantRanges = &range;
        GLINT_VK_CHECK(vkCreatePipelineLayout(device_, &pl, nullptr, &layout_));

        VkShaderModule vert = make_module(ShaderId::normal_vert);
        VkShaderModule frag = VK_NULL_HANDLE;
        try {
            frag = make_module(ShaderId::normal_frag);
        } catch (...) {
            vkDestroyShaderModule(device_, vert, nullptr);
            throw;
        }
        std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
        stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = vert;
        stages[0].pName = "main";
        stages[1] = stages[0];
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = frag;

        std::array<VkVertexInputBindingDescription, 2> bindings{{
            {GLINT_BINDING_POSITION, sizeof(Vec3f), VK_VERTEX_INPUT_RATE_VERTEX},
            {GLINT_BINDING_NORMAL, sizeof(Vec3f), VK_VERTEX_INPUT_RATE_VERTEX},
        }};
        std::array<VkVertexInputAttributeDescription, 2> attrs{{
            {GLINT_BINDING_POSITION, GLINT_BINDING_POSITION, VK_FORMAT_R32G32B32_SFLOAT, 0},
            {GLINT_BINDING_NORMAL, GLINT_BINDING_NORMAL, VK_FORMAT_R32G32B32_SFLOAT, 0},
        }};
        VkPipelineVertexInputStateCreateInfo vi{};
        vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
        vi.vertexBindingDescriptionCount = 2;
        vi.pVertexBindingDescriptions = bindings.data();
        vi.vertexAttributeDescriptionCount = 2;
        vi.pVertexAttributeDescriptions = attrs.data();
        VkPipelineInputAssemblyStateCreateInfo ia{};
        ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
        ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo vp{};
        vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
        vp.viewportCount = 1;
        vp.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo rs{};
        rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
        rs.polygonMode = VK_POLYGON_MODE_FILL;
        rs.cullMode = options_.cull_back_faces ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
        // note: clip_from_world flips y (Vulkan's framebuffer y points down) and Vulkan's
        // signed-area formula carries a minus sign for that reason, so a triangle that is
        // counter-clockwise seen from outside stays counter-clockwise here (checked by
        // RendererTest.BackFaceCullingLeavesAClosedMeshUnchanged).
        rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        rs.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo ms{};
        ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
        ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        VkPipelineDepthStencilStateCreateInfo ds{};
        ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
        ds.depthTestEnable = VK_TRUE;
        ds.depthWriteEnable = VK_TRUE;
        ds.depthCompareOp = VK_COMPARE_OP_LESS;
        std::array<VkPipelineColorBlendAttachmentState, 2> blend{};
        blend[0].colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                  VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
        // note: without the independentBlend feature every attachment's state must be equal;
        // the id attachment simply ignores the components it does not have.
        blend[1] = blend[0];
        VkPipelineColorBlendStateCreateInfo cb{};
        cb.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
        cb.attachmentCount = 2;
        cb.pAttachments = blend.data();
        std::array<VkDynamicState, 2> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dy{};
        dy.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
        dy.dynamicStateCount = static_cast<std::uint32_t>(dyn.size());
        dy.pDynamicStates = dyn.data();
        VkGraphicsPipelineCreateInfo gp{};
        gp.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
        gp.stageCount = 2;
        gp.pStages = stages.data();
        gp.pVertexInputState = &vi;
        gp.pInputAssemblyState = &ia;
        gp.pViewportState = &vp;
        gp.pRasterizationState = &rs;
        gp.pMultisampleState = &ms;
        gp.pDepthStencilState = &ds;
        gp.pColorBlendState = &cb;
        gp.pDynamicState = &dy;
        gp.layout = layout_;
        gp.renderPass = render_pass_;
        gp.subpass = 0;
        const VkResult r = vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &gp, nullptr, &pipeline_);
        vkDestroyShaderModule(device_, vert, nullptr);
        vkDestroyShaderModule(device_, frag, nullptr);
        if (r != VK_SUCCESS) vk_check_failed(r, "vkCreateGraphicsPipelines", __FILE__, __LINE__);
    }

    Image make_image(int w, int h, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect) {
        Image img;
        VkImageCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
        info.imageType = VK_IMAGE_TYPE_2D;
        info.format = format;
        info.extent = {static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), 1};
        info.mipLevels = 1;
        info.arrayLayers = 1;
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        GLINT_VK_CHECK(vkCreateImage(device_, &info, nullptr, &img.image));
        VkMemoryRequirements req{};
        vkGetImageMemoryRequirements(device_, img.image, &req);
        VkMemoryAllocateInfo alloc{};
        alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = find_memory_type(physical_, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        GLINT_VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &img.memory));
        GLINT_VK_CHECK(vkBindImageMemory(device_, img.image, img.memory, 0));
        VkImageViewCreateInfo v{};
        v.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        v.image = img.image;
        v.viewType = VK_IMAGE_VIEW_TYPE_2D;
        v.format = format;
        v.subresourceRange = {aspect, 0, 1, 0, 1};
        GLINT_VK_CHECK(vkCreateImageView(device_, &v, nullptr, &img.view));
        return img;
    }

    void destroy_image(Image& img) {
        if (img.view != VK_NULL_HANDLE) vkDestroyImageView(device_, img.view, nullptr);
        if (img.image != VK_NULL_HANDLE) vkDestroyImage(device_, img.image, nullptr);
        if (img.memory != VK_NULL_HANDLE) vkFreeMemory(device_, img.memory, nullptr);
        img = Image{};
    }

    void destroy_targets(Slot& slot) {
        if (slot.framebuffer != VK_NULL_HANDLE) vkDestroyFramebuffer(device_, slot.framebuffer, nullptr);
        slot.framebuffer = VK_NULL_HANDLE;
        destroy_image(slot.normal);
        destroy_image(slot.id);
        destroy_image(slot.depth);
        destroy_buffer(slot.normal_readback);
        destroy_buffer(slot.id_readback);
        slot.width = slot.height = 0;
    }

    void destroy_slot(Slot& slot) {
        destroy_targets(slot);
        if (slot.fence != VK_NULL_HANDLE) vkDestroyFence(device_, slot.fence, nullptr);
        slot.fence = VK_NULL_HANDLE;
    }

    /// (Re)creates a slot's targets for a sub-sample size; the slot is idle here.
    void ensure_targets(Slot& slot, int w, int h) {
        if (slot.width == w && slot.height == h) return;
        if (static_cast<std::uint32_t>(std::max(w, h)) > max_dimension_) {
            throw InputError("render target " + std::to_string(w) + "x" + std::to_string(h) +
                             " (size × supersample) exceeds the device limit of " +
                             std::to_string(max_dimension_) + " pixels per side");
        }
        destroy_targets(slot);
        const VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        slot.normal = make_image(w, h, kNormalFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
        slot.id = make_image(w, h, kIdFormat, color, VK_IMAGE_ASPECT_COLOR_BIT);
        slot.depth = make_image(w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                VK_IMAGE_ASPECT_DEPTH_BIT);
        std::array<VkImageView, 3> views{slot.normal.view, slot.id.view, slot.depth.view};
        VkFramebufferCreateInfo fb{};
        fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
        fb.renderPass = render_pass_;
        fb.attachmentCount = 3;
        fb.pAttachments = views.data();
        fb.width = static_cast<std::uint32_t>(w);
        fb.height = static_cast<std::uint32_t>(h);
        fb.layers = 1;
        GLINT_VK_CHECK(vkCreateFramebuffer(device_, &fb, nullptr, &slot.framebuffer));
        const VkDeviceSize pixels = static_cast<VkDeviceSize>(w) * static_cast<VkDeviceSize>(h);
        // Read-back: host-visible and coherent (no flush/invalidate needed), cached when the
        // device offers it (CPU reads of uncached memory are slow on discrete GPUs).
        const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        slot.normal_readback = make_buffer(pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host,
                                           VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        slot.id_readback = make_buffer(pixels * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, host,
                                       VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        slot.width = w;
        slot.height = h;
    }

    void record_and_submit(Slot& slot, const View& view) {
        const Camera& cam = view.camera;
        PushConstants pc{};
        const Eigen::Matrix4f clip = cam.clip_from_world().cast<float>();
        std::memcpy(pc.clip_from_world, clip.data(), sizeof(pc.clip_from_world));
        // depth = −z_camera = −(row 2 of camera_from_world) · (p, 1)
        const Eigen::Matrix4d camera_from_world = cam.world_from_camera.inverse().matrix();
        for (int k = 0; k < 4; ++k) pc.depth_row[k] = static_cast<float>(-camera_from_world(2, k));

        VkCommandBuffer cmd = slot.cmd;
        GLINT_VK_CHECK(vkResetCommandBuffer(cmd, 0));
        VkCommandBufferBeginInfo begin{};
        begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        GLINT_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
        std::array<VkClearValue, 3> clears{};
        clears[0].color.float32[0] = clears[0].color.float32[1] = clears[0].color.float32[2] = 0.0f;
        clears[0].color.float32[3] = 0.0f;
        clears[1].color.uint32[0] = GLINT_NO_PRIMITIVE;
        clears[2].depthStencil = {1.0f, 0};
        VkRenderPassBeginInfo rp{};
        rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
        rp.renderPass = render_pass_;
        rp.framebuffer = slot.framebuffer;
        rp.renderArea = {{0, 0}, {static_cast<std::uint32_t>(slot.width), static_cast<std::uint32_t>(slot.height)}};
        rp.clearValueCount = static_cast<std::uint32_t>(clears.size());
        rp.pClearValues = clears.data();
        vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
        VkViewport viewport{0.0f, 0.0f, static_cast<float>(slot.width), static_cast<float>(slot.height), 0.0f, 1.0f};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &rp.renderArea);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(pc), &pc);
        std::array<VkBuffer, 2> vbs{mesh_buffers_[0].buffer, mesh_buffers_[1].buffer};
        std::array<VkDeviceSize, 2> offsets{0, 0};
        vkCmdBindVertexBuffers(cmd, 0, 2, vbs.data(), offsets.data());
        vkCmdBindIndexBuffer(cmd, mesh_buffers_[2].buffer, 0, VK_INDEX_TYPE_UINT32);
        // One draw of every triangle from index 0, so gl_PrimitiveID is the triangle index.
        vkCmdDrawIndexed(cmd, index_count_, 1, 0, 0, 0);
        vkCmdEndRenderPass(cmd);

        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {static_cast<std::uint32_t>(slot.width), static_cast<std::uint32_t>(slot.height), 1};
        vkCmdCopyImageToBuffer(cmd, slot.normal.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               slot.normal_readback.buffer, 1, &region);
        vkCmdCopyImageToBuffer(cmd, slot.id.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               slot.id_readback.buffer, 1, &region);
        // Barrier: the copies' writes must be visible to the host reads after the fence.
        VkMemoryBarrier barrier{};
        barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
        GLINT_VK_CHECK(vkEndCommandBuffer(cmd));
        VkSubmitInfo submit{};
        submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        GLINT_VK_CHECK(vkQueueSubmit(queue_, 1, &submit, slot.fence));
    }

    /// Waits for a slot's view, resolves it and hands it to the consumer.
    void finish(Slot& slot, const MutableFrameConsumer& consumer) {
        GLINT_VK_CHECK(vkWaitForFences(device_, 1, &slot.fence, VK_TRUE, UINT64_MAX));
        GLINT_VK_CHECK(vkResetFences(device_, 1, &slot.fence));
        slot.busy = false;
        Frame& frame = slot.frame;
        if (frame.width != slot.out_width || frame.height != slot.out_height ||
            frame.coverage.size() != frame.pixel_count()) {
            frame = make_empty_frame(slot.out_width, slot.out_height);
        }
        frame.normal_space = NormalSpace::World;
        resolve_samples(static_cast<const float*>(slot.normal_readback.mapped),
                        static_cast<const std::uint32_t*>(slot.id_readback.mapped), options_.supersample,
                        threads_, frame);
        consumer(slot.view_index, frame);
    }

    RenderOptions options_;
    int threads_ = 1;
    mutable MessageLog log_;
    std::unique_ptr<Instance> instance_;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    std::uint32_t max_dimension_ = 4096;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<Buffer, 3> mesh_buffers_{};  // positions, normals, indices
    std::uint32_t index_count_ = 0;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    std::array<Slot, kSlots> slots_{};
};

}  // namespace

std::unique_ptr<RenderBackend> make_vulkan_backend(const Mesh& mesh, const RenderOptions& options,
                                                   RendererInfo& info) {
    return std::make_unique<VulkanBackend>(mesh, options, info);
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
