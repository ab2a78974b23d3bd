#include "scenario/asymmetry_scenario.h"

#include "mesh/error.h"
#include "scenario/scenario.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path write_scenario(const std::string& text) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "asymmetry_scenarios" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir);
    const fs::path p = dir / "s.toml";
    std::ofstream(p) << text;
    return p;
}

constexpr const char* kSurface = R"(
[reference]
phantom = "ellipsoid"
size = [12.0, 8.0, 6.0]
resolution = 3
)";

void expect_error(const std::string& text, std::initializer_list<const char*> fragments) {
    try {
        (void)load_scenario(write_scenario(text), {});
        FAIL() << "expected InputError for:\n" << text;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg;
    }
}

TEST(AsymmetryScenario, ReadsThePlaneAndEveryExpectation) {
    const Scenario sc = load_scenario(
        write_scenario(std::string("asymmetry = true\nplane = \"x=1.5\"\n") + kSurface + R"(
[expect]
findings = 1
min_findings = 1
max_findings = 2
plane = "point=0,0,0;normal=1,0,0"
max_plane_angle_deg = 0.2
max_plane_offset = 0.1
[[expect.finding]]
kind = "less"
side = "+x"
[[expect.finding]]
kind = "more"
side = "left"
center = [1.0, 2.0, 3.0]
max_distance = 4.0
)"),
        {});
    ASSERT_TRUE(sc.asymmetry.enabled);
    ASSERT_TRUE(sc.asymmetry.plane);
    EXPECT_NEAR(sc.asymmetry.plane->offset, 1.5, 1e-12);
    EXPECT_NEAR(std::abs(sc.asymmetry.plane->normal.x()), 1.0, 1e-12);
    const AsymmetryExpect& x = sc.expect.asymmetry;
    EXPECT_EQ(x.findings, 1u);
    EXPECT_EQ(x.min_findings, 1u);
    EXPECT_EQ(x.max_findings, 2u);
    ASSERT_EQ(x.each.size(), 2u);
    EXPECT_EQ(x.each[0].kind, "less");
    EXPECT_EQ(x.each[1].side, "left");
    EXPECT_FALSE(x.each[0].center);
    ASSERT_TRUE(x.each[1].center && x.each[1].max_distance);
    EXPECT_EQ(*x.each[1].center, Vec3d(1, 2, 3));
    EXPECT_DOUBLE_EQ(*x.each[1].max_distance, 4.0);
    EXPECT_DOUBLE_EQ(*x.max_plane_angle_deg, 0.2);
    EXPECT_DOUBLE_EQ(*x.max_plane_offset, 0.1);
    EXPECT_FALSE(x.no_plane);
}

TEST(AsymmetryScenario, AScenarioWithoutItIsUnchanged) {
    const Scenario sc = load_scenario(write_scenario(kSurface), {});
    EXPECT_FALSE(sc.asymmetry.enabled);
    EXPECT_FALSE(sc.expect.asymmetry.any());
}

TEST(AsymmetryScenario, BadInputNamesTheKeyAndLine) {
    const std::string s = kSurface;
    expect_error("asymmetry = \"yes\"\n" + s, {"line 1", "asymmetry: expected true or false"});
    expect_error("asymmetry = true\nplane = \"q=1\"\n" + s,
                 {"line 2", "plane: \"q=1\": expected x=C"});
    expect_error("plane = \"x=0\"\n" + s, {"plane: a symmetry plane needs asymmetry = true"});
    expect_error(s + "[expect]\nfindings = 1\n",
                 {"expect: findings, plane and no_plane expectations need asymmetry = true"});
    expect_error("asymmetry = true\n" + s + "[examined]\nmesh = \"other.ply\"\n",
                 {"examined: asymmetry = true analyses the one surface of [reference]"});
    expect_error("asymmetry = true\n" + s + "[examined]\nresolution = 4\n", {"names a second one"});
    expect_error("asymmetry = true\n", {"missing section [reference]"});
    expect_error("asymmetry = true\n" + s + "[expect]\nplane = \"x=0\"\n",
                 {"expect.plane: needs max_plane_angle_deg and max_plane_offset"});
    expect_error("asymmetry = true\n" + s + "[expect]\nmax_plane_offset = 0.1\n",
                 {"expect.max_plane_offset: needs plane"});
    expect_error("asymmetry = true\n" + s + "[expect]\nno_plane = true\nfindings = 1\n",
                 {"expect.no_plane: expects no plausible plane"});
    expect_error("asymmetry = true\n" + s + "[[expect.finding]]\nkind = \"dent\"\nside = \"+x\"\n",
                 {"expect.finding[0].kind: \"dent\": expected less, more or no mirrored surface"});
    expect_error("asymmetry = true\n" + s + "[[expect.finding]]\nkind = \"less\"\n",
                 {"expect.finding[0].side: missing"});
    expect_error("asymmetry = true\n" + s +
                     "[[expect.finding]]\nkind = \"less\"\nside = \"+x\"\ncenter = [1, 2, 3]\n",
                 {"expect.finding[0].center: center = [x, y, z] and max_distance go together"});
}

