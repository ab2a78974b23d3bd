// report.html (report/report_html.h): one self-contained page; its data holds the mesh and
// the atlas fields exactly, the regions' best views and the mosaic; nothing points outside
// the file. (The page itself runs in headless Chromium: tests/tools/report_html_test.sh.)
#include "report/report_html.h"
#include "report/inspect.h"

#include "analysis/asymmetry.h"
#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "report/asymmetry_json.h"
#include "report/detail/legend.h"
#include "report/detail/symmetry_plane_trace.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/strutil.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <sstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

TEST(FillTemplate, ReplacesEveryNameOnceAndNeverScansWhatItInserted) {
    EXPECT_EQ(fill_template("a @X@ b @Y_2@ c @x@ d@", {{"X", "@Y_2@"}, {"Y_2", "2"}}),
              "a @Y_2@ b 2 c @x@ d@");
    EXPECT_EQ(fill_template("e-mail a@b.c and @@", {}), "e-mail a@b.c and @@");
    EXPECT_THROW((void)fill_template("@MISSING@", {{"X", "1"}}), std::logic_error);
}

std::string read_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// The JSON data block of the page.
nlohmann::json page_data(const std::string& html) {
    const std::string open = "<script id=\"glint-data\" type=\"application/json\">";
    const auto a = html.find(open);
    const auto b = html.find("</script>", a);
    EXPECT_NE(a, std::string::npos);
    return nlohmann::json::parse(html.substr(a + open.size(), b - a - open.size()));
}

// Standard base64 (RFC 4648), as the page's atob() reads it.
std::string base64_decode(const std::string& text) {
    static const std::string alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    unsigned bits = 0;
    int count = 0;
    for (char c : text) {
        if (c == '=') break;
        const auto k = alphabet.find(c);
        if (k == std::string::npos) ADD_FAILURE() << "not base64: " << c;
        bits = (bits << 6) | static_cast<unsigned>(k);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out += static_cast<char>((bits >> count) & 0xFF);
        }
    }
    return out;
}

template <typename T>
std::vector<T> decode(const std::string& b64) {
    const std::string bytes = base64_decode(b64);
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    EXPECT_EQ(bytes.size() % sizeof(T), 0u);
    return out;
}

