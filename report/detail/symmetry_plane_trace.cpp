#include "report/detail/symmetry_plane_trace.h"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>
#include "mesh/mesh.h"

namespace glint::detail {

namespace {

// Two neighbouring pixels on one surface lie this many footprints apart along the plane's
// normal at most (a steep slope); farther, one occludes the other and the plane does not run
// between them.
constexpr double kNeighbourFootprints = 8.0;
constexpr int kTraceLabelFont = 12;

enum class PixelKind : std::uint8_t { None, Surface, Background };

struct PlaneDistances {
    std::vector<double> distance;  ///< per pixel, mesh units (NaN: none)
    std::vector<PixelKind> kind;
};

// Each pixel's signed distance from the plane: of the surface point it shows, or, on the
// background of an edge-on orthographic view, of its ray (every point of which lies at one
// distance).
PlaneDistances plane_distances(const Frame& frame, const View& view, const MirrorPictures& plane,
                               bool edge_on) {
    const Camera& camera = view.camera;
    PlaneDistances out{std::vector<double>(frame.pixel_count(), double(kNaN)),
                       std::vector<PixelKind>(frame.pixel_count(), PixelKind::None)};
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            const auto p = static_cast<std::size_t>(y * frame.width + x);
            const Ray ray = camera.pixel_ray(x + 0.5, y + 0.5);
            if (frame.primitive_id[p] != kNoPrimitive && std::isfinite(frame.depth[p])) {
                const double along = frame.depth[p] / ray.direction.dot(camera.forward());
                out.distance[p] = plane.distance(ray.origin + along * ray.direction);
                out.kind[p] = PixelKind::Surface;
            } else if (edge_on) {
                out.distance[p] = plane.distance(ray.origin);
                out.kind[p] = PixelKind::Background;
            }
        }
    return out;
}

bool touches_region(const Mesh& mesh, std::uint32_t triangle,
                    std::span<const std::int32_t> region) {
    if (triangle == kNoPrimitive || triangle >= mesh.triangles.size()) return false;
    for (const auto v : mesh.triangles[triangle])
        if (v < region.size() && region[v] != 0) return true;
    return false;
}

// Whether (x, y) lies within 3 px of one of the boxes.
bool near_any(std::span<const PixelBox> boxes, int x, int y) {
    for (const PixelBox& b : boxes)
        if (x >= b.x0 - 3 && x < b.x1 + 3 && y >= b.y0 - 3 && y < b.y1 + 3) return true;
    return false;
}

// The first place, from the top, where the label fits on the background beside a line pixel
// (right, left, above or below it, off the line), clear of the picture's edges and of
// `keep_clear`.
std::optional<PlaneLabel> label_place(const std::vector<std::uint8_t>& line,
                                      const PlaneDistances& d, int width, int height,
                                      std::span<const PixelBox> keep_clear) {
    const int w = text_width(kSymmetryPlaneLabel, kTraceLabelFont);
    const auto clear = [&](int x0, int y0, int x1, int y1) {
        if (x0 < 4 || y0 < 24 || x1 > width - 4 || y1 > height - 30) return false;
        for (const PixelBox& b : keep_clear)
            if (b.overlaps({x0 - 3, y0 - 3, x1 + 3, y1 + 3})) return false;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const auto p = static_cast<std::size_t>(y * width + x);
                if (d.kind[p] != PixelKind::Background || line[p]) return false;
            }
        return true;
    };
    // (x, baseline) of the label: right, left, above and below the line pixel
    const auto places = [&](int x, int y) {
        return std::array<PlaneLabel, 4>{PlaneLabel{x + 6, y}, PlaneLabel{x - 5 - w, y},
                                         PlaneLabel{x + 4, y - 5}, PlaneLabel{x + 4, y + 17}};
    };
    for (int y = 40; y < height - 40; ++y)
        for (int x = 0; x < width; ++x) {
            if (!line[static_cast<std::size_t>(y * width + x)]) continue;
            for (const PlaneLabel& l : places(x, y))
                if (clear(l.x - 2, l.y - kTraceLabelFont, l.x + w + 2, l.y + 4)) return l;
        }
    return std::nullopt;
}

}  // namespace

void draw_plane_label(Canvas& sheet, int x, int y, const std::optional<PlaneLabel>& label) {
    if (label)
        draw_text(sheet, x + label->x, y + label->y, std::string(kSymmetryPlaneLabel), 12,
                  kSymmetryPlane, TextAlign::Left, 2);
}

std::optional<PlaneLabel> draw_symmetry_plane(Canvas& image, const Frame& frame, const View& view,
                                              const Mesh& mesh,
                                              std::span<const std::int32_t> region,
                                              const MirrorPictures& plane,
                                              std::span<const PixelBox> keep_clear) {
    const Camera& camera = view.camera;
    const bool edge_on = camera.projection == Projection::Orthographic &&
                         std::abs(plane.normal.dot(camera.forward())) <
                             std::sin(kEdgeOnDeg * std::numbers::pi / 180.0);
    const PlaneDistances d = plane_distances(frame, view, plane, edge_on);
    const int w = frame.width, h = frame.height;
    const double reach = kNeighbourFootprints * view.footprint;
    std::vector<std::uint8_t> line(frame.pixel_count(), 0);
    const auto crossing = [&](std::size_t a, std::size_t b) {
        if (d.kind[a] == PixelKind::None || d.kind[a] != d.kind[b]) return;
        if ((d.distance[a] < 0) == (d.distance[b] < 0)) return;
        if (d.kind[a] == PixelKind::Surface && std::abs(d.distance[a] - d.distance[b]) > reach)
            return;
        line[a] = line[b] = 1;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto p = static_cast<std::size_t>(y * w + x);
            if (x + 1 < w) crossing(p, p + 1);
            if (y + 1 < h) crossing(p, p + static_cast<std::size_t>(w));
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto p = static_cast<std::size_t>(y * w + x);
            if (line[p] && !touches_region(mesh, frame.primitive_id[p], region) &&
                !near_any(keep_clear, x, y))
                image.set(x, y, kSymmetryPlane);
        }
    if (!edge_on) return std::nullopt;
    return label_place(line, d, w, h, keep_clear);
}

std::string symmetry_plane_footer(const MirrorPictures& plane, const std::string& unit) {
    const Vec3d n = plane.normal, q = plane.offset * plane.normal;
    // to 4 decimals: a fitted normal's 1e-17 is 0
    const auto number = [](double x) { return format_number(std::round(x * 1e4) / 1e4 + 0.0); };
    const auto triple = [&](const Vec3d& v) {
        return "(" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) + ")";
    };
    return with_minus_sign("symmetry plane (magenta line): normal " + triple(n) + ", through " +
                           triple(q) + " " + unit + ", residual " + format_number(plane.residual) +
                           " " + unit);
}

}  // namespace glint::detail