// The one scan may be made from a volume as a pair's examined scan is (an erosion, a motion
// about a pivot, another voxel size, noise): that scan is the surface analysed.
TEST(AsymmetryScenario, OneScanMayBeAnEditedVolume) {
    const Scenario sc = load_scenario(write_scenario(R"(asymmetry = true
[reference]
mesh = "scan.mha"
iso = 1250.0
[examined]
erode = [157.0, 113.0, 130.0, 16.0]
erode_to = 1040.0
[expect]
findings = 1
)"),
                                      {});
    EXPECT_TRUE(sc.asymmetry.enabled);
    EXPECT_TRUE(sc.resample_volume);
    ASSERT_EQ(sc.erosions.size(), 1u);
}

TEST(AsymmetryScenario, PlaneDifferenceIsAngleAndOffsetEitherSign) {
    const SymmetryPlane x0 = plane_through({0, 0, 0}, {1, 0, 0});
    const auto [a0, o0] = plane_difference(plane_through({0.3, 5, 5}, {-1, 0, 0}), x0);
    EXPECT_NEAR(a0, 0.0, 1e-9);
    EXPECT_NEAR(o0, 0.3, 1e-12);
    const double t = 2.0 * std::numbers::pi / 180.0;
    const auto [a1, o1] =
        plane_difference(plane_through({0, 0, 0}, {std::cos(t), std::sin(t), 0}), x0);
    EXPECT_NEAR(a1, 2.0, 1e-9);
    EXPECT_NEAR(o1, 0.0, 1e-12);
}

TEST(AsymmetryScenario, ChecksNameWhatDidNotHold) {
    AsymmetryExpect x;
    x.findings = 2;
    x.each = {{"less", "+x"}, {"less", "+x"}};
    x.plane = plane_through({0, 0, 0}, {1, 0, 0});
    x.max_plane_angle_deg = 0.2;
    x.max_plane_offset = 0.1;
    AsymmetryOutcome o;
    o.plausible = true;
    o.findings = {{"less", "+x"}};
    o.plane_angle_deg = 0.5;
    o.plane_offset = 0.05;
    std::vector<std::string> failures;
    check_asymmetry_expect(x, o, failures);
    ASSERT_EQ(failures.size(), 3u);
    EXPECT_EQ(failures[0], "findings = 1, expected 2");
    // One finding cannot answer two expectations.
    EXPECT_EQ(failures[1], "no finding 'less' on the +x side (found: less on the +x side)");
    EXPECT_EQ(failures[2], "plane angle = 0.5000°, expected at most 0.2000°");

    // A finding of the right kind and side, but elsewhere, does not answer a placed one.
    AsymmetryExpect placed;
    placed.each = {
        {.kind = "more", .side = "right", .center = Vec3d(55, 108, 134), .max_distance = 5.0}};
    AsymmetryOutcome far;
    far.plausible = true;
    far.findings = {{.kind = "more", .side = "right", .center = Vec3d(55, 40, 170)}};
    failures.clear();
    check_asymmetry_expect(placed, far, failures);
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0],
              "no finding 'more' on the right side at (55.0, 108.0, 134.0) within 5 (found: more "
              "on the right side at (55.0, 40.0, 170.0))");
    far.findings[0].center = Vec3d(57, 109, 132);
    failures.clear();
    check_asymmetry_expect(placed, far, failures);
    EXPECT_TRUE(failures.empty()) << failures.front();

    failures.clear();
    o.plausible = false;
    o.verdict = "no plausible symmetry plane: …";
    check_asymmetry_expect(x, o, failures);
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0], "no plausible symmetry plane: …, expected a plausible symmetry plane");

    AsymmetryExpect none;
    none.no_plane = true;
    failures.clear();
    check_asymmetry_expect(none, o, failures);
    EXPECT_TRUE(failures.empty());
    o.plausible = true;
    o.verdict = "plausibly mirror-symmetric";
    check_asymmetry_expect(none, o, failures);
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0],
              "a plausible symmetry plane was found (plausibly mirror-symmetric), "
              "expected none");
}

}  // namespace
}  // namespace glint