// Pixels of a PNG file in the symmetry plane's colour (report/detail/symmetry_plane_trace.h),
// left of column `max_x` (a picture's legend, on its right, has a swatch of that colour).
int plane_coloured_pixels(const fs::path& png, int max_x = std::numeric_limits<int>::max()) {
    OIIO::ImageBuf image(png.string());
    EXPECT_TRUE(image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << png;
    int n = 0;
    const OIIO::ROI roi = image.roi();
    for (int y = roi.ybegin; y < roi.yend; ++y)
        for (int x = roi.xbegin; x < std::min(roi.xend, max_x); ++x) {
            float p[3];
            image.getpixel(x, y, p, 3);
            bool same = true;
            for (int k = 0; k < 3; ++k)
                same &= std::abs(p[k] - detail::kSymmetryPlane[static_cast<std::size_t>(k)]) <
                        1.5f / 255;
            n += same;
        }
    return n;
}

TEST(ReportHtml, IsOneSelfContainedFileHoldingTheAtlasExactly) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "report_html";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Mesh ref = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    Mesh exa = ref;
    apply_damage(
        exa,
        {DamageSpec{.kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.5},
         DamageSpec{.kind = DamageKind::Bump, .center = {0, 0, 10}, .radius = 3.0, .depth = 0.4}});
    InspectOptions inspect_options;
    AnalysisOptions& options = inspect_options.analysis;
    options.fit.mode = FitMode::Identity;
    options.sweep.plan.azimuth_step_deg = 90;
    options.sweep.plan.elevations_deg = {-30, 30};
    options.sweep.plan.size = 64;
    options.sweep.render.backend = Backend::Embree;
    options.units.unit = "mm";
    inspect_options.exports.output = dir / "atlas";
    inspect_options.exports.write_views = false;  // the page still gets the best views
    const AnalysisResult result = inspect(ref, exa, inspect_options, {}).analysis;
    const std::string html = read_text(dir / "atlas" / "report.html");

    // Self-contained: no element loads anything; the libraries are inline.
    // (the markup without the scripts' text; std::regex would recurse through 1 MB of script)
    std::string markup;
    for (std::size_t pos = 0; pos < html.size();) {
        const auto open = html.find("<script", pos);
        const auto body = open == std::string::npos ? open : html.find('>', open);
        markup += html.substr(pos, body == std::string::npos ? std::string::npos : body + 1 - pos);
        if (body == std::string::npos) break;
        pos = html.find("</script>", body);
        ASSERT_NE(pos, std::string::npos) << "unclosed <script>";
    }
    EXPECT_FALSE(std::regex_search(
        markup, std::regex("<(script|link|img|iframe)\\b[^>]*\\s(src|href)\\s*=")));
    EXPECT_NE(html.find("REVISION=\"111\""), std::string::npos) << "three.js inlined";
    EXPECT_NE(html.find("THREE.OrbitControls"), std::string::npos) << "OrbitControls inlined";
    EXPECT_NE(html.find("window.glintSelftest"), std::string::npos) << "report.js inlined";

    const nlohmann::json data = page_data(html);
    EXPECT_EQ(data["unit"], "mm");
    EXPECT_EQ(data["report"]["zooms"].size(), 1u);
    const auto positions = decode<float>(data["mesh"]["positions"]);
    const auto indices = decode<std::uint32_t>(data["mesh"]["indices"]);
    ASSERT_EQ(positions.size(), 3 * ref.vertex_count());
    ASSERT_EQ(indices.size(), 3 * ref.triangle_count());
    EXPECT_EQ(positions[3 * 17 + 2], ref.positions[17].z());
    EXPECT_EQ(indices[3 * 5 + 1], ref.triangles[5][1]);
    std::map<std::string, nlohmann::json> fields;
    for (const auto& f : data["fields"]) fields[f["name"]] = f;
    for (const char* name : {"shape_change_mm", "angle_mean_deg_z0", "angle_max_deg_z0",
                             "region_id_z0", "seen_z0", "pixels_z0"})
        ASSERT_TRUE(fields.count(name)) << name;
    const auto distance = decode<float>(fields["shape_change_mm"]["values"]);
    ASSERT_EQ(distance.size(), ref.vertex_count());
    for (std::size_t v = 0; v < distance.size(); v += 97)
        EXPECT_EQ(distance[v], result.distance[v]);
    const auto region = decode<float>(fields["region_id_z0"]["values"]);
    for (std::size_t v = 0; v < region.size(); ++v)
        ASSERT_EQ(region[v], static_cast<float>(result.decisions[0].regions.region_of_vertex[v]));
    EXPECT_EQ(fields["shape_change_mm"]["range"][0].get<double>(),
              -fields["shape_change_mm"]["range"][1].get<double>());
    // The sweep's vertex normals, int16 scaled by 32767 (the live view renders with them).
    const auto normals = decode<std::int16_t>(data["mesh"]["normals"]);
    ASSERT_EQ(normals.size(), 3 * ref.vertex_count());
    for (std::size_t v = 0; v < ref.vertex_count(); v += 53)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(normals[3 * v + c] / 32767.0, ref.normals[v][c], 1.0 / 32767);

    // The live view's examined surface: the fitted one (here the identity fit), whole, with its
    // normals, and how the sweep averaged and compared.
    ASSERT_TRUE(data.contains("live"));
    const auto& live = data["live"];
    EXPECT_EQ(live["supersample"].get<int>(), result.sweep.options.render.supersample);
    EXPECT_FLOAT_EQ(live["min_coverage"].get<float>(), result.sweep.options.compare.min_coverage);
    EXPECT_EQ(live["examined"]["triangles"].get<std::size_t>(), exa.triangle_count());
    EXPECT_EQ(live["examined"]["shown_triangles"].get<std::size_t>(), exa.triangle_count());
    const auto exa_positions = decode<float>(live["examined"]["positions"]);
    const auto exa_indices = decode<std::uint32_t>(live["examined"]["indices"]);
    const auto exa_normals = decode<std::int16_t>(live["examined"]["normals"]);
    ASSERT_EQ(exa_positions.size(), 3 * exa.vertex_count());
    ASSERT_EQ(exa_normals.size(), 3 * exa.vertex_count());
    ASSERT_EQ(exa_indices.size(), 3 * exa.triangle_count());
    for (std::size_t v = 0; v < exa.vertex_count(); v += 41)
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(exa_positions[3 * v + c], exa.positions[v][c]);
            EXPECT_NEAR(exa_normals[3 * v + c] / 32767.0, exa.normals[v][c], 1.0 / 32767);
        }
    EXPECT_EQ(data["colormaps"]["diverging"].size(), 27u);

    // The pictures: the mosaic and every region's best view, as PNG data URIs.
    ASSERT_EQ(data["images"]["mosaics"].size(), 1u);
    EXPECT_EQ(data["images"]["mosaics"][0].get<std::string>().rfind(
                  "data:image/png;base64,iVBORw0KGgo", 0),
              0u);
    ASSERT_EQ(result.decisions[0].regions.regions.size(), 2u);
    for (const auto& r : result.decisions[0].regions.regions)
        EXPECT_TRUE(data["images"]["best_views"].contains(std::to_string(r.best_view)))
            << "region " << r.id;
    EXPECT_FALSE(fs::exists(dir / "atlas" / "views" / "z0_az000.0_el-30.0.png"))
        << "--no-views writes no view";
    // atlas.png inline, byte for byte the file beside the page (the page may travel alone).
    const std::string atlas_uri = data["images"]["atlas"].get<std::string>();
    const std::string png_prefix = "data:image/png;base64,";
    ASSERT_EQ(atlas_uri.rfind(png_prefix, 0), 0u);
    EXPECT_EQ(atlas_uri.substr(png_prefix.size()),
              OIIO::Strutil::base64_encode(read_text(dir / "atlas" / "atlas.png")));
    // Each view named as its files are (views/<name>.png): the region table shows the best one.
    ASSERT_EQ(data["view_names"].size(), result.sweep.plan.views.size());
    for (const auto& r : result.decisions[0].regions.regions)
        EXPECT_EQ(
            data["view_names"][static_cast<std::size_t>(r.best_view)].get<std::string>(),
            view_file_stem(result.sweep.plan.views[static_cast<std::size_t>(r.best_view)].view));
    EXPECT_EQ(data["view_names"][0].get<std::string>(), "z0_az000.0_el-30.0");
    // The page style is glint.css whole, the one cohort.html inlines too
    // (workflows/cohort/summary_html.py), and the page's scripts are all inline.
    const std::string style =
        read_text(fs::path(GLINT_TEST_DATA_DIR) / ".." / ".." / "report" / "html" / "glint.css");
    ASSERT_GT(style.size(), 100u);
    EXPECT_NE(html.find(style), std::string::npos) << "glint.css inlined";
    EXPECT_NE(html.find("window.glintEvidence"), std::string::npos) << "evidence.js inlined";
    EXPECT_NE(html.find("window.glintOverlays"), std::string::npos) << "overlays.js inlined";
    // A sweep's page and atlas have no asymmetry: no section, no plane drawn.
    EXPECT_EQ(html.find("id=\"asymmetry-panel\""), std::string::npos);
    EXPECT_EQ(plane_coloured_pixels(dir / "atlas" / "atlas.png"), 0);
    // Bounded: the libraries (~0.9 MB) plus the data, nothing per view beyond the best ones.
    EXPECT_LT(html.size(), 4'000'000u);

    // A mesh above the page's budget is shown decimated: every triangle touching a region kept,
    // the rest collapsed; every vertex shown is an atlas vertex at its place, with its values.
    const std::size_t budget = ref.triangle_count() / 8;
    const nlohmann::json small = page_data(
        report_html(ref, result, nullptr, read_text(dir / "atlas" / "report.json"), {}, budget));
    EXPECT_EQ(small["mesh"]["triangles"].get<std::size_t>(), ref.triangle_count());
    const auto ids = decode<std::uint32_t>(small["mesh"]["vertex_ids"]);
    const auto shown_positions = decode<float>(small["mesh"]["positions"]);
    const auto shown_indices = decode<std::uint32_t>(small["mesh"]["indices"]);
    ASSERT_EQ(shown_positions.size(), 3 * ids.size());
    std::size_t region_triangles = 0;
    for (const auto& t : ref.triangles)
        region_triangles += result.decisions[0].regions.region_of_vertex[t[0]] != 0 ||
                            result.decisions[0].regions.region_of_vertex[t[1]] != 0 ||
                            result.decisions[0].regions.region_of_vertex[t[2]] != 0;
    EXPECT_LT(shown_indices.size() / 3, budget + region_triangles + budget / 2);
    EXPECT_EQ(small["mesh"]["shown"]["triangles"].get<std::size_t>(), shown_indices.size() / 3);
    std::map<std::string, nlohmann::json> small_fields;
    for (const auto& f : small["fields"]) small_fields[f["name"]] = f;
    const auto shown_distance = decode<float>(small_fields["shape_change_mm"]["values"]);
    const auto shown_region = decode<float>(small_fields["region_id_z0"]["values"]);
    ASSERT_EQ(shown_distance.size(), ids.size());
    std::vector<std::uint8_t> is_shown(ref.vertex_count(), 0);
    for (std::size_t k = 0; k < ids.size(); ++k) {
        ASSERT_LT(ids[k], ref.vertex_count());
        is_shown[ids[k]] = 1;
        EXPECT_EQ(shown_positions[3 * k], ref.positions[ids[k]].x());
        EXPECT_EQ(shown_distance[k], result.distance[ids[k]]);
        EXPECT_EQ(shown_region[k],
                  static_cast<float>(result.decisions[0].regions.region_of_vertex[ids[k]]));
    }
    for (std::size_t v = 0; v < ref.vertex_count(); ++v)
        if (result.decisions[0].regions.region_of_vertex[v] != 0) {
            EXPECT_TRUE(is_shown[v]) << "region vertex " << v;
        }
}

