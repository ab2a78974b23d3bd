// The GPU atlas's per-view work (render/detail/gpu_atlas_impl.h has the command buffer's shape):
// view parameters, recording, the run over views, and the read-back of the totals.
#include "render/detail/gpu_atlas_impl.h"

#include "mesh/error.h"
#include "render/detail/backend.h"
#include "render/detail/vk_check.h"
#include "render/detail/vk_compute.h"
#include "spirv/bindings.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace glint::detail {
namespace {

void begin(VkCommandBuffer cmd) {
    GLINT_VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo info{};
    info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    GLINT_VK_CHECK(vkBeginCommandBuffer(cmd, &info));
}

/// Rows (R_r0, R_r1, R_r2, t_r) of an isometry.
void rows_of(const Rigid& t, double* out) {
    for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 4; ++k) out[4 * r + k] = t.matrix()(r, k);
    }
}

void check_view(const View& v, int supersample, std::uint32_t max_dimension, int zoom_count) {
    const Camera& c = v.camera;
    const long long w = static_cast<long long>(c.width) * supersample;
    const long long h = static_cast<long long>(c.height) * supersample;
    if (c.width < 1 || c.height < 1 || w > max_dimension || h > max_dimension)
        throw InputError(
            "GPU atlas: view " + std::to_string(v.index) + " of " + std::to_string(c.width) + "x" +
            std::to_string(c.height) + " pixels with supersample " + std::to_string(supersample) +
            ", expected 1.." + std::to_string(max_dimension) + " sub-samples per side");
    if (v.zoom_index < 0 || v.zoom_index >= zoom_count)
        throw InputError("GPU atlas: view " + std::to_string(v.index) + " has zoom " +
                         std::to_string(v.zoom_index) + ", expected 0.." +
                         std::to_string(zoom_count - 1));
}

}  // namespace

void GpuAtlasImpl::write_params(Slot& slot, const View& view, const Scales& scales) {
    const Camera& cam = view.camera;
    AtlasParams p{};
    rows_of(cam.world_from_camera, p.world_from_camera);
    // As Projector does (mesh/geometry.cpp): the inverse isometry, the image's half extents.
    rows_of(cam.world_from_camera.inverse(), p.camera_from_world);
    const Vec3d eye = cam.eye();
    const Vec3d to_camera = -cam.forward();
    for (int k = 0; k < 3; ++k) {
        p.eye[k] = eye[k];
        p.to_ortho_camera[k] = to_camera[k];
    }
    const double aspect = static_cast<double>(cam.width) / cam.height;
    const bool ortho = cam.projection == Projection::Orthographic;
    const double half_height = ortho ? cam.ortho_half_height : std::tan(0.5 * cam.fov_y_rad);
    p.frame[0] = cam.width;
    p.frame[1] = cam.height;
    p.frame[2] = aspect;
    p.frame[3] = cam.ortho_half_height;
    p.projector[0] = half_height * aspect;
    p.projector[1] = half_height;
    p.projector[2] =
        std::max(3.0 * view.footprint, 0.02 * options_.framed_radius);  // backproject.cpp gather
    p.projector[3] = options_.min_cos_incidence;
    // The view's angle sum: at most 180° per compared pixel.
    slot.angle_scale =
        std::ldexp(1.0, 62 - 8 - bits_for(static_cast<double>(cam.width) * cam.height));
    p.scales[0] = scales.weight;
    p.scales[1] = scales.value;
    p.scales[2] = scales.depth;
    p.scales[3] = slot.angle_scale;
    p.camera[0] = std::tan(0.5 * cam.fov_y_rad);  // Camera::pixel_ray
    const auto vertices = reference_.buffers.vertex_count;
    const auto zoom = static_cast<std::uint32_t>(view.zoom_index);
    p.size[0] = static_cast<std::uint32_t>(cam.width);
    p.size[1] = static_cast<std::uint32_t>(cam.height);
    p.size[2] = static_cast<std::uint32_t>(supersample_);
    p.size[3] = vertices;
    p.mode[0] = (ortho ? 0u : GLINT_ATLAS_PERSPECTIVE) |
                (options_.metric == Metric::RgbAbs ? GLINT_ATLAS_METRIC_RGB : 0u);
    p.mode[1] = zoom * GLINT_SUM_FIELDS * vertices;
    p.mode[2] = zoom * GLINT_WORD_FIELDS * vertices;
    p.view[0] = view.index;
    p.thresholds[0] =
        1.0f / static_cast<float>(supersample_ * supersample_);  // resolve.cpp inv_samples
    p.thresholds[1] = options_.min_coverage;
    p.thresholds[2] = mask_threshold_;
    p.thresholds[3] = options_.missing_value;
    p.rgb[0] = 1.0f / static_cast<float>(
                          std::numeric_limits<std::uint8_t>::max());  // OpenImageIO's uint8 → float
    std::memcpy(slot.params.mapped, &p, sizeof(p));
}

