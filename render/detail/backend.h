// Internal interface every render backend implements (not part of the public API).
#pragma once

#include "mesh/mesh.h"
#include "render/frame.h"
#include "render/renderer.h"
#include "render/view.h"

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace glint::detail {

/// Receives resolved frames (world-space normals, unmasked); may modify them in place.
using MutableFrameConsumer = std::function<void(std::size_t view_index, Frame& frame)>;

class RenderBackend {
public:
    virtual ~RenderBackend() = default;
    /// Renders views in order, resolving s×s sub-samples, and hands each frame over.
    virtual void render_views(std::span<const View> views, const MutableFrameConsumer& consumer) = 0;
    virtual std::vector<std::string> validation_messages() const { return {}; }
};

/// Creates the Vulkan backend; fills info.device_name / device_type.
std::unique_ptr<RenderBackend> make_vulkan_backend(const Mesh& mesh, const RenderOptions& options,
                                                   RendererInfo& info);
/// Creates the Embree backend; fills info.device_name / device_type.
std::unique_ptr<RenderBackend> make_embree_backend(const Mesh& mesh, const RenderOptions& options,
                                                   RendererInfo& info);

/// Threads to use for CPU work given RenderOptions::threads (0 = hardware concurrency).
int worker_count(int requested);

/// Runs body(begin, end) over [0, count) split into `threads` contiguous chunks.
void parallel_for(int count, int threads, const std::function<void(int begin, int end)>& body);

/// Resolves sub-sample buffers of a (width·s) × (height·s) image into `frame` (sized
/// width × height). normal_depth: 4 floats per sub-sample (unit normal xyz, linear depth);
/// ids: one per sub-sample, kNoPrimitive where uncovered. See render/frame.h for the rules.
void resolve_samples(const float* normal_depth, const std::uint32_t* ids, int s, int threads,
                     Frame& frame);

/// Resolves output rows [y0, y1) of `frame`; the buffers start at sub-sample row y0·s.
void resolve_rows(const float* normal_depth, const std::uint32_t* ids, int s, int y0, int y1, Frame& frame);

}  // namespace glint::detail
