#include "report/report_html.h"

#include "image/sampled_maps.h"
#include "mesh/decimate.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/mesh.h"
#include "mesh/normals.h"
#include "report/asymmetry_html.h"
#include "report/atlas_fields.h"
#include "report/detail/canvas.h"
#include "scanner/metric.h"

#include <openssl/evp.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <unordered_set>
#include <utility>

namespace glint {

// The embedded page sources and libraries (cmake/GlintEmbed.cmake, report/CMakeLists.txt).
std::string_view report_asset(std::string_view key);

namespace {

using nlohmann::json;

// note: typed arrays are read in the page with the machine's byte order; every machine glint
// and browsers run on is little-endian, as the arrays are written here.
// Base64 of bytes (OpenSSL's encoder, one line without breaks).
std::string base64(std::string_view bytes) {
    std::string out(4 * ((bytes.size() + 2) / 3), '\0');
    const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                  static_cast<int>(bytes.size()));
    out.resize(static_cast<std::size_t>(n));
    return out;
}

template <typename T>
std::string base64_of(const std::vector<T>& values) {
    static_assert(std::endian::native == std::endian::little,
                  "report.html arrays are little-endian");
    return base64(
        std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

std::string asset(std::string_view key) {
    const std::string_view text = report_asset(key);
    GLINT_ASSERT(!text.empty(), "report.html: asset '" + std::string(key) + "' is not embedded");
    // A script inlined in <script> must not close it early.
    GLINT_ASSERT(key == "report.html.in" || text.find("</script") == std::string_view::npos,
                 "report.html: asset '" + std::string(key) + "' contains \"</script\"");
    return std::string(text);
}

// A per-vertex field for the page: its values, how it is coloured and its default range.
json field_json(const std::string& name, const std::string& label, const std::string& kind,
                const std::string& unit, int zoom, const std::vector<float>& values, double low,
                double high) {
    return {{"name", name},
            {"label", label},
            {"kind", kind},
            {"unit", unit},
            {"zoom", zoom},
            {"range", {low, high}},
            {"values", base64_of(values)}};
}

// What the page shows of the reference: the mesh itself, or for a large one a decimated copy
// (mesh/decimate.h) whose vertices are vertices of the reference (`ids`: their ids there).
struct ShownMesh {
    const Mesh* mesh = nullptr;
    std::optional<DecimatedMesh> decimated;

    [[nodiscard]] std::size_t vertex(std::size_t k) const {
        return decimated ? decimated->original_vertex[k] : k;
    }
    [[nodiscard]] std::size_t vertex_count() const { return mesh->vertex_count(); }
};

// Above `max_triangles`: the triangles that touch a region are kept as they are, so regions
// keep their exact outline; the rest is collapsed (meshoptimizer) within 1 % of the size, the
// surface's borders kept.
ShownMesh shown_mesh(const Mesh& reference, const AnalysisResult& result,
                     std::size_t max_triangles) {
    ShownMesh shown{&reference, std::nullopt};
    if (reference.triangle_count() <= max_triangles) return shown;
    std::vector<std::uint8_t> keep(reference.triangle_count(), 0);
    for (std::size_t t = 0; t < reference.triangle_count(); ++t)
        for (const auto& d : result.decisions)
            for (const auto v : reference.triangles[t])
                if (d.regions.region_of_vertex[v] != 0) keep[t] = 1;
    shown.decimated = decimate(reference, max_triangles, keep, 0.01 * result.size);
    shown.mesh = &shown.decimated->mesh;
    return shown;
}

json fields_json(const ShownMesh& shown, const AnalysisResult& result, const ShapeScale& scale) {
    const std::size_t n = shown.vertex_count();
    const MetricDescriptor& m = describe(result.sweep.options.metric);
    const std::string unit = result.unit.empty() ? "units" : result.unit;
    const Metric metric = result.sweep.options.metric;
    json fields = json::array();
    if (!result.distance.empty()) {
        const std::vector<float> shape = shape_change_values(result);
        std::vector<float> distance(n);
        for (std::size_t k = 0; k < n; ++k) distance[k] = shape[shown.vertex(k)];
        fields.push_back(field_json(shape_change_field(result.unit),
                                    "shape change (signed distance; in a hole the depth gone)",
                                    "signed", unit, -1, distance, -scale.limit, scale.limit));
    }
    for (std::size_t z = 0; z < result.sweep.zooms.size(); ++z) {
        const auto& a = result.sweep.zooms[z].atlas;
        const auto& seen = result.sweep.zooms[z].coverage.seen;
        const auto& d = result.decisions[z];
        const std::string at = " (zoom " + std::to_string(z) + ")";
        std::vector<float> mean(n), max(n), region(n), seen_f(n), count(n), compared(n);
        const auto& classes = d.comparison.vertex_class;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t v = shown.vertex(i);
            mean[i] = seen[v] ? a.value_mean[v] : kNaN;
            max[i] = seen[v] ? a.value_max[v] : kNaN;
            region[i] = static_cast<float>(d.regions.region_of_vertex[v]);
            seen_f[i] = seen[v] ? 1.0f : 0.0f;
            count[i] = static_cast<float>(a.count[v]);
            compared[i] = classes.size() == seen.size() ? static_cast<float>(classes[v]) : 0.0f;
        }
        const double top = std::max(2.0 * d.normal.value, 1e-6);
        fields.push_back(field_json(metric_field(metric, "mean", z), "normal deviation, mean" + at,
                                    "sequential", std::string(m.symbol), static_cast<int>(z), mean,
                                    0.0, top));
        fields.push_back(field_json(metric_field(metric, "max", z), "normal deviation, max" + at,
                                    "sequential", std::string(m.symbol), static_cast<int>(z), max,
                                    0.0, top));
        fields.push_back(field_json(region_field(z), "damaged: region id" + at, "category", "",
                                    static_cast<int>(z), region, 0.0,
                                    static_cast<double>(d.regions.regions.size())));
        fields.push_back(field_json(comparison_field(z),
                                    "not compared: 1 reference border, 2 examined border, 3 not "
                                    "reached, 4 below resolution" +
                                        at,
                                    "category", "", static_cast<int>(z), compared, 0.0, 4.0));
        fields.push_back(field_json(seen_field(z), "coverage: seen" + at, "binary", "",
                                    static_cast<int>(z), seen_f, 0.0, 1.0));
        const auto most = a.count.empty() ? 1u : *std::max_element(a.count.begin(), a.count.end());
        fields.push_back(field_json(pixels_field(z), "coverage: observations" + at, "sequential",
                                    "pixels", static_cast<int>(z), count, 0.0,
                                    std::max(1.0, static_cast<double>(most))));
    }
    return fields;
}

// OIIO's inferno sampled at 17 points: the page's sequential map is the one OIIO draws.
std::vector<float> inferno_knots() {
    // 17 evenly spaced colours of OpenImageIO's map, from its build-time samples (the page
    // loads no image library): sample i·(intervals/16) is the map at i/16.
    constexpr int kKnots = 17;
    constexpr int kStride = kSampledIntervals / (kKnots - 1);
    const std::span<const float> samples = sampled_map(SampledMap::Inferno);
    std::vector<float> knots;
    for (int i = 0; i < kKnots; ++i) {
        const auto first = samples.begin() + 3 * i * kStride;
        knots.insert(knots.end(), first, first + 3);
    }
    return knots;
}

// A mesh's arrays for the page: float32 positions, uint32 indices and, when it has them,
// its vertex normals as int16 scaled by 32767 (half the bytes of float32; the rounding tilts
// a unit normal by at most 0.003°, far below any floor).
json mesh_arrays_json(const Mesh& m) {
    std::vector<float> positions;
    positions.reserve(3 * m.vertex_count());
    for (const auto& p : m.positions) positions.insert(positions.end(), {p.x(), p.y(), p.z()});
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * m.triangle_count());
    for (const auto& t : m.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
    json out = {{"positions", base64_of(positions)}, {"indices", base64_of(indices)}};
    if (m.has_normals()) {
        std::vector<std::int16_t> normals;
        normals.reserve(3 * m.vertex_count());
        for (const auto& n : m.normals)
            for (int c = 0; c < 3; ++c)
                normals.push_back(static_cast<std::int16_t>(
                    std::lround(32767.0f * std::clamp(n[c], -1.0f, 1.0f))));
        out["normals"] = base64_of(normals);
    }
    return out;
}

json mesh_json(const Mesh& reference, const ShownMesh& shown) {
    const Mesh& m = *shown.mesh;
    const Bounds b = bounds(reference);
    const Vec3f c = b.center();
    json out = mesh_arrays_json(m);
    out.update({{"vertices", reference.vertex_count()},
                {"triangles", reference.triangle_count()},
                {"center", {c.x(), c.y(), c.z()}},
                {"radius", 0.5 * b.diagonal()}});
    if (shown.decimated) {
        // The page names a vertex by its id in the atlas files.
        out["vertex_ids"] = base64_of(shown.decimated->original_vertex);
        out["shown"] = {{"vertices", m.vertex_count()},
                        {"triangles", m.triangle_count()},
                        {"error", shown.decimated->error}};
    }
    return out;
}

// The live view's data: the examined surface, and how the sweep rendered and compared (its
// plan, footprints and floors are report.json's, which the page holds whole).
json live_json(const LiveSurface& examined, const AnalysisResult& result) {
    json surface = mesh_arrays_json(examined.mesh);
    surface.update({{"vertices", examined.mesh.vertex_count()},
                    {"triangles", examined.triangles},
                    {"shown_triangles", examined.mesh.triangle_count()},
                    {"error", examined.error}});
    return {{"examined", std::move(surface)},
            {"supersample", result.sweep.options.render.supersample},
            {"min_coverage", result.sweep.options.compare.min_coverage}};
}

// Cells of the grid that marks where regions are: the vertex's cell and its 26 neighbours.
std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
    // note: 21 bits per axis hold ±10^6 cells, 10^4 times the 1 % cells across a mesh.
    constexpr std::int64_t kBias = 1 << 20, kMask = (1 << 21) - 1;
    return (static_cast<std::uint64_t>((x + kBias) & kMask) << 42) |
           (static_cast<std::uint64_t>((y + kBias) & kMask) << 21) |
           static_cast<std::uint64_t>((z + kBias) & kMask);
}

std::string data_uri(const std::string& png) { return "data:image/png;base64," + base64(png); }

// JSON text safe inside <script type="application/json">: "</" (as in "</script>") and the
// HTML comment opener are escaped, which JSON allows ("\/") or leaves equal in meaning.
std::string script_safe(std::string text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '<' && i + 1 < text.size() && (text[i + 1] == '/' || text[i + 1] == '!')) {
            out += "\\u003c";
            continue;
        }
        out += text[i];
    }
    return out;
}

}  // namespace

