// Which way is up in the pictures (report/orientation.h): superior up and anatomical names for
// a surface in a patient space, +z and axis names (never "top") for a mesh that says nothing,
// --up obeyed; report.json says which and why.
#include "report/orientation.h"

#include "mesh/error.h"
#include "mesh/phantom.h"
#include "report/inspect.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

void expect_near(const Vec3d& a, const Vec3d& b) {
    EXPECT_LT((a - b).norm(), 1e-9) << a.transpose() << " vs " << b.transpose();
}

TEST(Orientation, AMeshThatSaysNothingIsDrawnWithZUpAndNamedByAxis) {
    const Orientation o = resolve_orientation(PatientSpace::Unknown, "");
    expect_near(o.up, Vec3d::UnitZ());
    expect_near(o.front, Vec3d::UnitX());
    EXPECT_FALSE(o.up_known);
    EXPECT_EQ(o.name(Vec3d::UnitZ()), "+z");
    EXPECT_EQ(o.name(Vec3d(1, 0, 1)), "+x+z");
    EXPECT_EQ(o.letter(Vec3d(0.2, -0.9, 0.1)), "-y");
    EXPECT_NE(o.source.find("--up"), std::string::npos) << o.source;
}

TEST(Orientation, PatientSpacesPutSuperiorUpAndLookFromTheFrontFirst) {
    const Orientation lps = resolve_orientation(PatientSpace::LPS, "");
    EXPECT_TRUE(lps.up_known);
    expect_near(lps.up, Vec3d::UnitZ());
    expect_near(lps.front, -Vec3d::UnitY());  // LPS: +y is posterior
    EXPECT_EQ(lps.name(lps.front), "anterior");
    // The panels turn from the front to the patient's left, back, right, then top and bottom.
    EXPECT_EQ(lps.name(panel_direction(lps, 90, 0)), "left");
    EXPECT_EQ(lps.name(panel_direction(lps, 180, 0)), "posterior");
    EXPECT_EQ(lps.name(panel_direction(lps, 270, 0)), "right");
    EXPECT_EQ(lps.name(panel_direction(lps, 0, 90)), "superior");
    EXPECT_EQ(lps.name(panel_direction(lps, 0, -90)), "inferior");
    EXPECT_EQ(lps.letter(Vec3d::UnitX()), "L");
    EXPECT_EQ(lps.name(Vec3d(0.3, -1, 1)), "anterior-superior");  // equal parts: axis order

    const Orientation ras = resolve_orientation(PatientSpace::RAS, "");
    expect_near(ras.front, Vec3d::UnitY());  // RAS: +y is anterior
    EXPECT_EQ(ras.name(Vec3d::UnitX()), "right");
    EXPECT_EQ(ras.name(panel_direction(ras, 90, 0)), "left");
}

TEST(Orientation, UpAsGivenWinsAndIsNamedTop) {
    const Orientation o = resolve_orientation(PatientSpace::Unknown, "-z");
    EXPECT_TRUE(o.up_known);
    expect_near(o.up, -Vec3d::UnitZ());
    expect_near(o.front, Vec3d::UnitX());
    expect_near(panel_direction(o, 0, 90), -Vec3d::UnitZ());
    // A right-handed display frame: from the front, turning towards up × front.
    expect_near(panel_direction(o, 90, 0), -Vec3d::UnitY());
    expect_near(resolve_orientation(PatientSpace::Unknown, "y").up, Vec3d::UnitY());
    // Up along the file's inferior axis (CThead's hand-written header, whose slices run
    // downwards): the picture obeys and the labels stay anatomical, -z named superior (issue 51:
    // --up -z turned every label into an axis name).
    const Orientation ct = resolve_orientation(PatientSpace::LPS, "-z");
    EXPECT_EQ(ct.space, PatientSpace::LPS);
    EXPECT_NE(ct.source.find("slices running downwards, so -z is named superior"),
              std::string::npos)
        << ct.source;
    EXPECT_EQ(ct.name(panel_direction(ct, 0, 90)), "superior");
    EXPECT_EQ(ct.letter(-Vec3d::UnitZ()), "S");
    EXPECT_EQ(ct.name(Vec3d::UnitZ()), "inferior");
    EXPECT_EQ(ct.name(Vec3d::UnitX()), "left");
    EXPECT_EQ(ct.name(-Vec3d::UnitY()), "anterior");
    EXPECT_EQ(ct.name(panel_direction(ct, 0, 0)), "anterior");
    // An up along another axis than the space's S-I contradicts it: named by axis, said so.
    const Orientation turned = resolve_orientation(PatientSpace::LPS, "+y");
    EXPECT_EQ(turned.space, PatientSpace::Unknown);
    EXPECT_NE(turned.source.find("is not superior"), std::string::npos) << turned.source;
    // An up that agrees keeps the anatomical names.
    EXPECT_EQ(resolve_orientation(PatientSpace::RAS, "+z").name(Vec3d::UnitX()), "right");
}

