// atlas.png (private to report/): the atlas of zoom 0 from the six directions of the run's
// orientation (report/orientation.h: front, left, back, right, top, bottom in a patient space,
// the mesh axes otherwise; letters at the panels' edges name what lies there), all at one scale framed tightly on the mesh, and below them close-ups of the largest
// regions seen face on (their mean normal), so a damage a few millimetres wide on a whole jaw
// still shows its colours.
#pragma once

#include "decision/regions.h"
#include "mesh/mesh.h"
#include "render/renderer.h"
#include "report/detail/legend.h"
#include "report/detail/surface_paint.h"
#include "report/orientation.h"
#include "scanner/plan.h"

#include <string>
#include <vector>

namespace glint::detail {

struct OverviewInput {
    const Mesh* mesh = nullptr;
    const SurfaceFields* fields = nullptr;
    const LegendContent* legend = nullptr;
    double limit = 1.0;  ///< colour range ±limit
    const std::vector<Region>* regions = nullptr;
    const SweepPlan* plan = nullptr;  ///< for the regions' best views
    double coverage = 0.0;            ///< share of the surface seen
    std::string name;                 ///< of the reference, for the title
    std::string unit;
    /// Which way is up and what directions are called; null: +z up, axes named by axis.
    const Orientation* orientation = nullptr;
    /// Lines below the picture (report/detail/footer.h); none: no footer.
    std::vector<std::string> footer;
};

/// Close-ups shown, at most (the largest regions).
inline constexpr std::size_t kMaxCloseUps = 4;

/// The picture as PNG bytes, rendered with `renderer` (a renderer of *input.mesh).
/// \throw IoError, DeviceError.
[[nodiscard]] std::string atlas_overview_png(Renderer& renderer, const OverviewInput& input);

}  // namespace glint::detail