std::string escape_markup(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string fill_template(std::string_view page_template,
                          const std::vector<std::pair<std::string, std::string>>& values) {
    std::string out;
    std::size_t pos = 0;
    while (pos < page_template.size()) {
        const std::size_t at = page_template.find('@', pos);
        if (at == std::string_view::npos) break;
        std::size_t end = at + 1;
        while (end < page_template.size() &&
               (std::isupper(static_cast<unsigned char>(page_template[end])) ||
                std::isdigit(static_cast<unsigned char>(page_template[end])) ||
                page_template[end] == '_'))
            ++end;
        if (end == at + 1 || end >= page_template.size() || page_template[end] != '@') {
            out.append(page_template.substr(pos, at + 1 - pos));
            pos = at + 1;
            continue;
        }
        const std::string_view name = page_template.substr(at + 1, end - at - 1);
        const auto it = std::find_if(values.begin(), values.end(),
                                     [&](const auto& kv) { return kv.first == name; });
        GLINT_ASSERT(it != values.end(),
                     "report.html template: no value for @" + std::string(name) + "@");
        out.append(page_template.substr(pos, at - pos));
        out.append(it->second);
        pos = end + 1;
    }
    out.append(page_template.substr(std::min(pos, page_template.size())));
    return out;
}

LiveSurface live_examined(const Mesh& fitted, const Mesh& reference, const AnalysisResult& result,
                          std::size_t max_triangles) {
    LiveSurface live;
    live.triangles = fitted.triangle_count();
    if (!fitted.has_normals()) {
        // The normals the renderer made for it (render/renderer.cpp), then as below.
        Mesh with_normals;
        with_normals.positions = fitted.positions;
        with_normals.triangles = fitted.triangles;
        compute_vertex_normals(with_normals);
        return live_examined(with_normals, reference, result, max_triangles);
    }
    if (fitted.triangle_count() <= max_triangles) {
        live.mesh.positions = fitted.positions;
        live.mesh.triangles = fitted.triangles;
        live.mesh.normals = fitted.normals;
        return live;
    }
    // note: cells of 1 % of the size, the decimation's error bound: the examined surface near
    // a region (its dent or bump, a fraction of a cell away from the reference's) falls in a
    // marked cell or a neighbour of one.
    const double cell = std::max(0.01 * result.size, 1e-12);
    const auto index = [&](const Vec3f& p, int axis) {
        return static_cast<std::int64_t>(std::floor(p[axis] / cell));
    };
    std::unordered_set<std::uint64_t> marked;
    for (std::size_t v = 0; v < reference.vertex_count(); ++v) {
        bool in_region = false;
        for (const auto& d : result.decisions) in_region |= d.regions.region_of_vertex[v] != 0;
        if (!in_region) continue;
        const Vec3f& p = reference.positions[v];
        const std::int64_t x = index(p, 0), y = index(p, 1), z = index(p, 2);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy)
                for (std::int64_t dz = -1; dz <= 1; ++dz)
                    marked.insert(cell_key(x + dx, y + dy, z + dz));
    }
    std::vector<std::uint8_t> keep(fitted.triangle_count(), 0);
    if (!marked.empty())
        for (std::size_t t = 0; t < fitted.triangle_count(); ++t)
            for (const auto v : fitted.triangles[t]) {
                const Vec3f& p = fitted.positions[v];
                if (marked.count(cell_key(index(p, 0), index(p, 1), index(p, 2)))) keep[t] = 1;
            }
    DecimatedMesh d = decimate(fitted, max_triangles, keep, 0.01 * result.size);
    live.mesh.positions = std::move(d.mesh.positions);
    live.mesh.triangles = std::move(d.mesh.triangles);
    live.mesh.normals = std::move(d.mesh.normals);
    live.error = d.error;
    return live;
}