// Above the budget the live view's examined surface is decimated: at most about the budget
// beyond the triangles kept near the regions, every vertex one of the fitted mesh's with its
// normal, and the dent (the region's surface on the examined side) kept whole. Surfaces given
// without normals get the ones the sweep rendered with.
TEST(ReportHtml, LiveExaminedSurfaceIsDecimatedAboveTheBudgetKeepingTheDamage) {
    const Mesh ref = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 5});
    Mesh exa = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Uv, .resolution = 80});
    const DamageSpec dent{
        .kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.6};
    apply_damage(exa, {dent});
    InspectOptions inspect_options;
    AnalysisOptions& options = inspect_options.analysis;
    options.fit.mode = FitMode::Identity;
    options.sweep.plan.azimuth_step_deg = 90;
    options.sweep.plan.elevations_deg = {0};
    options.sweep.plan.size = 96;
    options.sweep.render.backend = Backend::Embree;
    const AnalysisResult result = inspect(ref, exa, inspect_options, {}).analysis;
    ASSERT_FALSE(result.decisions.empty());
    ASSERT_FALSE(result.decisions[0].regions.regions.empty()) << "the dent is a region";

    const LiveSurface whole = live_examined(exa, ref, result);
    EXPECT_FALSE(whole.is_decimated());
    EXPECT_EQ(whole.mesh.positions, exa.positions);
    EXPECT_EQ(whole.mesh.normals, exa.normals);

    const std::size_t budget = exa.triangle_count() / 8;
    const LiveSurface live = live_examined(exa, ref, result, budget);
    ASSERT_TRUE(live.is_decimated());
    EXPECT_EQ(live.triangles, exa.triangle_count());
    EXPECT_GT(live.error, 0.0);
    ASSERT_TRUE(live.mesh.has_normals());
    std::map<std::array<float, 3>, std::size_t> vertex_at;
    for (std::size_t v = 0; v < exa.vertex_count(); ++v)
        vertex_at[{exa.positions[v].x(), exa.positions[v].y(), exa.positions[v].z()}] = v;
    std::vector<std::uint8_t> shown(exa.vertex_count(), 0);
    for (std::size_t k = 0; k < live.mesh.vertex_count(); ++k) {
        const Vec3f& p = live.mesh.positions[k];
        const auto it = vertex_at.find({p.x(), p.y(), p.z()});
        ASSERT_NE(it, vertex_at.end()) << "vertex " << k << " is not one of the fitted mesh's";
        EXPECT_EQ(live.mesh.normals[k], exa.normals[it->second]) << "the sweep's normal";
        shown[it->second] = 1;
    }
    std::size_t in_dent = 0;
    for (std::size_t v = 0; v < exa.vertex_count(); ++v)
        if ((exa.positions[v].cast<double>() - dent.center).norm() < 0.9 * dent.radius) {
            ++in_dent;
            EXPECT_TRUE(shown[v]) << "dent vertex " << v << " was collapsed";
        }
    EXPECT_GT(in_dent, 50u);

    // Meshes without normals get those the renderer and analyse() make (angle-weighted).
    Mesh bare_exa{.positions = exa.positions, .triangles = exa.triangles};
    const LiveSurface made = live_examined(bare_exa, ref, result);
    ASSERT_TRUE(made.mesh.has_normals());
    for (std::size_t v = 0; v < exa.vertex_count(); v += 97)
        EXPECT_LT((made.mesh.normals[v] - exa.normals[v]).norm(), 1e-5f) << "vertex " << v;
    const Mesh bare_ref{.positions = ref.positions, .triangles = ref.triangles};
    const nlohmann::json page = page_data(report_html(bare_ref, result, nullptr, "{}", {}));
    const auto ref_normals = decode<std::int16_t>(page["mesh"]["normals"]);
    ASSERT_EQ(ref_normals.size(), 3 * ref.vertex_count());
    for (std::size_t v = 0; v < ref.vertex_count(); v += 97)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ref_normals[3 * v + c] / 32767.0, ref.normals[v][c], 2.0 / 32767);
    EXPECT_LT(live.mesh.triangle_count(), budget + 6 * in_dent + budget / 2);
    EXPECT_LT(live.mesh.triangle_count(), exa.triangle_count() / 2);
}

