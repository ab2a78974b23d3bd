#include "report/detail/surface_paint.h"

#include "mesh/error.h"
#include "mesh/mesh.h"
#include "render/shade.h"
#include "report/view_measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace glint::detail {

namespace {

// What one pixel shows of the per-vertex fields.
struct PixelFields {
    std::vector<float> distance;
    std::vector<std::int32_t> region;  // 0 also for uncovered pixels
    std::vector<std::uint8_t> seen;
};

// Barycentric weights of point p in the 2-D triangle (a, b, c), clamped to the triangle
// (a supersampled pixel's centre may lie just outside the triangle its centre sub-sample hit)
// and renormalised; equal weights for a degenerate projection (a triangle seen edge-on).
std::array<double, 3> barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                  const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const Eigen::Vector2d v0 = b - a, v1 = c - a, v2 = p - a;
    const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
    const double d20 = v2.dot(v0), d21 = v2.dot(v1);
    const double denom = d00 * d11 - d01 * d01;
    // note: 1e-12 px⁴: a triangle whose projection has (practically) no area.
    if (!(std::abs(denom) > 1e-12)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
    const double v = (d11 * d20 - d01 * d21) / denom;
    const double w = (d00 * d21 - d01 * d20) / denom;
    std::array<double, 3> bw{std::max(0.0, 1.0 - v - w), std::max(0.0, v), std::max(0.0, w)};
    const double sum = bw[0] + bw[1] + bw[2];
    if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
    for (double& x : bw) x /= sum;
    return bw;
}

PixelFields sample_fields(const Mesh& mesh, const Frame& frame, const View& view,
                          const SurfaceFields& fields) {
    const std::size_t n = frame.pixel_count();
    PixelFields out{std::vector<float>(n, kNaN), std::vector<std::int32_t>(n, 0),
                    std::vector<std::uint8_t>(n, 0)};
    const Projector project(view.camera);
    std::uint32_t cached = kNoPrimitive;
    std::array<Eigen::Vector2d, 3> corner;
    // The ray caster's own weights when the frame has them (pictures render at s = 1).
    const bool hits = frame.barycentric.size() == 2 * n;
    for (std::size_t p = 0; p < n; ++p) {
        const std::uint32_t t = frame.primitive_id[p];
        if (!frame.is_covered(p) || t == kNoPrimitive || t >= mesh.triangle_count()) continue;
        const auto& tri = mesh.triangles[t];
        std::array<double, 3> w;
        if (hits) {
            const double u = frame.barycentric[2 * p], v = frame.barycentric[2 * p + 1];
            w = {std::max(0.0, 1.0 - u - v), u, v};
        } else {
            if (t != cached) {
                for (int k = 0; k < 3; ++k)
                    corner[k] = project(mesh.positions[tri[k]].cast<double>()).head<2>();
                cached = t;
            }
            const Eigen::Vector2d centre(
                static_cast<double>(p % static_cast<std::size_t>(frame.width)) + 0.5,
                static_cast<double>(p / static_cast<std::size_t>(frame.width)) + 0.5);
            w = barycentric(centre, corner[0], corner[1], corner[2]);
        }
        const int nearest = static_cast<int>(std::max_element(w.begin(), w.end()) - w.begin());
        double d = 0.0;
        bool known = true;
        for (int k = 0; k < 3; ++k) {
            const float dk = fields.distance[tri[k]];
            if (std::isnan(dk)) known = false;
            d += w[k] * dk;
        }
        const std::uint32_t v = tri[nearest];
        out.distance[p] = known ? static_cast<float>(d) : fields.distance[v];
        out.region[p] = fields.region[v];
        out.seen[p] = fields.seen[v];
    }
    return out;
}

// Contour pixels: a covered pixel whose region differs from a 4-neighbour's (an uncovered
// neighbour counts as no region). Width 1 marks the region side only, width 2 both sides.
std::vector<std::uint8_t> contour(const Frame& frame, const std::vector<std::int32_t>& region,
                                  int width) {
    const int w = frame.width, h = frame.height;
    std::vector<std::uint8_t> edge(frame.pixel_count(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                  static_cast<std::size_t>(x);
            if (!frame.is_covered(p)) continue;
            const std::int32_t r = region[p];
            const int nx[4] = {x - 1, x + 1, x, x};
            const int ny[4] = {y, y, y - 1, y + 1};
            for (int k = 0; k < 4; ++k) {
                const bool inside = nx[k] >= 0 && nx[k] < w && ny[k] >= 0 && ny[k] < h;
                const std::int32_t q =
                    inside ? region[static_cast<std::size_t>(ny[k]) * static_cast<std::size_t>(w) +
                                    static_cast<std::size_t>(nx[k])]
                           : 0;
                if (q != r && (r != 0 || (width >= 2 && q != 0))) {
                    edge[p] = 1;
                    break;
                }
            }
        }
    return edge;
}

// Per region visible: its pixel count and the region pixel nearest the pixel centroid (the
// centroid itself may lie outside a curved region).
std::vector<RegionAnchor> anchors_of(const Frame& frame, const std::vector<std::int32_t>& region) {
    std::int32_t max_id = 0;
    for (std::int32_t r : region) max_id = std::max(max_id, r);
    std::vector<double> sx(static_cast<std::size_t>(max_id) + 1, 0.0), sy(sx.size(), 0.0);
    std::vector<std::size_t> count(sx.size(), 0);
    const auto w = static_cast<std::size_t>(frame.width);
    for (std::size_t p = 0; p < region.size(); ++p) {
        if (region[p] <= 0) continue;
        const auto r = static_cast<std::size_t>(region[p]);
        sx[r] += static_cast<double>(p % w);
        sy[r] += static_cast<double>(p / w);
        ++count[r];
    }
    std::vector<RegionAnchor> anchors(sx.size());
    for (auto& a : anchors) {
        a.min_x = a.min_y = std::numeric_limits<int>::max();
        a.max_x = a.max_y = -1;
    }
    std::vector<double> best(sx.size(), std::numeric_limits<double>::max());
    for (std::size_t p = 0; p < region.size(); ++p) {
        if (region[p] <= 0) continue;
        const auto r = static_cast<std::size_t>(region[p]);
        const int x = static_cast<int>(p % w), y = static_cast<int>(p / w);
        auto& a = anchors[r];
        a.min_x = std::min(a.min_x, x);
        a.max_x = std::max(a.max_x, x);
        a.min_y = std::min(a.min_y, y);
        a.max_y = std::max(a.max_y, y);
        const double dx = x - sx[r] / static_cast<double>(count[r]);
        const double dy = y - sy[r] / static_cast<double>(count[r]);
        if (dx * dx + dy * dy < best[r]) {
            best[r] = dx * dx + dy * dy;
            a.id = static_cast<std::int32_t>(r);
            a.x = x;
            a.y = y;
            a.pixels = count[r];
        }
    }
    std::erase_if(anchors, [](const RegionAnchor& a) { return a.pixels == 0; });
    return anchors;
}

// Hatching: stripes 2 px wide every `period` px, rising (up) or falling diagonals.
bool on_stripe(std::size_t p, std::size_t width, int hatch_period, bool rising) {
    const auto period = static_cast<std::size_t>(std::max(2, hatch_period));
    const std::size_t x = p % width, y = p / width;
    return rising ? (x + y) % period < 2 : (x + period * width - y % (period * width)) % period < 2;
}

// A covered pixel's colour from the per-vertex fields: the distance, or hatched unseen / not
// compared.
Rgb vertex_colour(const PixelFields& px, const Frame& frame, std::size_t p,
                  const PaintStyle& style) {
    const auto w = static_cast<std::size_t>(frame.width);
    if (!px.seen[p]) return on_stripe(p, w, style.hatch_period, true) ? kUnseenStripe : kUnseen;
    if (px.seen[p] == 2)
        return on_stripe(p, w, style.hatch_period, false) ? kNotComparedStripe : kNotCompared;
    return DivergingTable::get()(px.distance[p], style.limit);
}

// A covered pixel's colour from what the view measured: the signed depth (paler within the
// floor), hatched violet with no examined surface behind, hatched as not compared otherwise,
// and where the decision compares nothing (decision/comparison.h: an open border of either
// surface, or surface the examined scan never reached: what the view sees there is another
// part of the examined surface behind the cut, not a loss).
Rgb measured_colour(const MeasuredPixels& m, const PixelFields& px, const Frame& frame,
                    std::size_t p, const PaintStyle& style) {
    const auto w = static_cast<std::size_t>(frame.width);
    const auto status = static_cast<MeasuredStatus>(m.status[p]);
    if (px.seen[p] == 2)
        return on_stripe(p, w, style.hatch_period, false) ? kNotComparedStripe : kNotCompared;
    if (status == MeasuredStatus::ReferenceOnly)
        return on_stripe(p, w, style.hatch_period, true) ? kNothingBehindStripe : kNothingBehind;
    if (status != MeasuredStatus::Compared || std::isnan(m.depth[p]))
        return on_stripe(p, w, style.hatch_period, false) ? kNotComparedStripe : kNotCompared;
    const DivergingTable& colours = DivergingTable::get();
    Rgb c = colours(m.depth[p], style.limit);
    if (!m.beyond[p]) {
        const Rgb white = colours(0.0f, style.limit);
        for (int k = 0; k < 3; ++k) c[k] += kWithinFloorPale * (white[k] - c[k]);
    }
    return c;
}

}  // namespace

Rgb back_face_colour() {
    const Rgb c = DivergingTable::get()(0.0f, 1.0);
    return {c[0] * kAmbientShade, c[1] * kAmbientShade, c[2] * kAmbientShade};
}

PaintedSurface paint_surface(const Mesh& mesh, const Frame& frame, const View& view,
                             const SurfaceFields& fields, const PaintStyle& style) {
    const std::size_t nv = mesh.vertex_count();
    GLINT_ASSERT(
        fields.distance.size() == nv && fields.region.size() == nv && fields.seen.size() == nv,
        "paint_surface: fields are not sized as the mesh");
    const std::size_t n = frame.pixel_count();
    GLINT_ASSERT(!style.measured ||
                     (style.measured->depth.size() == n && style.measured->status.size() == n &&
                      style.measured->beyond.size() == n),
                 "paint_surface: measured pixels are not sized as the frame");
    const PixelFields px = sample_fields(mesh, frame, view, fields);
    std::vector<std::uint8_t> rgb(3 * n);
    const std::vector<std::uint8_t> edge = contour(frame, px.region, style.outline_width);
    const Vec3f light = ShadeOptions{}.light_in_camera.normalized().cast<float>();
    for (std::size_t p = 0; p < n; ++p) {
        std::uint8_t* c = &rgb[3 * p];
        const float cover = std::clamp(frame.coverage[p], 0.0f, 1.0f);
        if (cover <= 0.0f) {
            // Examined surface outside the reference's outline: all a view sees of it.
            const bool examined_only =
                style.measured && style.measured->status[p] ==
                                      static_cast<std::uint8_t>(MeasuredStatus::ExaminedOnly);
            const Rgb& bg = examined_only ? kExaminedOnly : style.background;
            for (int k = 0; k < 3; ++k) c[k] = to_byte(bg[k]);
            continue;
        }
        Rgb base = style.measured ? measured_colour(*style.measured, px, frame, p, style)
                                  : vertex_colour(px, frame, p, style);
        if (edge[p]) base = kOutline;
        // Lambert with an ambient part: the form stays visible where the light grazes.
        const float lambert = std::max(0.0f, normal_in_camera(frame, view, p).dot(light));
        const float shade = edge[p] ? 1.0f : kAmbientShade + (1.0f - kAmbientShade) * lambert;
        for (int k = 0; k < 3; ++k)
            c[k] = to_byte(cover * base[k] * shade + (1.0f - cover) * style.background[k]);
    }
    PaintedSurface out;
    out.image = Canvas(frame.width, frame.height, 3, std::move(rgb));
    out.anchors = anchors_of(frame, px.region);
    return out;
}

}  // namespace glint::detail
