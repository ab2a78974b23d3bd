// inspect(): a run with outputs around analyse().
#include "report/inspect.h"

#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "mesh/surface_index.h"
#include "render/context.h"
#include "tests/scanner/dented_pair.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {
namespace {

TEST(Inspect, ReadsFramesBackFromTheGpuOnlyWhenPerViewExrsAreWritten) {
    const test::DentedPair& p = test::dented_pair();
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "gpu_sweep";
    std::filesystem::create_directories(dir);
    InspectOptions o;
    o.analysis.fit.mode = FitMode::Identity;
    o.analysis.sweep = test::small_vulkan_sweep(Accumulation::Auto);
    o.analysis.sweep.plan.size = 48;
    o.exports.write_views = false;
    o.exports.replace_existing = true;
    o.exports.write_exr = true;
    o.exports.output = dir / "with_exr";
    const AnalysisResult with_exr = inspect(p.reference, p.examined, o, {}).analysis;
    EXPECT_FALSE(with_exr.sweep.on_gpu);
    EXPECT_NE(with_exr.sweep.accumulation_note.find("EXR"), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(dir / "with_exr" / "views" / "z0_az000.0_el-30.0.exr"));
    o.exports.write_exr = false;
    o.exports.output = dir / "without_exr";
    const AnalysisResult without = inspect(p.reference, p.examined, o, {}).analysis;
    EXPECT_TRUE(without.sweep.on_gpu) << without.sweep.accumulation_note;
    EXPECT_EQ(without.decisions[0].regions.region_of_vertex,
              with_exr.decisions[0].regions.region_of_vertex);
}

// One BVH per surface per run (mesh/surface_index.h): the fit, the distance, the Embree sweep
// and the pictures share them; a run used to build five, three over the reference.
TEST(Inspect, BuildsOneBvhPerSurface) {
    const test::DentedPair& p = test::dented_pair();
    const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "inspect_bvh";
    InspectOptions o;
    o.analysis.fit.mode = FitMode::Register;
    o.analysis.sweep.plan.azimuth_step_deg = 90;
    o.analysis.sweep.plan.elevations_deg = {0};
    o.analysis.sweep.plan.size = 48;
    o.analysis.sweep.render.backend = Backend::Embree;
    o.exports.output = dir;
    o.exports.replace_existing = true;
    o.exports.write_views = false;
    auto bvhs = [] { return SurfaceIndex::builds() + render_context_stats().embree_scenes; };
    const std::size_t before = bvhs();
    const Inspection run = inspect(p.reference, p.examined, o, {});
    EXPECT_EQ(bvhs() - before, 2u) << "reference and examined, once each";
    EXPECT_TRUE(std::filesystem::exists(dir / "atlas.png"));  // the pictures ran on the shared one
    EXPECT_EQ(run.analysis.reference_index, nullptr) << "released once the outputs are written";
}

// Every stage of a run is announced, exports included, and each export that counts its items
// counts them up to its total after its stage began (issue 26: the exports used to be silent
// behind a finished sweep).
TEST(Inspect, AnnouncesEveryStageAndCountsTheExports) {
    const test::DentedPair& p = test::dented_pair();
    InspectOptions o;
    o.analysis.fit.mode = FitMode::Identity;
    o.analysis.sweep.plan.azimuth_step_deg = 90;
    o.analysis.sweep.plan.elevations_deg = {0, 45};
    o.analysis.sweep.plan.size = 32;
    o.analysis.sweep.render.backend = Backend::Embree;
    o.exports.output = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "inspect_stages";
    o.exports.replace_existing = true;
    o.exports.write_views = true;  // one picture per view, counted below
    std::vector<std::string> stages;
    std::map<std::string, std::pair<std::size_t, std::size_t>> last;  // stage → (done, total)
    std::size_t views = 0;
    AnalysisObserver observer;
    observer.stage = [&](std::string_view s) { stages.emplace_back(s); };
    observer.views = [&](std::size_t done, std::size_t) { views = done; };
    observer.items = [&](std::size_t done, std::size_t total) {
        ASSERT_FALSE(stages.empty());
        ASSERT_LE(done, total);
        last[stages.back()] = {done, total};
    };
    const Inspection run = inspect(p.reference, p.examined, o, {}, observer);
    const std::vector<std::string> expected{"fit",     "distance",    "sweep",       "decide",
                                            "export",  "atlas files", "report page", "pictures",
                                            "mosaics", "atlas.png",   "report.html"};
    EXPECT_EQ(stages, expected);
    const std::size_t planned = run.analysis.sweep.plan.views.size();
    EXPECT_EQ(views, planned);
    const AtlasFiles& f = o.exports.atlas_files;
    const std::size_t files = std::size_t{f.ply} + f.vtk + f.vtp + 2;  // + regions.csv, report.json
    EXPECT_EQ(last["atlas files"], std::make_pair(files, files));
    EXPECT_EQ(last["pictures"], std::make_pair(planned, planned)) << "one per per-view picture";
    EXPECT_EQ(last["mosaics"], std::make_pair(std::size_t{1}, std::size_t{1})) << "one per zoom";
}

}  // namespace
}  // namespace glint
