#include "report/detail/picture_batches.h"

#include "mesh/cancel.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <thread>
#include <vector>

namespace glint::detail {

std::size_t batch_size(int threads) {
    const int workers =
        threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    return static_cast<std::size_t>(std::clamp(2 * workers, 2, 16));
}

void render_in_batches(Renderer& renderer, std::span<const View> views, int threads,
                       const std::function<void(std::size_t, std::size_t, const Frame&)>& paint,
                       const std::function<void(std::size_t, std::size_t)>& finish) {
    const std::size_t capacity = batch_size(threads);
    std::vector<Frame> frames;  // copies: a rendered frame is valid only during the callback
    std::vector<std::size_t> index;
    std::size_t used = 0;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    const auto flush = [&] {
        arena.execute([&] {
            tbb::parallel_for(std::size_t{0}, used,
                              [&](std::size_t slot) { paint(slot, index[slot], frames[slot]); });
        });
        if (finish)
            for (std::size_t slot = 0; slot < used; ++slot) finish(slot, index[slot]);
        used = 0;
    };
    renderer.render_views(views, [&](std::size_t k, const Frame& frame) {
        throw_if_cancelled();  // Ctrl-C stops at the next picture, as the sweep at the next view
        if (frames.size() <= used) {
            frames.push_back(frame);
            index.push_back(k);
        } else {
            frames[used] = frame;  // copy assignment keeps the slot's storage
            index[used] = k;
        }
        if (++used == capacity) flush();
    });
    if (used > 0) flush();
}

}  // namespace glint::detail
