// Pictures rendered and painted in parallel (private to report/): the frames of a run of
// views are rendered one after the other (each in parallel, render/renderer.h), copied into a
// batch, and the batch is painted by every worker at once; then each picture of the batch is
// finished in view order (pasted into a sheet, written). A batch holds at most
// batch_size(threads) frames, so memory does not grow with the number of views.
#pragma once

#include "render/frame.h"
#include "render/renderer.h"
#include "render/view.h"

#include <cstddef>
#include <functional>
#include <span>

namespace glint::detail {

/// Frames per batch for `threads` workers: twice the workers (so one slow picture does not
/// leave the others idle), at least 2, at most 16.
[[nodiscard]] std::size_t batch_size(int threads);

/// Renders `views` with `renderer`; for each view k, paint(slot, k, frame) runs on a worker
/// (concurrently with other slots of the batch; slot < batch_size(threads)), then
/// finish(slot, k) on the calling thread, in view order, once its batch is painted. Checks for
/// cancellation between views. Exceptions from either callback stop the run and propagate.
/// `threads`: 0 = the machine's.
void render_in_batches(
    Renderer& renderer, std::span<const View> views, int threads,
    const std::function<void(std::size_t slot, std::size_t k, const Frame& frame)>& paint,
    const std::function<void(std::size_t slot, std::size_t k)>& finish = {});

}  // namespace glint::detail