/// Clears every accumulator: sums, counts and maxima 0, views -1, best incidence -2 (as
/// AtlasAccumulator starts), and this view's scratch 0.
void GpuAtlasImpl::record_clear(VkCommandBuffer cmd) {
    // Barrier: a previous run's passes and read-back copies are done with the accumulators
    // before the fills overwrite them (write-after-read and write-after-write).
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, sums_.buffer, 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, scratch_key_.buffer, 0, VK_WHOLE_SIZE, 0u);
    vkCmdFillBuffer(cmd, scratch_cos_.buffer, 0, VK_WHOLE_SIZE, 0u);
    const VkDeviceSize field = VkDeviceSize{reference_.buffers.vertex_count} * 4;
    const std::array<std::uint32_t, GLINT_WORD_FIELDS> initial{
        0u, 0u, 0u, 0xFFFFFFFFu, std::bit_cast<std::uint32_t>(-2.0f), 0xFFFFFFFFu};
    for (int z = 0; z < options_.zoom_count; ++z) {
        for (std::size_t f = 0; f < initial.size(); ++f) {
            const VkDeviceSize offset =
                (static_cast<VkDeviceSize>(z) * GLINT_WORD_FIELDS + f) * field;
            vkCmdFillBuffer(cmd, words_.buffer, offset, field, initial[f]);
        }
    }
}

