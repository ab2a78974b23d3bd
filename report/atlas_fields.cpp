#include "report/atlas_fields.h"

#include "decision/decision.h"
#include "mesh/units.h"
#include "report/images.h"
#include "report/pictures.h"
#include "scanner/metric.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace glint {

namespace {

std::string zoom_suffix(std::size_t z) { return "_z" + std::to_string(z); }

// A value for the files: NaN or infinity (none is expected) becomes the unseen sentinel 0.
float finite_or_zero(float x) { return std::isfinite(x) ? x : 0.0f; }

std::vector<float> finite_copy(const std::vector<float>& in) {
    std::vector<float> out(in.size());
    for (std::size_t v = 0; v < in.size(); ++v) out[v] = finite_or_zero(in[v]);
    return out;
}

// The fields of one zoom, in the order of the header comment.
void add_zoom_fields(Mesh& atlas, const AnalysisResult& result, std::size_t z) {
    const std::size_t n = atlas.vertex_count();
    const auto& sz = result.sweep.zooms[z];
    const auto& a = sz.atlas;
    std::vector<float> seen(n), mean(n), max(n), missing(n), pixels(n), region(n), compared(n);
    const auto& classes = result.decisions[z].comparison.vertex_class;
    for (std::size_t v = 0; v < n; ++v) {
        const bool s = sz.coverage.seen[v] != 0;
        seen[v] = s ? 1.0f : 0.0f;
        mean[v] = s ? finite_or_zero(a.value_mean[v]) : 0.0f;
        max[v] = s ? finite_or_zero(a.value_max[v]) : 0.0f;
        missing[v] = s ? finite_or_zero(a.missing[v]) : 0.0f;
        pixels[v] = static_cast<float>(a.count[v]);
        region[v] = static_cast<float>(result.decisions[z].regions.region_of_vertex[v]);
        compared[v] = classes.size() == n ? static_cast<float>(classes[v]) : 0.0f;
    }
    const Metric metric = result.sweep.options.metric;
    atlas.set_scalar(seen_field(z), std::move(seen));
    atlas.set_scalar(metric_field(metric, "mean", z), std::move(mean));
    atlas.set_scalar(metric_field(metric, "max", z), std::move(max));
    atlas.set_scalar(missing_field(z), std::move(missing));
    atlas.set_scalar(pixels_field(z), std::move(pixels));
    atlas.set_scalar(region_field(z), std::move(region));
    atlas.set_scalar(comparison_field(z), std::move(compared));
}

}  // namespace

std::string shape_change_field(const std::string& unit) {
    return "shape_change" + unit_suffix(unit);
}
std::vector<float> shape_change_values(const AnalysisResult& result) {
    if (result.decisions.empty()) return result.distance;
    return decided_shape(result.distance, result.decisions[0]);
}

std::string shape_tolerance_field(const std::string& unit) {
    return "shape_tolerance" + unit_suffix(unit);
}
std::string seen_field(std::size_t zoom) { return "seen" + zoom_suffix(zoom); }
std::string region_field(std::size_t zoom) { return "region_id" + zoom_suffix(zoom); }
std::string pixels_field(std::size_t zoom) { return "pixels" + zoom_suffix(zoom); }
std::string missing_field(std::size_t zoom) { return "missing_fraction" + zoom_suffix(zoom); }
std::string comparison_field(std::size_t zoom) { return "not_compared" + zoom_suffix(zoom); }

std::string metric_field(Metric metric, const std::string& statistic, std::size_t zoom) {
    const MetricDescriptor& m = describe(metric);
    return std::string(m.name) + "_" + statistic + "_" + std::string(m.unit) + zoom_suffix(zoom);
}

// note: the view-ray depth difference the sweep also accumulates (ZoomAtlas::depth_mean) is
// not a field: measured along each view's ray, not the surface normal, it grows as
// 1/cos(incidence) and, at a silhouette, takes the depth of whatever surface lies behind
// (−5.5 mm at a vertex 0.47 mm from the examined jaw); shape_change_<u> is the shape change.
Mesh make_atlas_mesh(const Mesh& reference, const AnalysisResult& result) {
    Mesh atlas = reference;
    atlas.unit = result.unit;
    atlas.scalars.clear();
    atlas.labels.clear();
    const std::size_t n = reference.vertex_count();
    const std::vector<float> shape =
        result.distance.size() == n ? shape_change_values(result) : std::vector<float>{};
    if (!shape.empty()) atlas.set_scalar(shape_change_field(result.unit), finite_copy(shape));
    if (result.tolerance.size() == n)
        atlas.set_scalar(shape_tolerance_field(result.unit), finite_copy(result.tolerance));
    for (std::size_t z = 0; z < result.sweep.zooms.size(); ++z) add_zoom_fields(atlas, result, z);
    if (!result.sweep.zooms.empty() && !shape.empty()) {
        // The pictures' colours (report/pictures.h): signed shape change, blue loss, red gain,
        // symmetric range; grey where zoom 0 saw nothing or a hole's depth is unknown.
        const ShapeScale scale = shape_scale(result);
        std::vector<float> shown(shape);
        for (std::size_t v = 0; v < n; ++v)
            if (!result.sweep.zooms[0].coverage.seen[v])
                shown[v] = std::numeric_limits<float>::quiet_NaN();
        atlas.colors = colorize(shown, ColorScale{.low = -scale.limit,
                                                  .high = scale.limit,
                                                  .map = "diverging",
                                                  .no_data_grey = 0.6f});
    }
    return atlas;
}

}  // namespace glint
