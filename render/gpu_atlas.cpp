#include "render/gpu_atlas.h"

#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/detail/gpu_atlas_impl.h"
#include "render/detail/vk_context.h"

#include <cmath>
#include <utility>

namespace glint {

void GpuAtlasOptions::validate() const {
    if (!(std::isfinite(missing_value) && missing_value >= 0.0f))
        throw OptionError("missing_value", missing_value, "expected a finite value ≥ 0");
    if (!(min_coverage > 0.0f && min_coverage <= 1.0f))
        throw OptionError("min_coverage", min_coverage, "expected a share in (0, 1]");
    if (!(min_cos_incidence > 0.0 && min_cos_incidence <= 1.0))
        throw OptionError("min_cos_incidence", min_cos_incidence, "expected a cosine in (0, 1]");
    if (!(std::isfinite(framed_radius) && framed_radius > 0.0))
        throw OptionError("framed_radius", framed_radius, "expected a finite length > 0");
    if (zoom_count < 1 || zoom_count > 256)
        throw OptionError("zoom_count", zoom_count, "expected 1..256");
    if (in_flight < 1 || in_flight > 8) throw OptionError("in_flight", in_flight, "expected 1..8");
}

const detail::VulkanMesh* GpuAtlas::vulkan_mesh(const Renderer& renderer) {
    return renderer.backend_ ? renderer.backend_->vulkan_mesh() : nullptr;
}

bool has_gpu_kernel(Metric metric) {
    switch (metric) {
        case Metric::AngleDeg:             // GLINT_ATLAS_METRIC 0 in shaders/atlas_pixels.comp
        case Metric::RgbAbs: return true;  // GLINT_ATLAS_METRIC_RGB
    }
    return false;  // a metric added without a kernel
}

bool GpuAtlas::supported(const Renderer& reference, const Renderer& examined,
                         const GpuAtlasOptions& options, std::string* why) {
    const auto no = [&](std::string reason) {
        if (why != nullptr) *why = std::move(reason);
        return false;
    };
    if (!has_gpu_kernel(options.metric))
        return no("metric " + std::to_string(static_cast<int>(options.metric)) +
                  " has no GPU kernel (the device would fold another metric)");
    const detail::VulkanMesh* ref = vulkan_mesh(reference);
    const detail::VulkanMesh* exa = vulkan_mesh(examined);
    if (ref == nullptr || exa == nullptr) return no("the renderers do not use the Vulkan backend");
    if (reference.context() != examined.context())
        return no("the renderers are on two render contexts");
    const RenderOptions& r = reference.options();
    const RenderOptions& e = examined.options();
    if (r.normal_space != NormalSpace::World || e.normal_space != NormalSpace::World)
        return no("view-space normals (the device compares world-space normals)");
    if (r.supersample != e.supersample || r.min_coverage != e.min_coverage)
        return no("the renderers resolve their frames differently (supersample, min_coverage)");
    const detail::VulkanDevice& device = *ref->device;
    if (!device.has_gpu_atlas())
        return no("device \"" + device.info().name + "\" " + device.info().gpu_atlas_reason);
    const VkPhysicalDeviceLimits& limits = device.limits();
    const double vertices = ref->buffers.vertex_count;
    const double zooms = std::max(options.zoom_count, 1);
    const double largest = std::max({zooms * GLINT_SUM_FIELDS * vertices * 8.0, 12.0 * vertices,
                                     4.0 * static_cast<double>(ref->buffers.index_count)});
    if (largest > static_cast<double>(limits.maxStorageBufferRange))
        return no("the atlas buffers (" + std::to_string(static_cast<long long>(largest)) +
                  " bytes) exceed the device's storage buffer range (" +
                  std::to_string(limits.maxStorageBufferRange) + ")");
    if (std::ceil(vertices / GLINT_ATLAS_VERTEX_GROUP) > limits.maxComputeWorkGroupCount[0])
        return no("the reference has more vertices than one dispatch reaches");
    return true;
}

GpuAtlas::GpuAtlas(Renderer& reference, Renderer& examined, const GpuAtlasOptions& options) {
    options.validate();
    std::string why;
    if (!supported(reference, examined, options, &why)) throw InputError("GPU atlas: " + why);
    impl_ = std::make_unique<detail::GpuAtlasImpl>(*vulkan_mesh(reference), *vulkan_mesh(examined),
                                                   reference.options().frame_options(), options);
}

GpuAtlas::~GpuAtlas() = default;
GpuAtlas::GpuAtlas(GpuAtlas&&) noexcept = default;
GpuAtlas& GpuAtlas::operator=(GpuAtlas&&) noexcept = default;

void GpuAtlas::run(std::span<const View> views, const GpuViewConsumer& consumer) {
    GLINT_ASSERT(impl_ != nullptr, "run on a moved-from GpuAtlas");
    impl_->run(views, consumer);
}

const GpuAtlasTimings& GpuAtlas::timings() const {
    GLINT_ASSERT(impl_ != nullptr, "timings of a moved-from GpuAtlas");
    return impl_->timings();
}

std::vector<AtlasTotals> GpuAtlas::read_totals() {
    GLINT_ASSERT(impl_ != nullptr, "read_totals on a moved-from GpuAtlas");
    return impl_->read_totals();
}

}  // namespace glint
