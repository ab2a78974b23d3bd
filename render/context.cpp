#include "render/context.h"

#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/renderer.h"

#include <cstdlib>
#include <mutex>
#include <utility>

namespace glint {

Backend parse_backend(const std::string& text) {
    if (text == "auto") return Backend::Auto;
    if (text == "vulkan") return Backend::Vulkan;
    if (text == "embree") return Backend::Embree;
    throw InputError("backend \"" + text + "\": expected auto, vulkan or embree");
}

std::string to_string(Backend backend) {
    switch (backend) {
        case Backend::Auto: return "auto";
        case Backend::Vulkan: return "vulkan";
        case Backend::Embree: return "embree";
    }
    return "?";
}

Raster parse_raster(const std::string& text) {
    if (text == "auto") return Raster::Auto;
    if (text == "graphics") return Raster::Graphics;
    if (text == "compute") return Raster::Compute;
    throw InputError("raster \"" + text + "\": expected auto, graphics or compute");
}

std::string to_string(Raster raster) {
    switch (raster) {
        case Raster::Auto: return "auto";
        case Raster::Graphics: return "graphics";
        case Raster::Compute: return "compute";
    }
    return "?";
}

void ContextOptions::validate() const {
    if (!device.empty() && backend == Backend::Embree)
        throw OptionError(
            "device", "\"" + device + "\"",
            "names a Vulkan device, but backend = embree (expected backend vulkan or auto)");
    if (threads < 0) throw OptionError("threads", threads, "expected ≥ 0 (0 = all cores)");
    if (raster != Raster::Auto && backend == Backend::Embree)
        throw OptionError("raster", to_string(raster),
                          "chooses the Vulkan rasteriser, but backend = embree (expected auto)");
}

void FrameOptions::validate() const {
    // note: 8×8 = 64 sub-samples per pixel is far beyond any useful footprint averaging and
    // keeps the s× target within device limits for the image sizes glint uses.
    if (supersample < 1 || supersample > 8)
        throw OptionError("supersample", supersample, "expected 1..8");
    if (!(min_coverage >= 0.0f && min_coverage <= 1.0f))
        throw OptionError("min_coverage", min_coverage, "expected 0..1");
}

namespace detail {

CreationCounters& creation_counters() {
    static CreationCounters counters;
    return counters;
}

}  // namespace detail

RenderContextStats render_context_stats() {
    const auto& c = detail::creation_counters();
    return RenderContextStats{.contexts = c.contexts.load(),
                              .vulkan_instances = c.vulkan_instances.load(),
                              .vulkan_devices = c.vulkan_devices.load(),
                              .embree_devices = c.embree_devices.load(),
                              .embree_scenes = c.embree_scenes.load()};
}

namespace {

bool env_flag(const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0' && std::string(v) != "0";
}

/// The options with the environment folded in (device name, validation).
ContextOptions effective(ContextOptions options) {
    if (env_flag("GLINT_VK_VALIDATION")) options.validation = true;
    if (options.device.empty() && options.backend != Backend::Embree) {
        if (const char* env = std::getenv("GLINT_DEVICE")) options.device = env;
    }
    if (options.raster == Raster::Auto && options.backend != Backend::Embree) {
        const char* env = std::getenv("GLINT_RASTER");
        if (env != nullptr && *env != '\0') options.raster = parse_raster(env);
    }
    return options;
}

}  // namespace

RenderContext::RenderContext(const ContextOptions& options) : options_(effective(options)) {
    options.validate();
    std::string reason;
    const Backend chosen = resolve_backend(
        RenderOptions{.backend = options_.backend, .device = options_.device}, 0, &reason);
    if (options_.backend == Backend::Auto) warnings_.push_back(reason);
    options_.backend = chosen;
    impl_ = chosen == Backend::Vulkan
                ? detail::make_vulkan_context(options_, device_name_, device_type_, options_.raster)
                : detail::make_embree_context(options_, device_name_, device_type_);
    ++detail::creation_counters().contexts;
}

RenderContext::~RenderContext() = default;

std::vector<std::string> RenderContext::validation_messages() const {
    return impl_->validation_messages();
}

std::shared_ptr<RenderContext> shared_render_context(const ContextOptions& options) {
    options.validate();
    const ContextOptions key = effective(options);
    // note: never destroyed: devices torn down by static destructors at exit can outlive
    // the driver they belong to (the same reason the Vulkan anchor instance is kept).
    static auto* contexts = new std::vector<std::shared_ptr<RenderContext>>();
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& c : *contexts) {
        // A context remembers its resolved backend; Auto matches whatever it resolved to.
        ContextOptions asked = key;
        if (asked.backend == Backend::Auto) asked.backend = c->backend();
        if (asked.raster == Raster::Auto) asked.raster = c->options().raster;
        if (c->options() == asked && c->warnings().empty() == (key.backend != Backend::Auto))
            return c;
    }
    contexts->push_back(std::make_shared<RenderContext>(options));
    return contexts->back();
}

}  // namespace glint
