#include "report/detail/atlas_overview.h"

#include "render/view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace glint::detail {

using OIIO::ImageBuf;
namespace IBA = OIIO::ImageBufAlgo;

namespace {

constexpr int kPanel = 320;    // px: one direction
constexpr int kCloseUp = 240;  // px: one close-up (four fill the width of three directions)

struct Direction {
    double azimuth;
    double elevation;
    const char* name;
};
// note: mesh axes, not anatomy: glint cannot know how a scan is oriented.
constexpr Direction kDirections[] = {{0, 0, "from +x"},        {90, 0, "from +y"},
                                     {180, 0, "from -x"},      {270, 0, "from -y"},
                                     {0, 90, "from +z (top)"}, {0, -90, "from -z (bottom)"}};

// The six views at one scale: the largest half extent of the bounding box's corners across
// them (a sphere around an elongated jaw would leave most of each panel empty).
std::vector<View> direction_views(const Mesh& mesh) {
    const FramingSphere sphere = framing_sphere(mesh);
    const Bounds b = bounds(mesh);
    double half = 0.0;
    for (const auto& d : kDirections) {
        const View v = make_view(sphere, ViewSpec{.azimuth_deg = d.azimuth,
                                                  .elevation_deg = d.elevation,
                                                  .width = kPanel,
                                                  .height = kPanel});
        const Rigid camera_from_world = v.camera.world_from_camera.inverse();
        for (int c = 0; c < 8; ++c) {
            const Vec3d corner((c & 1 ? b.max : b.min).x(), (c & 2 ? b.max : b.min).y(),
                               (c & 4 ? b.max : b.min).z());
            const Vec3d q = camera_from_world * corner;
            half = std::max({half, std::abs(q.x()), std::abs(q.y())});
        }
    }
    // note: 4 % margin, so the silhouette never touches the panel's edge.
    const double footprint = 2.0 * 1.04 * std::max(half, 1e-12) / kPanel;
    std::vector<View> views;
    for (const auto& d : kDirections)
        views.push_back(make_view(sphere, ViewSpec{.azimuth_deg = d.azimuth,
                                                   .elevation_deg = d.elevation,
                                                   .zoom = ZoomKind::Footprint,
                                                   .zoom_value = footprint,
                                                   .width = kPanel,
                                                   .height = kPanel}));
    return views;
}

// The direction a region faces: the mean of its vertices' normals; when they cancel out (a
// region around a thin part), its best view's direction.
Vec3d facing(const Mesh& mesh, const SurfaceFields& fields, const Region& r,
             const SweepPlan& plan) {
    Vec3d sum = Vec3d::Zero();
    for (std::size_t v = 0; v < fields.region.size() && v < mesh.normals.size(); ++v)
        if (fields.region[v] == r.id) sum += mesh.normals[v].cast<double>();
    // note: 0.2 of a unit normal per vertex: below it the normals mostly cancel.
    if (sum.norm() > 0.2 * static_cast<double>(r.vertex_count) && sum.norm() > 0)
        return sum.normalized();
    if (r.best_view >= 0 && static_cast<std::size_t>(r.best_view) < plan.views.size()) {
        const View& v = plan.views[static_cast<std::size_t>(r.best_view)].view;
        return direction_from_az_el(v.azimuth_deg, v.elevation_deg);
    }
    return Vec3d::UnitX();
}

// A region seen face on, framed on its centroid: four times its radius (as a disc of its
// area) across, at least 6 % of the mesh's radius. The framing sphere encloses the whole mesh
// so nothing in front of or behind the region is clipped away.
View close_up_view(const Mesh& mesh, const SurfaceFields& fields, const FramingSphere& whole,
                   const Region& r, const SweepPlan& plan) {
    const Vec3d d = facing(mesh, fields, r, plan);
    const double az = std::atan2(d.y(), d.x()) * 180.0 / std::numbers::pi;
    const double el = std::asin(std::clamp(d.z(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    const double radius = whole.radius + (r.centroid - whole.center).norm();
    const double half =
        std::max(4.0 * std::sqrt(std::max(r.area, 0.0) / std::numbers::pi), 0.06 * whole.radius);
    return make_view(FramingSphere{r.centroid, radius},
                     ViewSpec{.azimuth_deg = az,
                              .elevation_deg = el,
                              .zoom = ZoomKind::Footprint,
                              .zoom_value = 2.0 * half / kCloseUp,
                              .width = kCloseUp,
                              .height = kCloseUp});
}

void place(ImageBuf& sheet, int x, int y, const PaintedSurface& painted, const std::string& label,
           int min_pixels) {
    IBA::paste(sheet, x, y, 0, 0, painted.image);
    draw_region_numbers(sheet, x, y, painted.image.spec().width, painted.anchors, 13,
                        static_cast<std::size_t>(min_pixels));
    draw_text(sheet, x + 8, y + 18, label, 13, kText, IBA::TextAlignX::Left, 2);
}

}  // namespace

std::string atlas_overview_png(Renderer& renderer, const OverviewInput& in) {
    const std::vector<View> views = direction_views(*in.mesh);
    std::vector<View> close;
    const FramingSphere whole = framing_sphere(*in.mesh);
    for (std::size_t i = 0; i < in.regions->size() && close.size() < kMaxCloseUps; ++i)
        close.push_back(close_up_view(*in.mesh, *in.fields, whole, (*in.regions)[i], *in.plan));
    const int close_h = close.empty() ? 0 : kCloseUp + 6;
    char title[300];
    std::snprintf(
        title, sizeof title,
        "damage atlas of %s (zoom 0): signed shape change, %zu region(s), coverage %.0f %%",
        in.name.c_str(), in.regions->size(), 100.0 * in.coverage);
    ImageBuf sheet = framed_sheet(3 * kPanel, 2 * kPanel + close_h, title, *in.legend);
    const PaintStyle style{.limit = in.limit};
    renderer.render_views(views, [&](std::size_t k, const Frame& frame) {
        char label[80];
        std::snprintf(label, sizeof label, "%s (az %.0f, el %+.0f deg)", kDirections[k].name,
                      kDirections[k].azimuth, kDirections[k].elevation);
        place(sheet, static_cast<int>(k % 3) * kPanel,
              kTitleHeight + static_cast<int>(k / 3) * kPanel,
              paint_surface(*in.mesh, frame, views[k], *in.fields, style), label, 20);
    });
    const int y0 = kTitleHeight + 2 * kPanel + 6;
    renderer.render_views(close, [&](std::size_t k, const Frame& frame) {
        const Region& r = (*in.regions)[k];
        char label[120];
        std::snprintf(label, sizeof label, "close-up %d: %s %+.3g %s", r.id,
                      to_string(r.kind).c_str(), r.peak_depth, in.unit.c_str());
        const int x = static_cast<int>(k) * kCloseUp;
        place(sheet, x, y0, paint_surface(*in.mesh, frame, close[k], *in.fields, style), label, 20);
        draw_box(sheet, x, y0, x + kCloseUp - 1, y0 + kCloseUp - 1, kDimText, false);
    });
    return encode_png(sheet);
}

}  // namespace glint::detail