struct ReportPageData::Parts {
    json data;  ///< the page's data without "report" and "images"
};

ReportPageData report_page_data(const Mesh& reference_in, const AnalysisResult& result,
                                const LiveSurface* examined, std::size_t max_triangles) {
    // The live view renders the reference with the normals the sweep did: analyse() makes
    // them for a reference without any (analysis/analysis.cpp), and so does the page.
    std::optional<Mesh> with_normals;
    if (!reference_in.has_normals()) {
        with_normals = reference_in;
        compute_vertex_normals(*with_normals);
    }
    const Mesh& reference = with_normals ? *with_normals : reference_in;
    auto parts = std::make_shared<ReportPageData::Parts>();
    json& data = parts->data;
    const ShapeScale scale = shape_scale(result);
    data["unit"] = result.unit.empty() ? "units" : result.unit;
    {
        const ShownMesh shown = shown_mesh(reference, result, max_triangles);
        data["mesh"] = mesh_json(reference, shown);
        data["fields"] = fields_json(shown, result, scale);
    }
    if (examined) data["live"] = live_json(*examined, result);
    // Views by their index as their files are named (views/<name>.png): the region table
    // names each region's best view.
    json view_names = json::array();
    for (const auto& v : result.sweep.plan.views) view_names.push_back(view_file_stem(v.view));
    data["view_names"] = std::move(view_names);
    data["shape_scale"] = {
        {"limit", scale.limit}, {"source", scale.source}, {"floor", scale.floor}};
    const auto knots = detail::diverging_knots();
    data["colormaps"] = {{"diverging", std::vector<float>(knots.begin(), knots.end())},
                         {"sequential", inferno_knots()}};
    return {std::move(parts)};
}

