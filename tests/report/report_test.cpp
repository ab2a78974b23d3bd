// What a sweep writes into its output folder (report/report.h): every file a user opens is
// there, and report.json holds what the README promises — inputs with checksums, device and
// backend, the plan and analysis options (enough to repeat the run), thresholds, coverage,
// unseen patches, regions, histogram and timings.
#include "report/report.h"

#include "report/atlas_fields.h"

#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/phantom.h"
#include "mesh/units.h"
#include "mesh/write.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

TEST(SweepReport, WritesEveryPromisedFileAndAReportThatRepeatsTheRun) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "report";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Mesh ref = make_phantom(
        {.kind = PhantomKind::Sphere, .scheme = TessellationScheme::Ico, .resolution = 4});
    Mesh exa = ref;
    apply_damage(
        exa,
        {DamageSpec{.kind = DamageKind::Dent, .center = {10, 0, 0}, .radius = 3.0, .depth = 0.5}});
    write_ply(ref, dir / "ref.ply");

    InspectOptions options;
    AnalysisOptions& a = options.analysis;
    a.fit.mode = FitMode::Identity;
    a.sweep.plan.azimuth_step_deg = 45;
    a.sweep.plan.elevations_deg = {-30, 30};
    a.sweep.plan.size = 48;
    a.sweep.render.backend = Backend::Embree;
    a.sweep.render.supersample = 2;
    a.sweep.max_incidence_deg = 70.0;
    options.exports.output = dir / "atlas";
    options.exports.write_exr = true;
    options.exports.write_views = true;
    RunRecord record{.command_line = "glint sweep ref.ply exa.ply -o atlas --exr"};
    record.add(mesh_run_input("reference", ref, "", dir / "ref.ply"));
    // A scenario's ground truth rides along into the atlas files, beside glint's own fields.
    std::vector<float> truth(ref.vertex_count());
    for (std::size_t v = 0; v < truth.size(); ++v) truth[v] = static_cast<float>(exa.labels[v]);
    options.exports.extra_scalars.emplace_back("truth_damage", truth);
    const Inspection result = inspect(ref, exa, options, record);
    EXPECT_EQ(result.output, dir / "atlas");
    for (const char* f :
         {"atlas.ply", "atlas.vtp", "regions.csv", "report.json", "report.html", "atlas.png",
          "mosaic_z0.png", "views/z0_az000.0_el-30.0.png", "views/z0_az000.0_el-30.0.exr"})
        EXPECT_TRUE(fs::exists(dir / "atlas" / f)) << f;

    const Mesh atlas = load_mesh(dir / "atlas" / "atlas.ply").mesh;
    const auto* truth_read = atlas.find_scalar("truth_damage");
    ASSERT_NE(truth_read, nullptr);
    EXPECT_EQ(truth_read->values, truth);
    // The decision field first, named with its unit, and MeshLab's quality the same values; no
    // field holds NaN (unseen is 0 with seen_z0 = 0: report/atlas_fields.h).
    ASSERT_FALSE(atlas.scalars.empty());
    EXPECT_EQ(atlas.scalars.front().name, shape_change_field(atlas.unit));
    ASSERT_NE(atlas.find_scalar("quality"), nullptr);
    EXPECT_EQ(atlas.find_scalar("quality")->values, atlas.scalars.front().values);
    for (const auto& f : atlas.scalars)
        for (float x : f.values) ASSERT_TRUE(std::isfinite(x)) << f.name;
    EXPECT_EQ(atlas.find_scalar("depth_z0"), nullptr);  // the view-ray depth misled: dropped

    std::ifstream in(dir / "atlas" / "report.json");
    const nlohmann::json r = nlohmann::json::parse(in);
    EXPECT_EQ(r["command_line"], record.command_line);
    // --json prints the text inspect() made once; the file holds the same.
    EXPECT_EQ(r, nlohmann::json::parse(result.report_json));
    ASSERT_EQ(r["inputs"].size(), 1u);
    EXPECT_EQ(r["inputs"][0]["sha256"], sha256_file(dir / "ref.ply"));
    EXPECT_EQ(r["inputs"][0]["sha256"].get<std::string>().size(), 64u);
    EXPECT_EQ(r["device"]["backend"], "embree");
    EXPECT_FALSE(r["device"]["name"].get<std::string>().empty());
    const auto& sweep = r["analysis"]["sweep"];
    EXPECT_EQ(sweep["plan"], "rotary");
    EXPECT_EQ(r["plan"]["views"], 16);
    EXPECT_EQ(sweep["elevations"], nlohmann::json({-30.0, 30.0}));
    EXPECT_EQ(sweep["supersample"], 2);
    EXPECT_EQ(sweep["backend"], "embree");
    EXPECT_DOUBLE_EQ(sweep["max_incidence"].get<double>(), 70.0);
    EXPECT_TRUE(r["analysis"]["threshold"]["deg"].is_null());  // the noise floor decided
    EXPECT_EQ(r["analysis"]["registration"]["mode"], "identity");
    EXPECT_EQ(r["metric"]["name"], "angle");
    ASSERT_EQ(r["zooms"].size(), 1u);
    const auto& z = r["zooms"][0];
    EXPECT_GT(z["threshold_deg"].get<double>(), 0.0);
    EXPECT_EQ(z["normal_floor"]["value"], z["threshold_deg"]);
    EXPECT_FALSE(z["normal_floor"]["rule"].get<std::string>().empty());
    EXPECT_FALSE(z["rule_text"].get<std::string>().empty());
    EXPECT_GT(z["coverage"].get<double>(), 0.5);
    ASSERT_EQ(z["regions"].size(), 1u) << z["regions"].dump();
    EXPECT_EQ(z["regions"][0]["kind"], "dent");
    // The histogram counts every seen vertex once.
    const auto counts = z["histogram"]["counts"].get<std::vector<std::size_t>>();
    EXPECT_GT(std::accumulate(counts.begin(), counts.end(), std::size_t{0}),
              ref.vertex_count() / 2);
    EXPECT_EQ(r["views"].size(), 16u);
    EXPECT_GT(r["timings_s"]["sweep_total"].get<double>(), 0.0);
    EXPECT_LT(z["regions"][0]["peak_depth"].get<double>(), 0.0);
    EXPECT_LT(z["regions"][0]["volume"].get<double>(), 0.0);
    EXPECT_FALSE(z["regions"][0].contains("depth_note"));

    // The same region as "missing surface": its area and kind, no depth or volume.
    AnalysisResult missing = result.analysis;
    missing.decisions[0].regions.regions[0].kind = RegionKind::MissingSurface;
    const nlohmann::json m = nlohmann::json::parse(report_json(ref, missing, options, record));
    const auto& region = m["zooms"][0]["regions"][0];
    EXPECT_EQ(region["kind"], "missing surface");
    EXPECT_GT(region["area"].get<double>(), 0.0);
    for (const char* key : {"peak_depth", "mean_depth", "volume"})
        EXPECT_TRUE(region[key].is_null()) << key;
    EXPECT_EQ(region["depth_note"], std::string(kMissingSurfaceNote));

    // The same region as a dent in a hole (surface gone): its depth a lower bound, said so.
    AnalysisResult hole = result.analysis;
    hole.decisions[0].regions.regions[0].hole = true;
    const nlohmann::json h = nlohmann::json::parse(report_json(ref, hole, options, record));
    const auto& lost = h["zooms"][0]["regions"][0];
    EXPECT_EQ(lost["kind"], "dent");
    EXPECT_LT(lost["peak_depth"].get<double>(), 0.0);
    EXPECT_EQ(lost["depth_note"], std::string(kHoleLossNote));
    EXPECT_TRUE(h["zooms"][0]["comparison"]["holes"].contains("losses"));
    // Its atlas field and colours give the depth gone, as atlas.png paints it, not the distance
    // to the hole's rim (which may be positive: a worn cusp read as a gain in a viewer).
    Comparison& hc = hole.decisions[0].comparison;
    const std::size_t n = ref.vertex_count();
    hc.in_hole.assign(n, 0);
    hc.hole_depth.assign(n, std::numeric_limits<float>::quiet_NaN());
    hc.hole_loss.assign(n, 0);
    std::size_t worn = 0;
    while (!hole.sweep.zooms[0].coverage.seen[worn]) ++worn;
    hc.in_hole[worn] = 1;
    hc.hole_depth[worn] = -0.6f;
    hc.hole_loss[worn] = 1;
    hole.distance[worn] = 0.35f;
    const Mesh holed = make_atlas_mesh(ref, hole);
    const auto& shape = holed.scalars.front();
    EXPECT_EQ(shape.name, shape_change_field(hole.unit));
    EXPECT_FLOAT_EQ(shape.values[worn], -0.6f);
    for (std::size_t v = 0; v < n; v += 41) {
        if (v == worn) continue;
        EXPECT_EQ(shape.values[v], std::isfinite(hole.distance[v]) ? hole.distance[v] : 0.0f);
    }
    EXPECT_GT(holed.colors[worn][2], holed.colors[worn][0]);  // blue (loss), not red

    // regions.csv says the same: the dent's depths and volume as numbers, the missing surface's
    // cells empty (peak_depth, mean_depth, volume are the 10th to 12th columns).
    const auto cells = [](const std::string& csv) {
        std::istringstream lines(csv);
        std::string header, row;
        std::getline(lines, header);
        std::getline(lines, row);
        std::vector<std::string> out;
        std::istringstream fields(row);
        for (std::string f; std::getline(fields, f, ',');) out.push_back(f);
        return std::make_pair(header, out);
    };
    const auto [header, dent_row] = cells(regions_csv(result.analysis));
    const std::string& unit = result.analysis.unit;
    EXPECT_NE(header.find(",peak_depth" + unit_suffix(unit) + ",mean_depth" + unit_suffix(unit) +
                          ",volume" + unit_suffix(unit, 3) + ","),
              std::string::npos)
        << header;
    ASSERT_GE(dent_row.size(), 12u);
    EXPECT_LT(std::stod(dent_row[9]), 0.0);
    EXPECT_LT(std::stod(dent_row[11]), 0.0);
    const auto missing_row = cells(regions_csv(missing)).second;
    ASSERT_GE(missing_row.size(), 12u);
    EXPECT_EQ(missing_row[3], "missing surface");
    for (std::size_t c : {9u, 10u, 11u}) EXPECT_TRUE(missing_row[c].empty()) << c;
    // Its significance, then the radius its evidence was read over, close the row: empty
    // where no significance was stated, z and p where it was; 0 for each vertex's own scale.
    EXPECT_NE(header.rfind(",z,p_value,scale_radius" + unit_suffix(unit)), std::string::npos)
        << header;
    AnalysisResult stated = result.analysis;
    Region& first = stated.decisions[0].regions.regions[0];
    first.z = 9.25;
    first.p_value = 3e-16;
    first.scale_radius = 2.5;
    const std::string stated_csv = regions_csv(stated);
    EXPECT_NE(stated_csv.find(",9.25,3e-16,2.5\n"), std::string::npos) << stated_csv;
    const std::string plain_csv = regions_csv(missing);
    EXPECT_EQ(plain_csv.substr(plain_csv.size() - 5), ",,,0\n") << plain_csv;
    // A loss in a hole is named as report.json names it, not "dent".
    AnalysisResult gone = result.analysis;
    gone.decisions[0].regions.regions[0].kind = RegionKind::Dent;
    gone.decisions[0].regions.regions[0].hole = true;
    EXPECT_EQ(cells(regions_csv(gone)).second[3], "surface gone");
    // The evidence sentence names the unit of its lengths.
    EXPECT_NE(z["regions"][0]["evidence"].get<std::string>().find(
                  " " + (unit.empty() ? std::string("units") : unit)),
              std::string::npos)
        << z["regions"][0]["evidence"];
}

