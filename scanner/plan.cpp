#include "scanner/plan.h"

#include "mesh/error.h"
#include "mesh/parse.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace glint {

namespace {
// note: as sphere:N, at most 100000 views in all (every zoom level counted): 0.001° steps
// planned 1.8 M views and 1e-9 overflowed to one azimuth (issue 23).
constexpr double kMaxPlanViews = 100000;
}  // namespace

void SweepPlanOptions::validate() const {
    if (kind == Kind::Rotary) {
        if (!(azimuth_step_deg > 0 && azimuth_step_deg <= 360))
            throw OptionError("azimuth_step", azimuth_step_deg, "must be in (0, 360] degrees");
        if (elevations_deg.empty())
            throw OptionError("elevations", "[]", "no elevation rings: the plan would be empty");
        for (double e : elevations_deg)
            if (!(e >= -90 && e <= 90))
                throw OptionError("elevations", e, "each elevation must be in [-90, 90] degrees");
    } else if (sphere_views < 1) {
        throw OptionError("plan", "sphere:" + std::to_string(sphere_views), "needs N ≥ 1 views");
    }
    for (double f : footprints)
        if (!(f > 0) || !std::isfinite(f))
            throw OptionError("zoom", f, "each zoom footprint must be > 0 mesh units per pixel");
    if (size < 8 || size > max_size)
        throw OptionError("size", size, "must be in [8, " + std::to_string(max_size) + "] pixels");
    if (!(margin >= 1.0)) throw OptionError("margin", margin, "must be ≥ 1");
    const double per_level = kind == Kind::Rotary
                                 ? std::max(1.0, std::round(360.0 / azimuth_step_deg)) *
                                       static_cast<double>(elevations_deg.size())
                                 : static_cast<double>(sphere_views);
    const double views =
        per_level * static_cast<double>(std::max<std::size_t>(1, footprints.size()));
    if (views > kMaxPlanViews) {
        std::ostringstream s;
        s << "plans " << views << " views (" << per_level << " per zoom level × "
          << std::max<std::size_t>(1, footprints.size())
          << " levels), expected at most 100000 (a larger step, fewer elevations or zooms)";
        if (kind == Kind::Rotary) throw OptionError("azimuth_step", azimuth_step_deg, s.str());
        throw OptionError("plan", "sphere:" + std::to_string(sphere_views), s.str());
    }
}

void parse_plan_kind(const std::string& text, SweepPlanOptions& options) {
    if (text == "rotary") {
        options.kind = SweepPlanOptions::Kind::Rotary;
        return;
    }
    if (text.rfind("sphere:", 0) == 0) {
        options.kind = SweepPlanOptions::Kind::Sphere;
        const auto v = parse_number_list(text.substr(7), "plan '" + text + "'");
        // note: 100000 views bound a plan well beyond any sweep (and keep the cast defined).
        if (v.size() != 1 || !(v[0] >= 1 && v[0] <= 100000) || v[0] != std::floor(v[0]))
            throw InputError("plan '" + text +
                             "': expected sphere:N with N an integer from 1 to 100000");
        options.sphere_views = static_cast<int>(v[0]);
        return;
    }
    throw InputError("plan '" + text + "': expected 'rotary' or 'sphere:N'");
}

