#include "render/renderer.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/validate.h"
#include "render/detail/backend.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>
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

void RenderOptions::validate() const {
    // note: 8×8 = 64 sub-samples per pixel is far beyond any useful footprint averaging and
    // keeps the s× target within device limits for the image sizes glint uses.
    if (supersample < 1 || supersample > 8) throw OptionError("supersample", supersample, "expected 1..8");
    if (!(min_coverage >= 0.0f && min_coverage <= 1.0f)) throw OptionError("min_coverage", min_coverage, "expected 0..1");
    if (!device.empty() && backend == Backend::Embree)
        throw OptionError("device", "\"" + device + "\"",
                          "names a Vulkan device, but backend = embree (expected backend vulkan or auto)");
    if (threads < 0) throw OptionError("threads", threads, "expected ≥ 0 (0 = all cores)");
}

namespace {

bool env_flag(const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0' && std::string(v) != "0";
}

void check_view(const View& view, int supersample) {
    const Camera& c = view.camera;
    const long long limit = 16384;
    if (c.width < 1 || c.height < 1 || c.width * static_cast<long long>(supersample) > limit ||
        c.height * static_cast<long long>(supersample) > limit) {
        std::ostringstream s;
        s << "view " << view.index << ": size " << c.width << "x" << c.height << " with supersample "
          << supersample << ", expected 1.." << limit << " sub-samples per side";
        throw InputError(s.str());
    }
    if (!(c.near_plane > 0.0 && c.far_plane > c.near_plane)) {
        std::ostringstream s;
        s << "view " << view.index << ": near " << c.near_plane << ", far " << c.far_plane
          << ", expected 0 < near < far";
        throw InputError(s.str());
    }
    if (c.projection == Projection::Orthographic && !(c.ortho_half_height > 0.0)) {
        throw InputError("view " + std::to_string(view.index) + ": ortho_half_height must be > 0");
    }
}

}  // namespace

Backend resolve_backend(const RenderOptions& options, std::size_t triangle_count,
                        std::string* reason) {
    const auto say = [&](std::string text) {
        if (reason != nullptr) *reason = std::move(text);
    };
    if (options.backend != Backend::Auto) {
        say("backend chosen explicitly");
        return options.backend;
    }
    if (!options.device.empty() || std::getenv("GLINT_DEVICE") != nullptr) {
        say("a Vulkan device was named");
        return Backend::Vulkan;
    }
    std::vector<DeviceInfo> devices;
    try {
        devices = list_devices();
    } catch (const DeviceError& e) {
        say(std::string("auto: no Vulkan (") + e.what() + "), using Embree");
        return Backend::Embree;
    }
    for (const auto& d : devices) {
        if (d.is_usable && d.type != "cpu") {
            say("auto: GPU \"" + d.name + "\" present, using Vulkan");
            return Backend::Vulkan;
        }
    }
    // note: on CPU-only machines Embree's ray casting beats lavapipe's single-threaded
    // triangle setup at every mesh size we measured (bench/render_bench.cpp).
    say("auto: no GPU, " + std::to_string(triangle_count) +
        " triangles on the CPU: Embree is faster than lavapipe");
    return Backend::Embree;
}

Renderer::Renderer(const Mesh& mesh, const RenderOptions& options) : options_(options) {
    options_.validate();
    if (env_flag("GLINT_VK_VALIDATION")) options_.validation = true;
    if (mesh.triangles.empty()) throw InputError("renderer: mesh has no triangles");
    info_.triangle_count = mesh.triangle_count();
    info_.vertex_count = mesh.vertex_count();
    std::string reason;
    info_.backend = resolve_backend(options_, mesh.triangle_count(), &reason);
    if (options_.backend == Backend::Auto) info_.warnings.push_back(reason);
    if (options_.cull_back_faces) {
        // Culling is only correct for a closed surface: an open one would lose its back side
        // (seen through a hole or from behind). It is turned off, and the warnings say so.
        const ValidationReport report = validate_mesh(mesh, "renderer");
        if (!report.is_closed) {
            options_.cull_back_faces = false;
            info_.warnings.push_back("back-face culling turned off: the mesh is not closed (" +
                                     std::to_string(report.boundary_edges) + " boundary, " +
                                     std::to_string(report.non_manifold_edges) +
                                     " non-manifold edges)");
        }
    }

    const Mesh* source = &mesh;
    Mesh with_normals;
    if (!mesh.has_normals()) {
        with_normals.positions = mesh.positions;
        with_normals.triangles = mesh.triangles;
        compute_vertex_normals(with_normals);
        info_.computed_normals = true;
        info_.warnings.push_back("mesh had no vertex normals: angle-weighted normals computed");
        source = &with_normals;
    }
    if (info_.backend == Backend::Vulkan) {
        backend_ = detail::make_vulkan_backend(*source, options_, info_);
    } else {
        backend_ = detail::make_embree_backend(*source, options_, info_);
    }
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

const RendererInfo& Renderer::info() const { return info_; }
const RenderOptions& Renderer::options() const { return options_; }

std::vector<std::string> Renderer::validation_messages() const {
    return backend_ ? backend_->validation_messages() : std::vector<std::string>{};
}

namespace {

/// Applies the options that do not depend on the backend: coverage mask, normal space.
void finish_frame(Frame& frame, const View& view, const RenderOptions& options) {
    const std::size_t n = frame.pixel_count();
    if (options.min_coverage > 0.0f) {
        // note: coverage is a multiple of 1/s²; the 1e-6 slack keeps min_coverage = 1 from
        // rejecting fully covered pixels through float rounding.
        const float threshold = options.min_coverage - 1e-6f;
        for (std::size_t p = 0; p < n; ++p) {
            if (frame.coverage[p] > 0.0f && frame.coverage[p] < threshold) {
                frame.normal[3 * p] = frame.normal[3 * p + 1] = frame.normal[3 * p + 2] = 0.0f;
                frame.primitive_id[p] = kNoPrimitive;
                frame.depth[p] = kNoDepth;
                frame.coverage[p] = 0.0f;
            }
        }
    }
    if (options.normal_space == NormalSpace::View) {
        const Eigen::Matrix3f camera_from_world =
            view.camera.world_from_camera.linear().transpose().cast<float>();
        for (std::size_t p = 0; p < n; ++p) {
            Eigen::Map<Eigen::Vector3f> nrm(&frame.normal[3 * p]);
            nrm = camera_from_world * Eigen::Vector3f(nrm);
        }
    }
    frame.normal_space = options.normal_space;
}

}  // namespace

void Renderer::render_views(std::span<const View> views, const FrameConsumer& consumer) {
    GLINT_ASSERT(backend_ != nullptr, "render_views on a moved-from Renderer");
    for (const View& v : views) check_view(v, options_.supersample);
    backend_->render_views(views, [&](std::size_t i, Frame& frame) {
        finish_frame(frame, views[i], options_);
        consumer(i, frame);
    });
}

Frame Renderer::render(const View& view) {
    GLINT_ASSERT(backend_ != nullptr, "render on a moved-from Renderer");
    check_view(view, options_.supersample);
    Frame result;
    backend_->render_views(std::span<const View>(&view, 1), [&](std::size_t, Frame& frame) {
        finish_frame(frame, view, options_);
        result = std::move(frame);
    });
    return result;
}

}  // namespace glint