// --atlas-formats / ExportOptions::atlas_files: a list of the three names, each at most once.
TEST(AtlasFiles, ParsesAListAndRefusesUnknownRepeatedAndEmpty) {
    const AtlasFiles two = parse_atlas_files("vtp,ply", "--atlas-formats");
    EXPECT_TRUE(two.ply);
    EXPECT_FALSE(two.vtk);
    EXPECT_TRUE(two.vtp);
    EXPECT_EQ(to_string(two), "ply,vtp");
    EXPECT_EQ(to_string(AtlasFiles{}), "ply,vtp");  // the default: the legacy .vtk when asked
    EXPECT_EQ(to_string(parse_atlas_files("ply,vtk,vtp", "--atlas-formats")), "ply,vtk,vtp");
    for (const char* bad : {"ply,stl", "vtk,vtk", "", "ply,", " ply"}) {
        try {
            (void)parse_atlas_files(bad, "--atlas-formats");
            ADD_FAILURE() << "accepted \"" << bad << "\"";
        } catch (const OptionError& e) {
            EXPECT_NE(std::string(e.what()).find("--atlas-formats"), std::string::npos) << e.what();
        }
    }
    ExportOptions none;
    none.atlas_files = AtlasFiles{.ply = false, .vtk = false, .vtp = false};
    EXPECT_THROW(none.validate(), OptionError);
}

}  // namespace
}  // namespace glint
