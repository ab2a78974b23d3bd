#include "report/detail/atlas_overview.h"

#include "mesh/error.h"
#include "render/frame.h"
#include "render/view.h"
#include "report/detail/footer.h"
#include "report/detail/labels.h"
#include "report/detail/scale_bar.h"
#include "report/detail/symmetry_plane_trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace glint::detail {

namespace {

constexpr int kPanel = 320;    // px: one direction
constexpr int kCloseUp = 240;  // px: one close-up (four fill the width of three directions)

// The six panels, in the orientation's display frame (report/orientation.h): from the front,
// turning about up, then from up and from below.
struct Panel {
    double azimuth;
    double elevation;
};
constexpr Panel kPanels[] = {{0, 0}, {90, 0}, {180, 0}, {270, 0}, {0, 90}, {0, -90}};

// A camera looking from `direction` (unit, mesh coordinates) with the orientation's up up.
ViewSpec panel_spec(const Orientation& o, const Vec3d& direction, int size) {
    return ViewSpec{
        .azimuth_deg = std::atan2(direction.y(), direction.x()) * 180.0 / std::numbers::pi,
        .elevation_deg = std::asin(std::clamp(direction.z(), -1.0, 1.0)) * 180.0 / std::numbers::pi,
        .width = size,
        .height = size,
        .up = up_hint(o, direction)};
}

constexpr int kCaptionFont = 13;

// A line of text on a panel, in the panel's pixels.
struct PanelText {
    std::string text;
    int x = 0;
    int y = 0;  ///< baseline
    TextAlign align = TextAlign::Left;
};

// The direction names at the panel's edges, as a radiologist's viewer puts them: what lies
// up, left and right in the picture.
std::vector<PanelText> edge_letters(int size, const Orientation& o, const View& v) {
    const auto& axes = v.camera.world_from_camera.linear();
    return {{with_minus_sign(o.letter(axes.col(1))), size / 2, 16, TextAlign::Center},
            {with_minus_sign(o.letter(-axes.col(0))), 6, size / 2 + 5, TextAlign::Left},
            {with_minus_sign(o.letter(axes.col(0))), size - 6, size / 2 + 5, TextAlign::Right}};
}

// The margin each panel keeps free of the surface, pixels: left and right for the letters
// there, top and bottom for the letter above and the caption below (the same both ways, as
// the surface is centred).
struct Margin {
    int x = 0;
    int y = 0;
};

Margin text_margin(const std::vector<View>& views, const Orientation& o) {
    // note: 3 px between a text's box and the surface, so the two never touch.
    constexpr int kGap = 3;
    const PixelBox caption = text_box("from", kCaptionFont, 8, kPanel - 8);
    Margin m{.x = 0, .y = kPanel - caption.y0 + kGap};
    for (const View& v : views)
        for (const PanelText& t : edge_letters(kPanel, o, v)) {
            const PixelBox b = text_box(t.text, kCaptionFont, t.x, t.y, t.align);
            if (t.align == TextAlign::Center) {  // the letter above
                m.y = std::max(m.y, b.y1 + kGap);
            } else if (t.align == TextAlign::Left) {
                m.x = std::max(m.x, b.x1 + kGap);
            } else {
                m.x = std::max(m.x, kPanel - b.x0 + kGap);
            }
        }
    return m;
}

// The six views at one scale: the bounding box's corners, seen from each direction, fit inside
// the panels less their margins (a sphere around an elongated jaw would leave most of each
// panel empty). The corners enclose the surface, so it keeps off the letters and captions.
std::vector<View> direction_views(const Mesh& mesh, const Orientation& o) {
    const FramingSphere sphere = framing_sphere(mesh);
    const Bounds b = bounds(mesh);
    std::vector<View> views;
    for (const auto& p : kPanels)
        views.push_back(
            make_view(sphere, panel_spec(o, panel_direction(o, p.azimuth, p.elevation), kPanel)));
    const Margin m = text_margin(views, o);
    const double room_x = 0.5 * kPanel - m.x, room_y = 0.5 * kPanel - m.y;
    GLINT_ASSERT(room_x > 0 && room_y > 0, "atlas panel margins leave no room for the surface");
    double footprint = 1e-12;
    for (const View& v : views) {
        const Rigid camera_from_world = v.camera.world_from_camera.inverse();
        for (int c = 0; c < 8; ++c) {
            const Vec3d corner((c & 1 ? b.max : b.min).x(), (c & 2 ? b.max : b.min).y(),
                               (c & 4 ? b.max : b.min).z());
            const Vec3d q = camera_from_world * corner;
            footprint = std::max({footprint, std::abs(q.x()) / room_x, std::abs(q.y()) / room_y});
        }
    }
    views.clear();
    for (const auto& p : kPanels) {
        ViewSpec spec = panel_spec(o, panel_direction(o, p.azimuth, p.elevation), kPanel);
        spec.zoom = ZoomKind::Footprint;
        spec.zoom_value = footprint;
        views.push_back(make_view(sphere, spec));
    }
    return views;
}

// "from anterior (az 270°, el +0°)"; the panel from up also says "(top)" when up is stated and
// the direction's name is an axis ("+z"): "superior" says it already, and the longer caption
// was cut before the scale bar (issue 51).
std::string panel_caption(const Orientation& o, const View& v) {
    const Vec3d from = v.camera.world_from_camera.linear().col(2);
    const std::string name = o.name(from);
    const bool axis = !name.empty() && (name[0] == '+' || name[0] == '-');
    const bool top = axis && o.up_known && from.dot(o.up) > 0.999;
    const bool bottom = axis && o.up_known && from.dot(o.up) < -0.999;
    char label[120];
    std::snprintf(label, sizeof label, "from %s%s (az %s, el %s)", name.c_str(),
                  top      ? " (top)"
                  : bottom ? " (bottom)"
                           : "",
                  format_degrees(v.azimuth_deg).c_str(),
                  format_degrees(v.elevation_deg, true).c_str());
    return with_minus_sign(label);
}

// The direction a region faces: the mean of its vertices' normals; when they cancel out (a
// region around a thin part), its best view's direction.
Vec3d facing(const Mesh& mesh, const SurfaceFields& fields, const Region& r,
             const SweepPlan& plan) {
    // The direction that sees the most of it face on and unoccluded, when the analysis chose
    // one (analysis/region_views.h).
    if (r.view_direction.norm() > 0.5) return r.view_direction.normalized();
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
// area) across, at most the mesh's radius across but never less than the region's own reach
// (a resected side of a jaw, 7890 mm², would be framed 400 mm across in a 165 mm jaw), at
// least 6 % of the mesh's radius. The framing sphere encloses the whole mesh so nothing in
// front of or behind the region is clipped away.
View close_up_view(const Mesh& mesh, const SurfaceFields& fields, const FramingSphere& whole,
                   const Region& r, const SweepPlan& plan, const Orientation& o) {
    const double radius = whole.radius + (r.centroid - whole.center).norm();
    double reach = 0.0;  // the farthest of its vertices from its centroid
    for (std::size_t v = 0; v < fields.region.size() && v < mesh.positions.size(); ++v)
        if (fields.region[v] == r.id)
            reach = std::max(reach, (mesh.positions[v].cast<double>() - r.centroid).norm());
    const double disc = 4.0 * std::sqrt(std::max(r.area, 0.0) / std::numbers::pi);
    const double half = std::max({std::min(disc, whole.radius), 1.1 * reach, 0.06 * whole.radius});
    ViewSpec spec = panel_spec(o, facing(mesh, fields, r, plan), kCloseUp);
    spec.zoom = ZoomKind::Footprint;
    spec.zoom_value = 2.0 * half / kCloseUp;
    return make_view(FramingSphere{r.centroid, radius}, spec);
}

// Height of the strip above a close-up that holds its title (pixels): a close-up is filled
// with surface, so its title cannot lie on the picture.
constexpr int kTitleStrip = 22;

PixelBox moved(PixelBox b, int dx, int dy) { return {b.x0 + dx, b.y0 + dy, b.x1 + dx, b.y1 + dy}; }

// Marks in the layout the sheet pixels where a frame pasted at (x, y) shows the surface.
void record_surface(OverviewLayout* layout, const Frame& frame, int x, int y) {
    if (layout == nullptr) return;
    for (int r = 0; r < frame.height; ++r)
        for (int c = 0; c < frame.width; ++c)
            if (frame.primitive_id[static_cast<std::size_t>(r * frame.width + c)] != kNoPrimitive)
                layout->surface[static_cast<std::size_t>((y + r) * layout->width + x + c)] = 1;
}

// A painted panel pasted at (x, y) with its caption at the bottom left (the six directions,
// in the margin their framing keeps free) or in the strip above it (close-ups), shortened to
// fit; its scale bar at the bottom right; `letters` at its edges; and the region numbers
// placed off all of them.
void place(Canvas& sheet, int x, int y, const PaintedSurface& painted, const View& view,
           const std::string& caption, const std::string& unit, bool caption_below,
           const std::vector<PanelText>& letters, OverviewLayout* layout) {
    const int w = painted.image.width(), h = painted.image.height();
    sheet.paste(painted.image, x, y);
    const PixelBox bar = view_scale_bar_box(view, unit);
    // the caption stops short of the scale bar when both share the bottom edge
    const int caption_room = (caption_below ? bar.x0 : w) - 16;
    const PanelText title{fit_text(caption, kCaptionFont, caption_room), 8,
                          caption_below ? h - 8 : 16 - kTitleStrip, TextAlign::Left};
    std::vector<PixelBox> reserved{bar};
    for (const auto& t : letters)
        reserved.push_back(text_box(t.text, kCaptionFont, t.x, t.y, t.align));
    const PixelBox title_box = text_box(title.text, kCaptionFont, title.x, title.y, title.align);
    if (caption_below) reserved.push_back(title_box);
    draw_region_numbers(sheet, x, y, w, h, painted.anchors, 13, 20, reserved);
    for (const auto& t : letters)
        draw_text(sheet, x + t.x, y + t.y, t.text, kCaptionFont, kDimText, t.align, 2);
    draw_text(sheet, x + title.x, y + title.y, title.text, kCaptionFont, kText, title.align, 2);
    draw_view_scale_bar(sheet, x, y, view, unit);
    if (layout == nullptr) return;
    for (std::size_t i = 0; i < letters.size(); ++i)
        layout->letters.push_back(moved(reserved[i + 1], x, y));
    layout->captions.push_back(moved(title_box, x, y));
}

// The panel painted, with the symmetry plane drawn on it (a mirror comparison) clear of the
// texts place() puts there (`letters`, the caption below or none); the label goes on the
// sheet once the panel is placed.
PaintedSurface painted_panel(const OverviewInput& in, const Frame& frame, const View& view,
                             const std::vector<PanelText>& letters, const std::string& caption,
                             std::optional<PlaneLabel>& label) {
    PaintedSurface painted = paint_surface(*in.mesh, frame, view, *in.fields, {.limit = in.limit});
    if (in.mirror == nullptr) return painted;
    std::vector<PixelBox> clear{view_scale_bar_box(view, in.unit)};
    for (const auto& t : letters)
        clear.push_back(text_box(t.text, kCaptionFont, t.x, t.y, t.align));
    if (!caption.empty())
        clear.push_back(text_box(caption, kCaptionFont, 8, frame.height - 8, TextAlign::Left));
    label = draw_symmetry_plane(painted.image, frame, view, *in.mesh, in.fields->region, *in.mirror,
                                clear);
    return painted;
}

}  // namespace

std::string atlas_overview_png(Renderer& renderer, const OverviewInput& in) {
    const Orientation o = in.orientation != nullptr ? *in.orientation : Orientation{};
    const std::vector<View> views = direction_views(*in.mesh, o);
    std::vector<View> close;
    const FramingSphere whole = framing_sphere(*in.mesh);
    for (std::size_t i = 0; i < in.regions->size() && close.size() < kMaxCloseUps; ++i)
        close.push_back(close_up_view(*in.mesh, *in.fields, whole, (*in.regions)[i], *in.plan, o));
    const int close_h = close.empty() ? 0 : 6 + kTitleStrip + kCloseUp;
    char title[300];
    std::snprintf(title, sizeof title,
                  "%s atlas of %s (zoom 0): %s, %zu region(s), coverage %.0f %%",
                  in.mirror ? "asymmetry" : "damage", in.name.c_str(),
                  in.mirror ? "this side − mirrored other side" : "signed shape change",
                  in.regions->size(), 100.0 * in.coverage);
    // a mirror comparison's atlas names the plane's line in its legend, the plane in its footer
    LegendContent legend = *in.legend;
    legend.plane_line = in.mirror != nullptr;
    std::vector<std::string> footer = in.footer;
    if (in.mirror != nullptr && !footer.empty())
        footer.push_back(symmetry_plane_footer(*in.mirror, in.unit));
    Canvas sheet = framed_sheet(3 * kPanel, 2 * kPanel + close_h, title, legend);
    if (in.layout != nullptr) {
        *in.layout = OverviewLayout{.width = sheet.width(), .height = sheet.height()};
        in.layout->surface.assign(static_cast<std::size_t>(in.layout->width * in.layout->height),
                                  0);
    }
    renderer.render_views(views, [&](std::size_t k, const Frame& frame) {
        const int x = static_cast<int>(k % 3) * kPanel;
        const int y = kTitleHeight + static_cast<int>(k / 3) * kPanel;
        std::optional<PlaneLabel> label;
        const auto letters = edge_letters(kPanel, o, views[k]);
        const std::string caption = panel_caption(o, views[k]);
        place(sheet, x, y, painted_panel(in, frame, views[k], letters, caption, label), views[k],
              caption, in.unit, true, letters, in.layout);
        draw_plane_label(sheet, x, y, label);
        record_surface(in.layout, frame, x, y);
    });
    const int y0 = kTitleHeight + 2 * kPanel + 6 + kTitleStrip;  // the close-ups' pictures
    renderer.render_views(close, [&](std::size_t k, const Frame& frame) {
        const Region& r = (*in.regions)[k];
        char label[120];
        // No depth for missing surface (the examined scan has none there) nor for surface gone
        // (its height above the rim is no depth of damage; the legend and report give it).
        if (r.kind == RegionKind::MissingSurface || r.is_hole_loss())
            std::snprintf(label, sizeof label, "close-up %d: %s", r.id,
                          region_kind_name(r, in.mirror != nullptr).c_str());
        else
            std::snprintf(label, sizeof label, "close-up %d: %s %s %s", r.id,
                          region_kind_name(r, in.mirror != nullptr).c_str(),
                          format_number(r.peak_depth, true).c_str(), in.unit.c_str());
        const int x = static_cast<int>(k) * kCloseUp;
        std::optional<PlaneLabel> plane_label;
        place(sheet, x, y0, painted_panel(in, frame, close[k], {}, "", plane_label), close[k],
              label, in.unit, false, {}, in.layout);
        draw_plane_label(sheet, x, y0, plane_label);
        record_surface(in.layout, frame, x, y0);
        draw_box(sheet, x, y0, x + kCloseUp - 1, y0 + kCloseUp - 1, kDimText, false);
    });
    return encode_png(footer.empty() ? sheet : with_footer(sheet, footer));
}

}  // namespace glint::detail
