// What each view of a sweep measured, kept for its pictures (issue 26): the per-view PNGs and
// the mosaic show a view's own comparison, not the atlas redrawn from its angle. Filled while
// the sweep runs (a ViewObserver's work, beside report/view_exports.h), read after the decision
// by report/pictures.h.
//
// Compact: per pixel of a grid no larger than the view's picture, the signed depth along the
// view ray and the sweep's metric as 16-bit floats and one status byte (5 bytes). A sweep frame
// larger than the grid is reduced block by block (the mean of the block's compared pixels, the
// status most of the block has). All views together stay within a byte budget: the grid of
// every view is reduced further until they fit, so hundreds of 1024-px views cost at most the
// budget, never 180 full-size float frames.
#pragma once

#include "scanner/compare.h"
#include "scanner/plan.h"

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

namespace glint {

/// What a grid cell of a view shows.
enum class MeasuredStatus : std::uint8_t {
    Nothing = 0,        ///< no surface in either frame, or not compared (a partly covered edge)
    Compared = 1,       ///< both frames cover it: depth and metric are known
    ReferenceOnly = 2,  ///< reference surface with no examined surface behind it
    ExaminedOnly = 3,   ///< examined surface where the reference has none
};

/// One view's measurement on its grid (row-major, top row first, in the sweep camera's image).
struct ViewMeasurement {
    int width = 0;                     ///< grid cells across
    int height = 0;                    ///< grid cells down
    int block = 1;                     ///< sweep pixels per grid cell along each axis
    std::vector<std::uint16_t> depth;  ///< signed depth, mesh units, as half-float bits
    std::vector<std::uint16_t> value;  ///< the sweep's metric, as half-float bits
    std::vector<std::uint8_t> status;  ///< MeasuredStatus per cell
    std::size_t compared = 0;          ///< compared pixels of the full frame (DeviationMap)

    /// The cell's signed depth / metric as float (NaN where not compared).
    [[nodiscard]] float depth_at(std::size_t cell) const;
    [[nodiscard]] float value_at(std::size_t cell) const;
    [[nodiscard]] MeasuredStatus status_at(std::size_t cell) const {
        return static_cast<MeasuredStatus>(status[cell]);
    }
};

/// note: 96 MiB: a default sweep (60 views) keeps its 512-px grids whole (47 MB); 360 views of
/// 1024 px keep grids of about 235 px. Below a run's 600 MiB peak for a 2M-triangle mesh.
inline constexpr std::size_t kMeasurementBudgetBytes = 96u << 20;

/// Grid cells kept per view, at most along each axis: the largest per-view picture
/// (report/pictures.cpp draws them 384-512 px across).
inline constexpr int kMeasurementMaxSize = 512;

/// The store. add() may be called from any thread; the rest after the sweep.
class ViewMeasurements {
  public:
    /// Sized for `plan`'s views (the block of each zoom chosen so that all views fit `budget`).
    explicit ViewMeasurements(const SweepPlan& plan,
                              std::size_t budget_bytes = kMeasurementBudgetBytes);
    ViewMeasurements(const ViewMeasurements&) = delete;
    ViewMeasurements& operator=(const ViewMeasurements&) = delete;

    /// Keeps `deviation` (view.view.index's map; `value` holding the metric). An empty map
    /// (0 x 0: the sweep compared on the GPU) keeps nothing.
    void add(const PlannedView& view, const DeviationMap& deviation);

    /// The view's measurement, or null when none was kept.
    [[nodiscard]] const ViewMeasurement* find(int view_index) const;

    /// Bytes held by the grids.
    [[nodiscard]] std::size_t bytes() const;

  private:
    std::vector<int> block_;  ///< per zoom
    std::vector<ViewMeasurement> views_;
    mutable std::mutex mutex_;
};

}  // namespace glint
