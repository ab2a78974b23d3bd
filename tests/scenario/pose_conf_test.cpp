// Ground-truth poses from a Stanford .conf file (scenario/pose_conf.h) and the scenario keys
// that read them: the convention p_common = R(q)ᵀ·p + t, and one clear line for every fault.
#include "scenario/pose_conf.h"
#include "scenario/scenario.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path write_file(const std::string& name, const std::string& text) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "pose_conf" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir);
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p;
}

std::string error_of(const fs::path& conf, const std::string& entry) {
    try {
        (void)read_conf_pose(conf, entry);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ConfPose, MapsAScanPointByTheTransposedRotationThenTheTranslation) {
    // q = (0, sin 45°, 0, cos 45°): 90° about y. R(q) maps x to −z; R(q)ᵀ maps x to +z.
    const double h = std::sin(std::numbers::pi / 4);
    const fs::path conf = write_file(
        "scan.conf",
        "camera 0 0 0 0 0 0 1\n# a comment\nbmesh a.ply 0 0 0 0 0 0 1\nbmesh b.ply 1 2 3 0 " +
            std::to_string(h) + " 0 " + std::to_string(h) + "\n");
    const Rigid b = read_conf_pose(conf, "b.ply");
    const Vec3d p = b * Vec3d(1, 0, 0);
    EXPECT_NEAR(p.x(), 1.0, 1e-6);
    EXPECT_NEAR(p.y(), 2.0, 1e-6);
    EXPECT_NEAR(p.z(), 4.0, 1e-6);
    EXPECT_TRUE(read_conf_pose(conf, "a.ply").isApprox(Rigid::Identity()));
}

TEST(ConfPose, NamesTheFileAndLineOfEveryFault) {
    const fs::path conf = write_file("bad.conf",
                                     "bmesh short.ply 1 2 3\nbmesh long.ply 0 0 0 0 0 0 2\n"
                                     "bmesh nan.ply nan 0 0 0 0 0 1\n");
    EXPECT_NE(error_of(conf, "short.ply").find("line 1: expected bmesh <file> tx ty tz"),
              std::string::npos);
    EXPECT_NE(error_of(conf, "long.ply").find("line 2: the quaternion has norm 2"),
              std::string::npos);
    EXPECT_NE(error_of(conf, "nan.ply").find("line 3"), std::string::npos);
    EXPECT_NE(error_of(conf, "absent.ply").find("no line \"bmesh absent.ply"), std::string::npos);
    EXPECT_THROW((void)read_conf_pose(conf.parent_path() / "none.conf", "a.ply"), IoError);
}

TEST(ConfPose, AScenarioTakesItsTruthFromTheConfAndNeedsBothKeys) {
    const fs::path conf = write_file("bun.conf", "bmesh s.ply 0.5 0 0 0 0 0 1\n");
    const std::string head =
        "[reference]\nphantom = \"sphere\"\n[examined]\nphantom = \"sphere\"\n";
    const fs::path good = write_file("good.toml", head + "truth_pose_conf = \"" + conf.string() +
                                                      "\"\ntruth_pose_entry = \"s.ply\"\n");
    const Scenario sc = load_scenario(good, {});
    EXPECT_NEAR(sc.pose.translation().x(), -0.5, 1e-12);  // examined = pose · reference
    const fs::path half = write_file("half.toml", head + "truth_pose_entry = \"s.ply\"\n");
    try {
        (void)load_scenario(half, {});
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("needs both truth_pose_conf and truth_pose_entry"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace glint
