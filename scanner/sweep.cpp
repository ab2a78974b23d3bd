#include "scanner/sweep.h"

#include "mesh/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

namespace glint {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Barycentric weights of the point where `ray` meets the plane of triangle t, clamped to the
// triangle (the pixel centre may fall just outside the triangle its sub-sample hit).
// cos_incidence is signed: positive when the triangle's front (its winding's normal, the side
// its vertex normals point to) faces the camera. The back of a surface — an open mesh seen
// from behind, or through a hole — is not an observation of it.
bool barycentric(const Mesh& mesh, std::uint32_t t, const Ray& ray, std::array<float, 3>& w,
                 double& cos_incidence) {
    const auto& tri = mesh.triangles[t];
    const Vec3d a = mesh.positions[tri[0]].cast<double>();
    const Vec3d b = mesh.positions[tri[1]].cast<double>();
    const Vec3d c = mesh.positions[tri[2]].cast<double>();
    const Vec3d n = (b - a).cross(c - a);
    const double area2 = n.norm();
    if (!(area2 > 0)) return false;
    const double denom = n.dot(ray.direction);
    cos_incidence = -denom / area2;
    if (std::abs(denom) < 1e-12 * area2) return false;
    const double s = n.dot(a - ray.origin) / denom;
    const Vec3d p = ray.origin + s * ray.direction;
    double wa = n.dot((b - p).cross(c - p)) / (area2 * area2);
    double wb = n.dot((c - p).cross(a - p)) / (area2 * area2);
    double wc = 1.0 - wa - wb;
    wa = std::max(0.0, wa);
    wb = std::max(0.0, wb);
    wc = std::max(0.0, wc);
    const double sum = wa + wb + wc;
    if (!(sum > 0)) return false;
    w = {static_cast<float>(wa / sum), static_cast<float>(wb / sum), static_cast<float>(wc / sum)};
    return true;
}

}  // namespace

Metric parse_metric(const std::string& text) {
    if (text == "angle") return Metric::AngleDeg;
    if (text == "rgb") return Metric::RgbAbs;
    throw InputError("metric \"" + text + "\": expected angle or rgb");
}

std::string to_string(Metric metric) { return metric == Metric::RgbAbs ? "rgb" : "angle"; }

void SweepOptions::validate() const {
    plan.validate();
    render.validate();
    auto bad = [](const std::string& field, double value, const std::string& rule) {
        std::ostringstream s;
        s << "sweep: " << field << " = " << value << ": " << rule;
        throw InputError(s.str());
    };
    if (!(max_incidence_deg > 0 && max_incidence_deg < 90)) bad("max incidence", max_incidence_deg, "must be in (0, 90) degrees");
    if (metric == Metric::RgbAbs) {
        if (threshold_deg && !(*threshold_deg > 0 && *threshold_deg <= 255)) bad("threshold", *threshold_deg, "must be in (0, 255] colour units (metric rgb)");
    } else if (threshold_deg && !(*threshold_deg > 0 && *threshold_deg <= 180)) {
        bad("threshold", *threshold_deg, "must be in (0, 180] degrees");
    }
    if (!(noise_k > 0)) bad("noise k", noise_k, "must be > 0");
    if (!(min_threshold_deg >= 0)) bad("minimum threshold", min_threshold_deg, "must be ≥ 0 degrees");
    if (!(compare.min_coverage > 0 && compare.min_coverage <= 1)) bad("min coverage", compare.min_coverage, "must be in (0, 1]");
}

View to_render_view(const PlannedView& p) {
    View v;
    v.camera = p.camera;
    v.azimuth_deg = p.azimuth_deg;
    v.elevation_deg = p.elevation_deg;
    v.footprint = p.footprint;
    v.zoom_index = p.zoom_index;
    v.index = p.index;
    return v;
}

FrameView frame_view(const Frame& f) {
    return {f.width, f.height, f.normal, f.primitive_id, f.depth, f.coverage};
}