std::string report_html(ReportPageData page, const std::string& report_json,
                        const PictureOutput& pictures) {
    GLINT_ASSERT(page.parts != nullptr, "report_html: no page data");
    json data = std::move(page.parts->data);
    page.parts.reset();
    data["report"] = json::parse(report_json);
    json images = {{"mosaics", json::array()}, {"best_views", json::object()}};
    for (const auto& m : pictures.mosaics) images["mosaics"].push_back(data_uri(m));
    for (const auto& [view, png] : pictures.best_views)
        images["best_views"][std::to_string(view)] = data_uri(png);
    // note: atlas.png inline rather than linked beside the page: a page mailed or copied alone
    // still shows it, and it costs ~0.1–0.3 MB whatever the mesh size (a fixed-size picture).
    if (!pictures.atlas.empty()) images["atlas"] = data_uri(pictures.atlas);
    data["images"] = std::move(images);
    std::string title = "glint report";
    for (const auto& in : data["report"]["inputs"])
        if (in.value("role", "") == "reference" && in.contains("path"))
            title +=
                ": " + std::filesystem::path(in["path"].get<std::string>()).filename().string();
    const std::string asymmetry = asymmetry_section_html(data["report"]);
    return fill_template(asset("report.html.in"), {{"TITLE", escape_markup(title)},
                                                   {"THREE_JS", asset("three.min.js")},
                                                   {"ORBIT_CONTROLS_JS", asset("OrbitControls.js")},
                                                   {"DATA_JSON", script_safe(json_text(data))},
                                                   {"LIVE_JS", asset("live.js")},
                                                   {"EVIDENCE_JS", asset("evidence.js")},
                                                   {"OVERLAYS_JS", asset("overlays.js")},
                                                   {"REPORT_JS", asset("report.js")},
                                                   {"GLINT_CSS", asset("glint.css")},
                                                   {"REPORT_CSS", asset("report.css")},
                                                   {"ASYMMETRY_SECTION", asymmetry}});
}

std::string report_html(const Mesh& reference, const AnalysisResult& result,
                        const LiveSurface* examined, const std::string& report_json,
                        const PictureOutput& pictures, std::size_t max_triangles) {
    return report_html(report_page_data(reference, result, examined, max_triangles), report_json,
                       pictures);
}

}  // namespace glint