// Draws this view's two frames: the compute rasteriser, or the graphics pipeline's render passes.
void GpuAtlasImpl::record_frames(Slot& slot, const View& view) {
    VkCommandBuffer cmd = slot.cmd;
    if (raster_ != nullptr) {
        // The frames in compute. Its first barrier stands for the two above: the previous
        // view's passes and copies (earlier) and the clear come before the fills (the summary's
        // among them) and the passes; this view's passes read the frames next (later).
        // note: two barriers fewer per view: each drains the device (measured on the H100 at
        // 1M triangles, 1024²: ~25 µs per view outside the stages, 12 % of the view).
        const std::array<RasterJob, 2> jobs{{
            {.target = &slot.reference.raster,
             .mesh = &reference_.buffers,
             .normal_depth = slot.reference.normal_depth.image,
             .primitive = slot.reference.primitive.image,
             .cull_back_faces = reference_.cull_back_faces},
            {.target = &slot.examined.raster,
             .mesh = &examined_.buffers,
             .normal_depth = slot.examined.normal_depth.image,
             .primitive = slot.examined.primitive.image,
             .cull_back_faces = examined_.cull_back_faces},
        }};
        const std::array<VkBuffer, 1> zero{slot.summary.buffer};
        record_compute_normal_passes(
            cmd, *raster_, jobs, slot.width, slot.height, view,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, zero,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    } else {
        // The frames: the render pass's dependencies order the colour writes before the
        // passes' imageLoad, and the previous view's reads of these targets before the clear.
        const VkPipelineLayout graphics_layout = device_->layout();
        record_normal_pass(cmd, pipelines_->render_pass, slot.reference.framebuffer, slot.width,
                           slot.height, pipelines_->graphics[reference_.cull_back_faces ? 1 : 0],
                           graphics_layout, reference_.buffers, view);
        record_normal_pass(cmd, pipelines_->render_pass, slot.examined.framebuffer, slot.width,
                           slot.height, pipelines_->graphics[examined_.cull_back_faces ? 1 : 0],
                           graphics_layout, examined_.buffers, view);
    }
}

void GpuAtlasImpl::record(Slot& slot, const View& view, bool clear_first) {
    VkCommandBuffer cmd = slot.cmd;
    begin(cmd);
    if (clear_first) record_clear(cmd);
    // Timestamps, each written once every command before it has completed.
    const auto stamp = [&](std::uint32_t query) {
        if (slot.timestamps != VK_NULL_HANDLE)
            vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.timestamps, query);
    };
    if (slot.timestamps != VK_NULL_HANDLE) vkCmdResetQueryPool(cmd, slot.timestamps, 0, 4);
    if (raster_ == nullptr) {
        // Barrier: the previous view's passes (atlas, scratch and pixel buffer writes) and its
        // summary copy, and the clear above, come before this view's summary fill and passes.
        barrier(
            cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        vkCmdFillBuffer(cmd, slot.summary.buffer, 0, VK_WHOLE_SIZE, 0u);
        // Barrier: the zeroed summary before the pixel pass's atomics on it.
        barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    stamp(0);
    record_frames(slot, view);
    stamp(1);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->layout, 0, 1,
                            &slot.set, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->pixels);
    const auto w = static_cast<std::uint32_t>(view.camera.width);
    const auto h = static_cast<std::uint32_t>(view.camera.height);
    vkCmdDispatch(cmd, groups(w, GLINT_ATLAS_TILE), groups(h, GLINT_ATLAS_TILE), 1);
    stamp(2);
    // Barrier: the pixel pass's atomics (atlas, scratch) and pixel buffer before the vertex
    // pass reads and folds them.
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_->vertices);
    vkCmdDispatch(cmd, groups(reference_.buffers.vertex_count, GLINT_ATLAS_VERTEX_GROUP), 1, 1);
    stamp(3);
    // Barrier: the summary's atomics (pixel pass) before its copy to the host-visible buffer.
    barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy copy{0, 0, sizeof(ViewTotals)};
    vkCmdCopyBuffer(cmd, slot.summary.buffer, slot.summary_host.buffer, 1, &copy);
    // Barrier: the copy's write before the host reads it after the fence.
    barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    GLINT_VK_CHECK(vkEndCommandBuffer(cmd));
    device_->submit(cmd, slot.fence);
}

void GpuAtlasImpl::add_timings(const Slot& slot) {
    std::array<std::uint64_t, 4> ticks{};
    GLINT_VK_CHECK(vkGetQueryPoolResults(device_->device(), slot.timestamps, 0, 4, sizeof(ticks),
                                         ticks.data(), sizeof(std::uint64_t),
                                         VK_QUERY_RESULT_64_BIT));
    const std::uint32_t bits = device_->timestamp_bits();
    const std::uint64_t mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1;
    const double seconds_per_tick = 1e-9 * device_->limits().timestampPeriod;
    const auto span = [&](int a, int b) {
        return seconds_per_tick * static_cast<double>((ticks[b] - ticks[a]) & mask);
    };
    timings_.measured = true;
    ++timings_.views;
    timings_.render_s += span(0, 1);
    timings_.pixels_s += span(1, 2);
    timings_.vertices_s += span(2, 3);
}

void GpuAtlasImpl::wait(Slot& slot) {
    const VkDevice dev = device_->device();
    GLINT_VK_CHECK(vkWaitForFences(dev, 1, &slot.fence, VK_TRUE, UINT64_MAX));
    GLINT_VK_CHECK(vkResetFences(dev, 1, &slot.fence));
    slot.busy = false;
}