SweepResult run_sweep(const Mesh& reference, const Mesh& examined, const SweepPlan& plan_in,
                      const SweepOptions& options, const ViewObserver& observer, const std::vector<float>& distance) {
    const auto t_start = Clock::now();
    options.validate();
    SweepResult result;
    result.plan = plan_in;
    result.options = options;
    const auto& plan = result.plan;
    if (plan.views.empty()) throw InputError("sweep plan has no views");

    Renderer ref_renderer(reference, options.render);
    Renderer exa_renderer(examined, options.render);
    result.renderer = ref_renderer.info();

    std::vector<AtlasAccumulator> acc;
    for (double f : plan.footprints) acc.emplace_back(reference, f);
    const double min_cos = std::cos(options.max_incidence_deg * std::numbers::pi / 180.0);
    // The metric folded onto the surface (the atlas' "angle" fields carry it).
    const bool use_rgb = options.metric == Metric::RgbAbs;
    CompareOptions compare = options.compare;
    compare.compute_rgb = compare.compute_rgb || use_rgb;
    const float missing_value = use_rgb ? 255.0f : 90.0f;  // no examined surface behind the pixel

    std::vector<View> views;
    views.reserve(plan.views.size());
    for (const auto& p : plan.views) views.push_back(to_render_view(p));

    // Gathering: which vertices a pixel centre already fell on in the current view.
    const std::size_t nv = reference.vertex_count();
    std::vector<std::int32_t> scattered_in(nv, -1);
    if (!reference.has_normals()) throw InputError("sweep: the reference mesh has no vertex normals");

    double render_s = 0.0;
    double compare_s = 0.0;
    auto t_view = Clock::now();
    ref_renderer.render_views(views, [&](std::size_t i, const Frame& ref_frame) {
        const PlannedView& pv = plan.views[i];
        const Frame exa_frame = exa_renderer.render(views[i]);
        render_s += seconds_since(t_view);
        const auto t_cmp = Clock::now();
        const DeviationMap dev = compare_frames(frame_view(ref_frame), frame_view(exa_frame), compare);
        const std::vector<float>& deviation = use_rgb ? dev.rgb_abs : dev.angle_deg;

        ViewSummary s;
        s.index = pv.index;
        s.azimuth_deg = pv.azimuth_deg;
        s.elevation_deg = pv.elevation_deg;
        s.zoom_index = pv.zoom_index;
        s.size = ref_frame.width;
        s.compared = dev.compared;
        s.reference_only = dev.reference_only;
        s.examined_only = dev.examined_only;
        s.max_angle_deg = dev.max_angle_deg;
        s.mean_angle_deg = dev.mean_angle_deg;

        auto& a = acc[static_cast<std::size_t>(pv.zoom_index)];
        for (int y = 0; y < ref_frame.height; ++y) {
            for (int x = 0; x < ref_frame.width; ++x) {
                const std::size_t px = static_cast<std::size_t>(y) * static_cast<std::size_t>(ref_frame.width) +
                                       static_cast<std::size_t>(x);
                const std::uint32_t t = ref_frame.primitive_id[px];
                if (t == kNoPrimitive || ref_frame.coverage[px] < options.compare.min_coverage) continue;
                ++s.reference_pixels;
                AtlasSample sample;
                sample.triangle = t;
                double cos_inc = 0.0;
                if (!barycentric(reference, t, pv.camera.pixel_ray(x + 0.5, y + 0.5), sample.barycentric, cos_inc))
                    continue;
                if (cos_inc < min_cos) continue;
                sample.cos_incidence = static_cast<float>(cos_inc);
                if (dev.silhouette[px] == static_cast<std::uint8_t>(Silhouette::ReferenceOnly)) {
                    sample.angle_deg = missing_value;
                    sample.signed_depth = std::numeric_limits<float>::quiet_NaN();
                } else if (!std::isnan(deviation[px])) {
                    sample.angle_deg = deviation[px];
                    sample.signed_depth = dev.signed_depth[px];
                } else {
                    sample.valid_deviation = false;
                }
                a.add(sample, pv.index);
                for (const auto v : reference.triangles[t]) scattered_in[v] = pv.index;
            }
        }
        // Gathering: at a coarse footprint one pixel covers many small triangles, and most
        // vertices are on no pixel's centre triangle. Each visible vertex that no pixel
        // centre fell on reads the (footprint-averaged) deviation of the pixel it projects
        // to. Visible: it projects onto a fully covered pixel whose depth is within the
        // pixel's own depth spread (3 footprints, or 2% of the framed radius), and its normal
        // faces the camera within the incidence limit.
        const double depth_tolerance = std::max(3.0 * pv.footprint, 0.02 * plan.radius);
        const Vec3d eye = pv.camera.eye();
        const Vec3d forward = pv.camera.forward();
        // note: Camera::project inverts the pose on every call; here it is inverted once per
        // view (a 1M-vertex mesh is projected 72 times in a sweep).
        const Rigid camera_from_world = pv.camera.world_from_camera.inverse();
        const Camera& cam = pv.camera;
        const double aspect = static_cast<double>(cam.width) / cam.height;
        const double tan_half = std::tan(0.5 * cam.fov_y_rad);
        const bool ortho = cam.projection == Projection::Orthographic;
        auto project = [&](const Vec3d& world) {
            const Vec3d c = camera_from_world * world;
            const double depth = -c.z();
            const double sx = ortho ? cam.ortho_half_height * aspect : depth * tan_half * aspect;
            const double sy = ortho ? cam.ortho_half_height : depth * tan_half;
            return Eigen::Vector3d(0.5 * (c.x() / sx + 1.0) * cam.width, 0.5 * (1.0 - c.y() / sy) * cam.height, depth);
        };
        for (std::size_t v = 0; v < nv; ++v) {
            if (scattered_in[v] == pv.index) continue;
            const Vec3d p = reference.positions[v].cast<double>();
            const Eigen::Vector3d uvd = project(p);
            if (!(uvd.x() >= 0 && uvd.y() >= 0 && uvd.x() < ref_frame.width && uvd.y() < ref_frame.height)) continue;
            const std::size_t px = static_cast<std::size_t>(uvd.y()) * static_cast<std::size_t>(ref_frame.width) +
                                   static_cast<std::size_t>(uvd.x());
            if (ref_frame.primitive_id[px] == kNoPrimitive || ref_frame.coverage[px] < options.compare.min_coverage) continue;
            if (std::abs(ref_frame.depth[px] - uvd.z()) > depth_tolerance) continue;
            const Vec3d to_camera = pv.camera.projection == Projection::Orthographic ? Vec3d(-forward) : Vec3d((eye - p).normalized());
            const double cos_inc = reference.normals[v].cast<double>().dot(to_camera);
            if (cos_inc < min_cos) continue;
            if (dev.silhouette[px] == static_cast<std::uint8_t>(Silhouette::ReferenceOnly))
                a.add_vertex(static_cast<std::uint32_t>(v), missing_value, std::numeric_limits<float>::quiet_NaN(),
                             static_cast<float>(cos_inc), pv.index);
            else if (!std::isnan(deviation[px]))
                a.add_vertex(static_cast<std::uint32_t>(v), deviation[px], dev.signed_depth[px],
                             static_cast<float>(cos_inc), pv.index);
        }
        result.views.push_back(s);
        if (observer) observer(pv, ref_frame, exa_frame, dev);
        compare_s += seconds_since(t_cmp);
        t_view = Clock::now();
    });
    std::size_t compared = 0;
    for (const auto& v : result.views) compared += v.compared;
    if (compared == 0)
        throw InputError("sweep: the reference and the fitted examined surface do not overlap in any of the " +
                         std::to_string(result.views.size()) +
                         " views (no pixel shows both); check the fit (--fit, --register, landmarks)");
    result.render_seconds = render_s;
    result.compare_seconds = compare_s;

    const auto areas = vertex_areas(reference);
    double total_area = 0.0;
    for (double x : areas) total_area += x;
    for (std::size_t z = 0; z < acc.size(); ++z) {
        ZoomResult zr;
        zr.atlas = acc[z].finish();
        const std::size_t n = reference.vertex_count();
        zr.seen.assign(n, 0);
        double seen_area = 0.0;
        const auto& roi = plan.options.roi;
        for (std::size_t v = 0; v < n; ++v) {
            zr.seen[v] = zr.atlas.weight[v] > 0.0f ? 1 : 0;
            if (roi && !roi->contains(reference.positions[v].cast<double>())) zr.seen[v] = 0;
            if (zr.seen[v]) seen_area += areas[v];
        }
        // Coverage of what was asked for: the ROI's area with an ROI, else the whole surface.
        double asked_area = total_area;
        if (roi) {
            asked_area = 0.0;
            for (std::size_t v = 0; v < n; ++v)
                if (roi->contains(reference.positions[v].cast<double>())) asked_area += areas[v];
        }
        zr.coverage = asked_area > 0 ? seen_area / asked_area : 0.0;
        zr.noise = noise_floor(zr.atlas.angle_mean_deg, zr.seen, options.noise_k, options.min_threshold_deg);
        if (options.threshold_deg) {
            zr.threshold_deg = *options.threshold_deg;
            zr.threshold_rule = "given";
        } else {
            zr.threshold_deg = zr.noise.threshold;
            std::ostringstream rule;
            rule << "noise floor: median + " << options.noise_k << "·1.4826·MAD of the per-vertex mean angle "
                 << "over seen vertices, at least " << options.min_threshold_deg << "°";
            zr.threshold_rule = rule.str();
        }
        RegionInputs in;
        in.angle_deg = &zr.atlas.angle_mean_deg;
        in.depth = &zr.atlas.depth_mean;
        if (distance.size() == n) in.distance = &distance;
        in.view = &zr.atlas.max_view;
        in.seen = &zr.seen;
        zr.regions = find_regions(reference, in,
                                  RegionOptions{.threshold_deg = zr.threshold_deg,
                                                .min_vertices = options.min_region_vertices});
        zr.histogram.assign(91, 0);
        for (std::size_t v = 0; v < n; ++v)
            if (zr.seen[v]) ++zr.histogram[std::min<std::size_t>(90, static_cast<std::size_t>(zr.atlas.angle_mean_deg[v]))];
        result.zooms.push_back(std::move(zr));
    }
    result.total_seconds = seconds_since(t_start);
    return result;
}

}  // namespace glint