namespace {

struct Direction {
    double az, el;
    int ring, step;
};

// The vertices the plan frames: all, or the ROI's.
std::vector<std::uint32_t> framed_vertices(const Mesh& reference, const SweepPlanOptions& options) {
    std::vector<std::uint32_t> framed;
    if (!options.roi) {
        framed.resize(reference.vertex_count());
        for (std::size_t v = 0; v < framed.size(); ++v) framed[v] = static_cast<std::uint32_t>(v);
        return framed;
    }
    const Roi& roi = *options.roi;
    if (roi.shape == Roi::Shape::VertexMask && roi.vertex_mask.size() != reference.vertex_count())
        throw InputError("ROI " + to_string(roi) + ": the mask has " +
                         std::to_string(roi.vertex_mask.size()) + " entries, the reference has " +
                         std::to_string(reference.vertex_count()) + " vertices");
    for (std::size_t v = 0; v < reference.vertex_count(); ++v)
        if (roi.contains(v, reference.positions[v].cast<double>()))
            framed.push_back(static_cast<std::uint32_t>(v));
    if (framed.empty())
        throw InputError("ROI " + to_string(roi) + " contains no vertex of the reference mesh");
    return framed;
}

// Centre and radius of the framed sphere.
void frame(const Mesh& reference, const SweepPlanOptions& options,
           const std::vector<std::uint32_t>& framed, SweepPlan& plan) {
    Bounds box;
    for (auto v : framed) box.extend(reference.positions[v]);
    plan.target = box.center().cast<double>();
    double r = 0.0;
    for (auto v : framed)
        r = std::max(r, (reference.positions[v].cast<double>() - plan.target).norm());
    if (!(r > 0) && options.roi) {
        // A single vertex in the ROI: frame the ROI shape itself.
        const auto& roi = *options.roi;
        // note: a mask of one vertex has no extent of its own; 1% of the mesh's size frames
        // its neighbourhood.
        r = roi.shape == Roi::Shape::Sphere ? roi.radius
            : roi.shape == Roi::Shape::Box  ? 0.5 * (roi.max - roi.min).norm()
                                            : 0.01 * bounds(reference).diagonal();
    }
    if (!(r > 0)) throw InputError("sweep plan: the framed part of the mesh has zero extent");
    plan.radius = r * options.margin;
}

// Footprints and the image size that frames the sphere at each.
void zoom_levels(const SweepPlanOptions& options, SweepPlan& plan) {
    plan.footprints = options.footprints.empty()
                          ? std::vector<double>{2.0 * plan.radius / options.size}
                          : options.footprints;
    for (double f : plan.footprints) {
        const double size = std::ceil(2.0 * plan.radius / f);
        if (size > options.max_size) {
            std::ostringstream s;
            s << "sweep plan: zoom footprint " << f << " needs " << size
              << " px to frame a radius of " << plan.radius << " (max size " << options.max_size
              << "): choose a coarser zoom, a larger max size, or an ROI";
            throw InputError(s.str());
        }
        // note: below 4 px across, the framed part is a dot: no view would compare anything.
        if (size < 4.0) {
            std::ostringstream s;
            s << "sweep plan: zoom footprint " << f << " frames a radius of " << plan.radius
              << " in only " << size << " px, expected at least 4 px across (a footprint ≤ "
              << 2.0 * plan.radius / 4.0 << "): choose a finer zoom";
            throw InputError(s.str());
        }
        plan.sizes.push_back(std::max(8, static_cast<int>(size)));
    }
}

std::vector<Direction> directions(const SweepPlanOptions& options, SweepPlan& plan) {
    std::vector<Direction> dirs;
    if (options.kind == SweepPlanOptions::Kind::Rotary) {
        const int steps =
            std::max(1, static_cast<int>(std::round(360.0 / options.azimuth_step_deg)));
        for (std::size_t ring = 0; ring < options.elevations_deg.size(); ++ring)
            for (int s = 0; s < steps; ++s)
                dirs.push_back({s * options.azimuth_step_deg, options.elevations_deg[ring],
                                static_cast<int>(ring), s});
        plan.columns = steps;
        plan.rows = static_cast<int>(options.elevations_deg.size());
        return dirs;
    }
    // Fibonacci sphere: z uniform in (-1, 1), longitude stepped by the golden angle.
    const int n = options.sphere_views;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double lon = std::fmod(golden * i, 2.0 * std::numbers::pi);
        dirs.push_back(
            {lon * 180.0 / std::numbers::pi, std::asin(z) * 180.0 / std::numbers::pi, 0, i});
    }
    plan.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    plan.rows = (n + plan.columns - 1) / plan.columns;
    return dirs;
}

// With an ROI: the directions from which some ROI vertex faces the camera.
std::vector<Direction> seeing_roi(const Mesh& reference, const std::vector<std::uint32_t>& framed,
                                  const std::vector<Direction>& dirs) {
    std::vector<Direction> kept;
    for (const auto& d : dirs) {
        const Vec3f to_camera = direction_from_az_el(d.az, d.el).cast<float>();
        const bool sees = std::any_of(framed.begin(), framed.end(), [&](std::uint32_t v) {
            // note: 0.1 = cos(84°): grazing views show the ROI too obliquely to help.
            return reference.normals[v].dot(to_camera) > 0.1f;
        });
        if (sees) kept.push_back(d);
    }
    if (kept.empty()) throw InputError("sweep plan: no view of the plan sees the ROI");
    return kept;
}

PlannedView planned_view(const SweepPlan& plan, const Direction& d, std::size_t zoom, int index) {
    PlannedView v;
    v.view.index = index;
    v.view.azimuth_deg = d.az;
    v.view.elevation_deg = d.el;
    v.view.zoom_index = static_cast<int>(zoom);
    v.view.footprint = plan.footprints[zoom];
    v.ring = d.ring;
    v.step = d.step;
    const Vec3d dir = direction_from_az_el(d.az, d.el);
    Camera& cam = v.view.camera;
    cam.projection = Projection::Orthographic;
    cam.world_from_camera =
        look_at(plan.target + 3.0 * plan.radius * dir, plan.target, Vec3d::UnitZ());
    cam.width = cam.height = plan.sizes[zoom];
    cam.ortho_half_height = 0.5 * plan.sizes[zoom] * plan.footprints[zoom];
    cam.near_plane = 1.0 * plan.radius;  // the framed sphere spans 2R..4R from the eye
    cam.far_plane = 5.0 * plan.radius;
    return v;
}

}  // namespace

SweepPlan make_sweep_plan(const Mesh& reference, const SweepPlanOptions& options) {
    options.validate();
    SweepPlan plan;
    plan.options = options;
    const std::vector<std::uint32_t> framed = framed_vertices(reference, options);
    if (options.roi) plan.roi_vertices = framed.size();
    frame(reference, options, framed, plan);
    zoom_levels(options, plan);
    std::vector<Direction> dirs = directions(options, plan);
    if (options.roi && reference.has_normals()) dirs = seeing_roi(reference, framed, dirs);
    int index = 0;
    for (std::size_t z = 0; z < plan.footprints.size(); ++z)
        for (const auto& d : dirs) plan.views.push_back(planned_view(plan, d, z, index++));
    return plan;
}

}  // namespace glint
