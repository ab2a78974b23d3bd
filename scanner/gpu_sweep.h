// The sweep's GPU path: compare and back-projection on the device (render/gpu_atlas.h), so that
// only the per-vertex totals (once) and a few numbers per view cross the bus.
//
//   plan ─▶ GpuAtlas::run (per view: render both meshes, compare, scatter, gather, on the device)
//        ─▶ per-view summaries ─▶ ViewSummary, observer (no frames)
//        ─▶ read_totals ─▶ ZoomAtlas per zoom (as AtlasAccumulator::finish) ─▶ coverage
//
// It yields the SweepResult the read-back path yields, within render/gpu_atlas.h's tolerances
// (tests/scanner/gpu_sweep_test.cpp measures them against that path on lavapipe).
#pragma once

#include "mesh/mesh.h"
#include "render/renderer.h"
#include "scanner/plan.h"
#include "scanner/sweep.h"

namespace glint {

/// Runs the sweep's views on the GPU when options.accumulate allows it and the renderers'
/// device can (GpuAtlas::supported), filling result's zooms, views, on_gpu and timings (not
/// total_seconds), and returns true; returns false (with result.accumulation_note saying why
/// when accumulate is Auto) for the caller to run the read-back path.
/// \throw DeviceError accumulate = Gpu and the GPU path cannot run; InputError as run_sweep
/// (no view overlaps); whatever the observer throws.
bool run_sweep_on_gpu(const Mesh& reference, Renderer& reference_renderer,
                      Renderer& examined_renderer, const SweepPlan& plan,
                      const SweepOptions& options, const ViewObserver& observer,
                      SweepResult& result);

}  // namespace glint
