// atlas.png (private to report/): the atlas of zoom 0 from the six directions of the run's
// orientation (report/orientation.h: front, left, back, right, top, bottom in a patient space,
// the mesh axes otherwise; letters at the panels' edges name what lies there), all at one scale
// framed on the mesh inside a margin that holds those letters, and below them close-ups of the
// largest regions seen face on (their mean normal), each under its own title strip, so a damage
// a few millimetres wide on a whole jaw still shows its colours. No text lies on the surface.
#pragma once

#include "decision/regions.h"
#include "mesh/mesh.h"
#include "render/renderer.h"
#include "report/detail/labels.h"
#include "report/detail/legend.h"
#include "report/detail/surface_paint.h"
#include "report/mirror_pictures.h"
#include "report/orientation.h"
#include "scanner/plan.h"

#include <cstdint>
#include <string>
#include <vector>

namespace glint::detail {

/// Where atlas_overview_png put the surface and its texts, in sheet pixels (the picture above
/// its footer): what a test checks the labels against.
struct OverviewLayout {
    int width = 0;   ///< of the sheet
    int height = 0;  ///< of the sheet, without the footer
    /// width × height, row by row: 1 where a panel or a close-up shows the surface.
    std::vector<std::uint8_t> surface;
    std::vector<PixelBox> letters;   ///< the direction letters at the panels' edges
    std::vector<PixelBox> captions;  ///< the panels' captions and the close-ups' titles
};

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
    /// The surface against its mirror image (glint asymmetry): the plane drawn on every panel
    /// and close-up it crosses (report/detail/symmetry_plane_trace.h), the title and the
    /// close-ups in the finding's words; null: a sweep's atlas.
    const MirrorPictures* mirror = nullptr;
    /// Filled with where things went when not null (tests).
    OverviewLayout* layout = nullptr;
};

/// Close-ups shown, at most (the largest regions).
inline constexpr std::size_t kMaxCloseUps = 4;

/// The picture as PNG bytes, rendered with `renderer` (a renderer of *input.mesh).
/// \throw IoError, DeviceError.
[[nodiscard]] std::string atlas_overview_png(Renderer& renderer, const OverviewInput& input);

}  // namespace glint::detail