// glint asymmetry's outputs (issue 27): a sphere dented at +x against its mirror about x = 0.
// Every output gives the +x side "less", as the finding does: report.json's regions,
// regions.csv and the legend's words; atlas.png draws the plane; report.html's asymmetry
// section holds the plane and one row per finding, as report.json's "asymmetry".
TEST(ReportHtml, AsymmetrySectionAndOutputsSpeakOfTheFinding) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "report_html_asymmetry";
    fs::remove_all(dir);
    fs::create_directories(dir);
    Mesh surface = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    apply_damage(
        surface,
        {DamageSpec{.kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.5}});
    AsymmetryOptions asymmetry{.given_plane = SymmetryPlane{.normal = {1, 0, 0}, .offset = 0.0}};
    AsymmetryPlane plane = prepare_asymmetry(surface, asymmetry);
    ASSERT_FALSE(plane.mirror.triangles.empty());
    InspectOptions inspect_options;
    AnalysisOptions& options = inspect_options.analysis;
    options.fit.mode = FitMode::Identity;
    options.sweep.plan.azimuth_step_deg = 90;
    options.sweep.plan.elevations_deg = {-30, 30};
    options.sweep.plan.size = 64;
    options.sweep.render.backend = Backend::Embree;
    options.units.unit = "mm";
    inspect_options.exports.output = dir / "out";
    inspect_options.exports.write_views = true;
    inspect_options.addition = [&](const AnalysisResult& r) {
        const AsymmetryFindings f = pair_findings(surface, plane.plane.plane, r);
        return ReportAddition{.key = "asymmetry",
                              .json = asymmetry_json(plane.plane, f, Orientation{}, r.unit),
                              .mirror = mirror_pictures(plane.plane)};
    };
    const Inspection run = inspect(surface, plane.mirror, inspect_options, {});
    const nlohmann::json report = nlohmann::json::parse(read_text(dir / "out" / "report.json"));
    const nlohmann::json& findings = report["asymmetry"]["findings"];
    ASSERT_EQ(findings.size(), 1u) << report["asymmetry"].dump(1);
    const nlohmann::json& f = findings[0];
    EXPECT_EQ(f["side"], "+x");
    EXPECT_EQ(f["kind"], "less");
    EXPECT_LT(f["depth"].get<double>(), -0.2);

    // The finding's region in report.json, regions.csv and the legend: a dent, less.
    const int id = f["region"].get<int>();
    bool found = false;
    for (const auto& r : report["zooms"][0]["regions"])
        if (r["id"].get<int>() == id) {
            found = true;
            EXPECT_EQ(r["kind"], "dent");
            EXPECT_EQ(r["evidence"].get<std::string>().rfind("shape change -", 0), 0u)
                << r["evidence"];
            EXPECT_NEAR(r["peak_depth"].get<double>(), f["depth"].get<double>(), 1e-9);
        } else if (r["id"].get<int>() == f["mirror_region"].get<int>()) {
            EXPECT_EQ(r["kind"], "bump") << "the mirror image of the dent";
        }
    EXPECT_TRUE(found);
    EXPECT_TRUE(std::regex_search(read_text(dir / "out" / "regions.csv"),
                                  std::regex("\\n0,[^,]+," + std::to_string(id) + ",dent,")));
    for (const auto& r : run.analysis.decisions[0].regions.regions) {
        if (r.id == id) {
            EXPECT_NE(detail::region_legend_line(r, "mm", true).find("  less  \u2212"),
                      std::string::npos);
        }
    }

    // atlas.png draws the plane (the x = 0 line of the panels from ±y, ±z, which see it
    // edge-on, and its trace on the sphere).
    EXPECT_GT(plane_coloured_pixels(dir / "out" / "atlas.png"), 4 * 200);
    // So do the per-view pictures and the mosaic's tiles (the trace on the sphere, the line
    // across a view that sees the plane edge-on), left of their legends.
    int in_views = 0;
    for (const auto& file : fs::directory_iterator(dir / "out" / "views"))
        if (file.path().extension() == ".png") {
            const int n = plane_coloured_pixels(file.path(), 300);
            EXPECT_GT(n, 50) << file.path() << ": no symmetry plane drawn";
            in_views += n;
        }
    EXPECT_GT(in_views, 8 * 150);
    EXPECT_GT(plane_coloured_pixels(dir / "out" / "mosaic_z0.png", 240), 100);

    // report.html: the section with the plane, the caveat, and one row per finding.
    const std::string html = read_text(dir / "out" / "report.html");
    const auto begin = html.find("<section id=\"asymmetry-panel\">");
    ASSERT_NE(begin, std::string::npos);
    const std::string section = html.substr(begin, html.find("</section>", begin) - begin);
    const nlohmann::json& p = report["asymmetry"]["plane"];
    EXPECT_NE(section.find(p["residual_text"].get<std::string>()), std::string::npos);
    EXPECT_NE(section.find("normal</th><td>(1, 0, 0)"), std::string::npos) << section;
    EXPECT_NE(section.find(escape_markup(std::string(kOneScanCaveat))), std::string::npos);
    // The floor in report.json's words (the terminal prints the same): its spread and the
    // smallest one-sided change that can be told from it.
    const nlohmann::json& floor = report["asymmetry"]["symmetry_floor"];
    ASSERT_TRUE(floor.contains("min_detectable_text")) << floor.dump(1);
    EXPECT_EQ(floor["spread_text"].get<std::string>().rfind("|asymmetry| RMS ", 0), 0u);
    EXPECT_NE(section.find(escape_markup(floor["spread_text"].get<std::string>())),
              std::string::npos);
    EXPECT_NE(section.find(escape_markup("can be told from it: " +
                                         floor["min_detectable_text"].get<std::string>())),
              std::string::npos)
        << section;
    const std::regex row(
        "<tr data-finding=\"(\\d+)\" data-region=\"(\\d+)\"><td>([^<]*)</td><td>([^<]*)</td>"
        "<td>([^<]*)</td><td>([^<]*)</td><td>([^<]*)</td><td>([^<]*)</td></tr>");
    std::size_t rows = 0;
    for (auto it = std::sregex_iterator(section.begin(), section.end(), row);
         it != std::sregex_iterator(); ++it, ++rows) {
        const auto& m = *it;
        const nlohmann::json& g = findings[std::stoul(m[1].str())];
        EXPECT_EQ(std::stoi(m[2].str()), g["region"].get<int>());
        EXPECT_EQ(m[3].str(), g["side"].get<std::string>());
        EXPECT_EQ(m[4].str(), g["kind"].get<std::string>());
        EXPECT_NEAR(std::stod(m[5].str()), g["depth"].get<double>(), 1e-3);
        EXPECT_NEAR(std::stod(m[6].str()), g["area"].get<double>(), 1e-3 * g["area"].get<double>());
        EXPECT_NEAR(std::stod(m[7].str()), g["volume"].get<double>(),
                    1e-3 * std::abs(g["volume"].get<double>()));
        EXPECT_EQ(m[8].str(), escape_markup(g["text"].get<std::string>()));
    }
    EXPECT_EQ(rows, findings.size());
    EXPECT_NE(section.find("depth (mm)"), std::string::npos);
}

}  // namespace
}  // namespace glint