ViewNumbers GpuAtlasImpl::finish(Slot& slot) {
    const auto t0 = std::chrono::steady_clock::now();
    wait(slot);
    timings_.host_wait_s +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (slot.timestamps != VK_NULL_HANDLE) add_timings(slot);
    ViewTotals t{};
    std::memcpy(&t, slot.summary_host.mapped, sizeof(t));
    ViewNumbers s;
    s.reference_pixels = t.reference_pixels;
    s.compared = t.compared;
    s.reference_only = t.reference_only;
    s.examined_only = t.examined_only;
    s.max_angle_deg = std::bit_cast<float>(t.max_angle_bits);
    s.mean_angle_deg =
        t.compared ? static_cast<double>(t.angle_sum) / slot.angle_scale / t.compared : 0.0;
    return s;
}

void GpuAtlasImpl::run(std::span<const View> views, const GpuViewConsumer& consumer) {
    std::size_t largest = 1;
    for (const View& v : views) {
        check_view(v, supersample_, device_->max_dimension(), options_.zoom_count);
        largest = std::max(largest, static_cast<std::size_t>(v.camera.width) *
                                        static_cast<std::size_t>(v.camera.height));
    }
    scales_ = scales_for(views);
    timings_ = GpuAtlasTimings{};
    const auto started = std::chrono::steady_clock::now();
    try {
        ensure_pixels(largest);
        if (views.empty()) {  // nothing to render: the accumulators are cleared all the same
            Slot& slot = slots_[0];
            begin(slot.cmd);
            record_clear(slot.cmd);
            GLINT_VK_CHECK(vkEndCommandBuffer(slot.cmd));
            device_->submit(slot.cmd, slot.fence);
            slot.busy = true;
            wait_all();
        }
        for (std::size_t i = 0; i < views.size(); ++i) {
            Slot& slot = slots_[i % slots_.size()];
            if (slot.busy) {
                const ViewNumbers summary = finish(slot);
                if (consumer) consumer(slot.view, summary);
            }
            const View& view = views[i];
            ensure_targets(slot, view.camera.width * supersample_,
                           view.camera.height * supersample_);
            if (!slot.set_current) write_set(slot);
            write_params(slot, view, scales_[static_cast<std::size_t>(view.zoom_index)]);
            record(slot, view, i == 0);
            slot.busy = true;
            slot.view = i;
        }
        // The views still in flight, oldest first.
        for (std::size_t i = views.size() > slots_.size() ? views.size() - slots_.size() : 0;
             i < views.size(); ++i) {
            Slot& slot = slots_[i % slots_.size()];
            if (!slot.busy) continue;
            const ViewNumbers summary = finish(slot);
            if (consumer) consumer(slot.view, summary);
        }
    } catch (...) {
        wait_all();
        throw;
    }
    has_run_ = true;
    timings_.host_work_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() -
        timings_.host_wait_s;
}

