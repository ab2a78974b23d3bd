#include "report/view_measurements.h"

#include "mesh/error.h"

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {

namespace {

std::uint16_t to_half(float v) { return Imath::half(v).bits(); }

float from_half(std::uint16_t bits) {
    Imath::half h;
    h.setBits(bits);
    return static_cast<float>(h);
}

std::size_t cells(int size, int block) {
    const auto n = static_cast<std::size_t>((size + block - 1) / block);
    return n * n;
}

// Bytes of all views with these blocks: 2 + 2 + 1 per cell.
std::size_t total_bytes(const SweepPlan& plan, const std::vector<int>& block) {
    std::size_t sum = 0;
    for (const auto& pv : plan.views) {
        const auto z = static_cast<std::size_t>(pv.view.zoom_index);
        sum += 5 * cells(std::max(pv.view.camera.width, pv.view.camera.height), block[z]);
    }
    return sum;
}

// The status most of a block's pixels have (ties: compared, then reference only).
MeasuredStatus block_status(std::size_t compared, std::size_t reference_only,
                            std::size_t examined_only) {
    if (compared + reference_only + examined_only == 0) return MeasuredStatus::Nothing;
    if (compared >= reference_only && compared >= examined_only) return MeasuredStatus::Compared;
    return reference_only >= examined_only ? MeasuredStatus::ReferenceOnly
                                           : MeasuredStatus::ExaminedOnly;
}

// One grid cell from the block of the map at cell (cx, cy).
void reduce_block(const DeviationMap& d, const std::vector<float>& metric, int block, int cx,
                  int cy, ViewMeasurement& m) {
    std::size_t counts[3] = {0, 0, 0};
    double depth = 0.0, value = 0.0;
    for (int y = cy * block; y < std::min(d.height, (cy + 1) * block); ++y)
        for (int x = cx * block; x < std::min(d.width, (cx + 1) * block); ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(d.width) +
                                  static_cast<std::size_t>(x);
            if (d.silhouette[p] == static_cast<std::uint8_t>(Silhouette::ReferenceOnly)) {
                ++counts[1];
            } else if (d.silhouette[p] == static_cast<std::uint8_t>(Silhouette::ExaminedOnly)) {
                ++counts[2];
            } else if (std::isfinite(d.signed_depth[p])) {
                ++counts[0];
                depth += d.signed_depth[p];
                value += std::isfinite(metric[p]) ? metric[p] : 0.0f;
            }
        }
    const std::size_t c = static_cast<std::size_t>(cy) * static_cast<std::size_t>(m.width) +
                          static_cast<std::size_t>(cx);
    const MeasuredStatus s = block_status(counts[0], counts[1], counts[2]);
    m.status[c] = static_cast<std::uint8_t>(s);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const auto n = static_cast<double>(counts[0]);
    m.depth[c] = to_half(s == MeasuredStatus::Compared ? static_cast<float>(depth / n) : nan);
    m.value[c] = to_half(s == MeasuredStatus::Compared ? static_cast<float>(value / n) : nan);
}

}  // namespace

float ViewMeasurement::depth_at(std::size_t cell) const { return from_half(depth[cell]); }
float ViewMeasurement::value_at(std::size_t cell) const { return from_half(value[cell]); }

ViewMeasurements::ViewMeasurements(const SweepPlan& plan, std::size_t budget_bytes)
    : views_(plan.views.size()) {
    block_.assign(plan.sizes.size(), 1);
    for (std::size_t z = 0; z < plan.sizes.size(); ++z)
        block_[z] = std::max(1, (plan.sizes[z] + kMeasurementMaxSize - 1) / kMeasurementMaxSize);
    // Coarser grids, the zoom with the largest grid first, until every view fits the budget.
    while (total_bytes(plan, block_) > budget_bytes) {
        std::size_t widest = 0;
        for (std::size_t z = 1; z < block_.size(); ++z)
            if (plan.sizes[z] / block_[z] > plan.sizes[widest] / block_[widest]) widest = z;
        if (plan.sizes[widest] / block_[widest] <= 1) break;
        ++block_[widest];
    }
}

void ViewMeasurements::add(const PlannedView& pv, const DeviationMap& d) {
    if (d.width <= 0 || d.height <= 0) return;
    const auto i = static_cast<std::size_t>(pv.view.index);
    const auto z = static_cast<std::size_t>(pv.view.zoom_index);
    GLINT_ASSERT(i < views_.size() && z < block_.size(), "view outside the measured plan");
    const std::size_t n = static_cast<std::size_t>(d.width) * static_cast<std::size_t>(d.height);
    GLINT_ASSERT(d.signed_depth.size() == n && d.silhouette.size() == n,
                 "deviation map of wrong size");
    ViewMeasurement m;
    m.block = block_[z];
    m.width = (d.width + m.block - 1) / m.block;
    m.height = (d.height + m.block - 1) / m.block;
    const std::size_t c = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height);
    m.depth.resize(c);
    m.value.resize(c);
    m.status.resize(c);
    m.compared = d.compared;
    // (the angle is the metric when the map holds no other)
    const std::vector<float>& metric = d.value.size() == n ? d.value : d.angle_deg;
    for (int cy = 0; cy < m.height; ++cy)
        for (int cx = 0; cx < m.width; ++cx) reduce_block(d, metric, m.block, cx, cy, m);
    const std::lock_guard lock(mutex_);
    views_[i] = std::move(m);
}

const ViewMeasurement* ViewMeasurements::find(int view_index) const {
    if (view_index < 0 || static_cast<std::size_t>(view_index) >= views_.size()) return nullptr;
    const ViewMeasurement& m = views_[static_cast<std::size_t>(view_index)];
    return m.width > 0 ? &m : nullptr;
}

std::size_t ViewMeasurements::bytes() const {
    std::size_t sum = 0;
    for (const auto& m : views_) sum += 2 * m.depth.size() + 2 * m.value.size() + m.status.size();
    return sum;
}

}  // namespace glint
