// CPU resolve of s×s sub-samples into one pixel (DESIGN.md "footprint averaging"):
//   n_pixel = normalize( Σ_covered n_k ),  depth = mean_covered(depth_k),
//   coverage = covered / s².
// Each n_k is already the normalised interpolated vertex normal at that sub-sample, so the
// pixel shows the mean normal direction over its footprint, renormalised, and a partly
// covered silhouette pixel still carries a unit normal (normalised by coverage). Every
// covered pixel of a frame has a unit normal.
#include "render/detail/backend.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

namespace glint::detail {

int worker_count(int requested) {
    if (requested > 0) return requested;
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

void parallel_for(int count, int threads, const std::function<void(int, int)>& body) {
    threads = std::clamp(threads, 1, std::max(count, 1));
    if (threads == 1) {
        body(0, count);
        return;
    }
    const auto chunk_begin = [&](int t) {
        return static_cast<int>(static_cast<long long>(count) * t / threads);
    };
    // note: oneTBB's workers persist across calls; starting `threads` std::threads per
    // frame cost more than resolving a 512² frame on a GPU machine. The arena caps the
    // concurrency at `threads` (RenderOptions::threads).
    tbb::task_arena arena(threads);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, threads, 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int t = r.begin(); t != r.end(); ++t) body(chunk_begin(t), chunk_begin(t + 1));
            },
            tbb::simple_partitioner());
    });
}

void resolve_rows(const float* normal_depth, const std::uint32_t* ids, int s, int y0, int y1,
                  Frame& frame) {
    const int w = frame.width;
    const std::size_t sw = static_cast<std::size_t>(w) * static_cast<std::size_t>(s);
    const int centre = s / 2;  // centre sub-sample (even s: just below-right of the centre)
    const float inv_samples = 1.0f / static_cast<float>(s * s);
    for (int y = y0; y < y1; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                  static_cast<std::size_t>(x);
            float nx = 0.0f, ny = 0.0f, nz = 0.0f, depth = 0.0f;
            int covered = 0;
            std::uint32_t first_id = kNoPrimitive;
            std::uint32_t centre_id = kNoPrimitive;
            for (int j = 0; j < s; ++j) {
                const std::size_t row =
                    (static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(s) +
                     static_cast<std::size_t>(j)) *
                        sw +
                    static_cast<std::size_t>(x) * static_cast<std::size_t>(s);
                for (int i = 0; i < s; ++i) {
                    const std::size_t k = row + static_cast<std::size_t>(i);
                    const std::uint32_t id = ids[k];
                    if (id == kNoPrimitive) continue;
                    const float* nd = normal_depth + 4 * k;
                    nx += nd[0];
                    ny += nd[1];
                    nz += nd[2];
                    depth += nd[3];
                    ++covered;
                    if (first_id == kNoPrimitive) first_id = id;
                    if (i == centre && j == centre) centre_id = id;
                }
            }
            // A footprint whose sub-sample normals cancel (a knife edge seen along its ridge)
            // has no mean direction: its sum is shorter than 1e-3 of what aligned normals give.
            // Such a pixel is reported uncovered, so no non-unit normal reaches a comparison.
            const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
            if (covered == 0 || len <= 1e-3f * static_cast<float>(covered)) {
                frame.normal[3 * p] = frame.normal[3 * p + 1] = frame.normal[3 * p + 2] = 0.0f;
                frame.primitive_id[p] = kNoPrimitive;
                frame.depth[p] = kNoDepth;
                frame.coverage[p] = 0.0f;
                continue;
            }
            const float inv = 1.0f / len;
            frame.normal[3 * p] = nx * inv;
            frame.normal[3 * p + 1] = ny * inv;
            frame.normal[3 * p + 2] = nz * inv;
            frame.primitive_id[p] = centre_id != kNoPrimitive ? centre_id : first_id;
            frame.depth[p] = depth / static_cast<float>(covered);
            frame.coverage[p] = static_cast<float>(covered) * inv_samples;
        }
    }
}

void resolve_samples(const float* normal_depth, const std::uint32_t* ids, int s, int threads,
                     Frame& frame) {
    const std::size_t sub_row = static_cast<std::size_t>(frame.width) *
                                static_cast<std::size_t>(s) *
                                static_cast<std::size_t>(s);  // sub-samples per output row
    // note: below ~64k sub-samples the thread start costs more than it saves.
    const int row_threads =
        frame.pixel_count() * static_cast<std::size_t>(s * s) < 64 * 1024 ? 1 : threads;
    parallel_for(frame.height, row_threads, [&](int y0, int y1) {
        const std::size_t offset = static_cast<std::size_t>(y0) * sub_row;
        resolve_rows(normal_depth + 4 * offset, ids + offset, s, y0, y1, frame);
    });
}

}  // namespace glint::detail