TEST(Orientation, RefusesAnUpThatIsNoAxis) {
    for (const char* bad : {"w", "+w", "up", "xz", "--z", "1"}) {
        try {
            (void)resolve_orientation(PatientSpace::Unknown, bad);
            ADD_FAILURE() << bad;
        } catch (const OptionError& e) {
            EXPECT_EQ(e.key(), "exports.up");
            EXPECT_NE(std::string(e.what()).find("+x, -x, +y, -y, +z, -z"), std::string::npos);
        }
    }
    ExportOptions exports;
    exports.up = "sideways";
    EXPECT_THROW(exports.validate(), OptionError);
}

TEST(Orientation, UprightRollsAViewAboutItsAxisOnly) {
    const Mesh m = make_phantom({.kind = PhantomKind::Sphere, .resolution = 3});
    const Orientation o = resolve_orientation(PatientSpace::Unknown, "-z");
    for (const auto& [az, el] : {std::pair{0.0, 0.0}, {30.0, 30.0}, {200.0, -60.0}, {0.0, 90.0}}) {
        const View v = make_view(m, {.azimuth_deg = az, .elevation_deg = el});
        const View r = upright(v, o);
        const auto& a = v.camera.world_from_camera;
        const auto& b = r.camera.world_from_camera;
        expect_near(b.translation(), a.translation());
        expect_near(b.linear().col(2), a.linear().col(2));  // same viewing axis
        EXPECT_NEAR(b.linear().determinant(), 1.0, 1e-9);
        const Vec3d back = a.linear().col(2);
        const Vec3d in_image = o.up - o.up.dot(back) * back;
        if (in_image.norm() > 0.05) {  // up is drawn as up as the view allows
            EXPECT_NEAR(b.linear().col(1).dot(in_image.normalized()), 1.0, 1e-9) << az << " " << el;
        } else {  // looking along up: the front is drawn up
            EXPECT_GT(b.linear().col(1).dot(o.front), 0.99) << az << " " << el;
        }
    }
}

TEST(Orientation, ReadsTheSpaceAMeshFileStates) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "orientation";
    fs::create_directories(dir);
    auto file = [&](const char* name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
        return dir / name;
    };
    EXPECT_EQ(space_stated_in(file("lps.vtk",
                                   "# vtk DataFile Version 4.2\n3D Slicer output. "
                                   "SPACE=LPS\nBINARY\n")),
              PatientSpace::LPS);
    EXPECT_EQ(space_stated_in(file("ras.ply", "ply\nformat ascii 1.0\ncomment SPACE=RAS\n")),
              PatientSpace::RAS);
    EXPECT_EQ(space_stated_in(file("none.ply", "ply\nformat ascii 1.0\n")), PatientSpace::Unknown);
    EXPECT_EQ(space_stated_in(file("odd.ply", "ply\ncomment SPACE=XYZ\n")), PatientSpace::Unknown);
    EXPECT_EQ(space_stated_in(file("short.ply", "SPACE=L")), PatientSpace::Unknown);
    EXPECT_EQ(space_stated_in(dir / "absent.ply"), PatientSpace::Unknown);
}

// report.json says how the pictures are oriented and why; the input keeps its space.
TEST(Orientation, ReportJsonRecordsTheOrientationAndTheInputsSpace) {
    const Mesh ref = make_phantom({.kind = PhantomKind::Sphere, .resolution = 3});
    InspectOptions o;
    o.analysis.fit.mode = FitMode::Identity;
    o.analysis.sweep.plan.azimuth_step_deg = 90;
    o.analysis.sweep.plan.elevations_deg = {0};
    o.analysis.sweep.plan.size = 32;
    o.analysis.sweep.render.backend = Backend::Embree;
    RunRecord record;
    RunInput in = mesh_run_input("reference", ref, "a volume's surface");
    in.record.space = "LPS";
    record.add(in);
    const nlohmann::json lps = nlohmann::json::parse(inspect(ref, ref, o, record).report_json);
    EXPECT_EQ(lps["inputs"][0]["space"], "LPS");
    EXPECT_EQ(lps["orientation"]["space"], "LPS");
    EXPECT_EQ(lps["orientation"]["up_name"], "superior");
    EXPECT_EQ(lps["orientation"]["front_name"], "anterior");
    EXPECT_EQ(lps["orientation"]["up_stated"], true);
    EXPECT_EQ(lps["analysis"]["exports"]["up"], nullptr);

    o.exports.up = "-y";
    const nlohmann::json given = nlohmann::json::parse(inspect(ref, ref, o, {}).report_json);
    EXPECT_TRUE(given["orientation"]["space"].is_null());
    EXPECT_EQ(given["orientation"]["up"], nlohmann::json({0.0, -1.0, 0.0}));
    EXPECT_EQ(given["orientation"]["up_name"], "-y");
    EXPECT_EQ(given["analysis"]["exports"]["up"], "-y");
}

}  // namespace
}  // namespace glint