std::vector<AtlasTotals> GpuAtlasImpl::read_totals() {
    GLINT_ASSERT(has_run_, "GPU atlas totals read before run()");
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const VkDevice dev = device_->device();
    if (staging_.buffer == VK_NULL_HANDLE)
        staging_ = make_buffer(dev, device_->physical(), sums_.size + words_.size,
                               VK_BUFFER_USAGE_TRANSFER_DST_BIT, kHostMemory,
                               VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    const Buffer& staging = staging_;
    std::vector<AtlasTotals> out;
    try {
        Slot& slot = slots_[0];
        begin(slot.cmd);
        // Barrier: the last view's vertex pass wrote the accumulators; the copies read them.
        barrier(slot.cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        const std::array<VkBufferCopy, 2> copies{
            {{0, 0, sums_.size}, {0, sums_.size, words_.size}}};
        vkCmdCopyBuffer(slot.cmd, sums_.buffer, staging.buffer, 1, &copies[0]);
        vkCmdCopyBuffer(slot.cmd, words_.buffer, staging.buffer, 1, &copies[1]);
        // Barrier: the copies' writes before the host reads the staging buffer.
        barrier(slot.cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        GLINT_VK_CHECK(vkEndCommandBuffer(slot.cmd));
        device_->submit(slot.cmd, slot.fence);
        slot.busy = true;
        wait(slot);
        const auto t1 = Clock::now();
        out = totals_from(static_cast<const std::int64_t*>(staging.mapped),
                          reinterpret_cast<const std::uint32_t*>(
                              static_cast<const unsigned char*>(staging.mapped) + sums_.size));
        timings_.totals_copy_s = std::chrono::duration<double>(t1 - t0).count();
        timings_.totals_convert_s = std::chrono::duration<double>(Clock::now() - t1).count();
    } catch (...) {
        wait_all();
        throw;
    }
    return out;
}

std::vector<AtlasTotals> GpuAtlasImpl::totals_from(const std::int64_t* sums,
                                                   const std::uint32_t* words) const {
    const std::size_t n = reference_.buffers.vertex_count;
    std::vector<AtlasTotals> out(static_cast<std::size_t>(options_.zoom_count));
    for (std::size_t z = 0; z < out.size(); ++z) {
        AtlasTotals& t = out[z];
        const Scales& sc = scales_[z];
        const std::int64_t* sum = sums + z * GLINT_SUM_FIELDS * n;
        const std::uint32_t* word = words + z * GLINT_WORD_FIELDS * n;
        const auto field = [&](int f) { return sum + static_cast<std::size_t>(f) * n; };
        const auto word_field = [&](int f) { return word + static_cast<std::size_t>(f) * n; };
        t.weight_resolution = 1.0 / sc.weight;
        t.value_resolution = 1.0 / sc.value;
        t.depth_resolution = 1.0 / sc.depth;
        // The 32-bit fields are the device's bits as they are (floats, ints, counts).
        const auto copy_bits = [&](auto& to, int f) {
            to.resize(n);
            static_assert(sizeof(to[0]) == sizeof(std::uint32_t));
            std::memcpy(to.data(), word_field(f), n * sizeof(std::uint32_t));
        };
        // Fixed point to double: the scales are powers of two, so the multiplication by the
        // step is exact (as the division it replaces, at a fifth of its cost).
        const auto to_double = [&](std::vector<double>& to, const std::int64_t* from,
                                   const std::int64_t* minus, double step) {
            to.resize(n);
            for (std::size_t v = 0; v < n; ++v) {
                const std::int64_t x = minus != nullptr ? from[v] - minus[v] : from[v];
                to[v] = static_cast<double>(x) * step;
            }
        };
        // One task per field, on the context's workers: at 1M triangles (500k vertices, 32 MB
        // of output) one thread took 10-11 ms on the H100 machine, most of it the first touch
        // of the new vectors' pages, which threads take side by side.
        constexpr int kFields = 11;
        parallel_for(kFields, device_->threads(), [&](int begin, int end) {
            for (int f = begin; f < end; ++f) {
                switch (f) {
                    case 0: copy_bits(t.value_max, GLINT_WORD_MAX); break;
                    case 1: copy_bits(t.depth_at_max, GLINT_WORD_DEPTH_AT_MAX); break;
                    case 2: copy_bits(t.max_view, GLINT_WORD_MAX_VIEW); break;
                    case 3: copy_bits(t.best_cos, GLINT_WORD_BEST_COS); break;
                    case 4: copy_bits(t.best_view, GLINT_WORD_BEST_VIEW); break;
                    case 5: copy_bits(t.count, GLINT_WORD_COUNT); break;
                    case 6:
                        to_double(t.weight, field(GLINT_SUM_WEIGHT), nullptr, t.weight_resolution);
                        break;
                    case 7:
                        to_double(t.missing_weight, field(GLINT_SUM_MISSING), nullptr,
                                  t.weight_resolution);
                        break;
                    case 8:
                        // Every valid observation either found no examined surface (missing, no
                        // depth) or was compared (finite depth): the depth weight is the rest.
                        to_double(t.depth_weight, field(GLINT_SUM_WEIGHT), field(GLINT_SUM_MISSING),
                                  t.weight_resolution);
                        break;
                    case 9:
                        to_double(t.value_sum, field(GLINT_SUM_VALUE), nullptr, t.value_resolution);
                        break;
                    default:
                        to_double(t.depth_sum, field(GLINT_SUM_DEPTH), nullptr, t.depth_resolution);
                        break;
                }
            }
        });
    }
    return out;
}

}  // namespace glint::detail
