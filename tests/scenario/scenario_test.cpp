#include "scenario/scenario.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <fstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

// Each test writes into a folder of its own: CTest runs the tests of this file as parallel
// processes, and a shared bad.toml was rewritten by one while another read it (a CI failure).
fs::path write_scenario(const std::string& name, const std::string& text) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "scenarios" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir);
    const fs::path p = dir / (name + ".toml");
    std::ofstream(p) << text;
    return p;
}

constexpr const char* kValid = R"(
name = "dent"
tags = ["ci"]
[reference]
phantom = "sphere"
scheme = "ico"
resolution = 4
size = 10.0
[examined]
scheme = "uv"
resolution = 40
pose = [2.0, 0.0, 1.0, 0.1, 0.0, 0.0]
[[damage]]
kind = "dent"
center = [10.0, 0.0, 0.0]
radius = 3.0
depth = 0.5
[sweep]
azimuth_step = 45
elevations = [-30, 30]
zoom = [0.2]
[threshold]
deg = 4
[expect]
regions = 1
min_iou = 0.8
)";

// Expects an InputError whose message holds every fragment.
void expect_error(const std::string& text, std::initializer_list<const char*> fragments) {
    const fs::path p = write_scenario("bad", text);
    try {
        (void)load_scenario(p, {});
        FAIL() << "expected InputError for:\n" << text;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        for (const char* f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg;
    }
}

TEST(LoadScenario, ReadsEverySection) {
    const Scenario sc = load_scenario(write_scenario("valid", kValid), {});
    EXPECT_EQ(sc.name, "dent");
    ASSERT_TRUE(sc.reference.phantom);
    EXPECT_EQ(sc.reference.phantom->kind, PhantomKind::Sphere);
    ASSERT_TRUE(sc.examined.phantom);
    EXPECT_EQ(sc.examined.phantom->scheme, TessellationScheme::Uv);
    EXPECT_EQ(sc.examined.phantom->resolution, 40);
    EXPECT_DOUBLE_EQ(sc.examined.phantom->radii.x(), 10.0);  // inherited from the reference
    ASSERT_EQ(sc.damages.size(), 1u);
    EXPECT_EQ(sc.damages[0].kind, DamageKind::Dent);
    EXPECT_DOUBLE_EQ(sc.damages[0].depth, 0.5);
    EXPECT_NEAR(rotation_angle_deg(sc.pose), std::hypot(2.0, 1.0), 0.05);
    EXPECT_EQ(sc.analysis.sweep.plan.elevations_deg.size(), 2u);
    ASSERT_TRUE(sc.analysis.decision.threshold);
    EXPECT_DOUBLE_EQ(*sc.analysis.decision.threshold, 4.0);
    EXPECT_EQ(sc.analysis.fit.mode, FitMode::Register);  // a scenario registers by default
    EXPECT_EQ(sc.expect.regions, 1u);
}

TEST(LoadScenario, ExportsSayWhatARunWritesAndWhichWayIsUp) {
    // A volume whose header lies about superior (CThead) says up = "-z" in [exports]; a
    // scenario without the section keeps the command line's defaults.
    EXPECT_TRUE(load_scenario(write_scenario("plain", kValid), {}).exports.up.empty());
    std::string text = kValid;
    text.replace(text.find("[expect]"), 8,
                 "[exports]\nup = \"-z\"\nviews = true\natlas_files = \"ply\"\n\n[expect]");
    const Scenario sc = load_scenario(write_scenario("exports", text), {});
    EXPECT_EQ(sc.exports.up, "-z");
    EXPECT_TRUE(sc.exports.write_views);
    std::string bad_up = kValid;
    bad_up.replace(bad_up.find("[expect]"), 8, "[exports]\nup = \"sideways\"\n\n[expect]");
    expect_error(bad_up, {"bad.toml", "exports.up", "sideways"});
    std::string typo = kValid;
    typo.replace(typo.find("[expect]"), 8, "[exports]\nupp = \"-z\"\n\n[expect]");
    expect_error(typo, {"bad.toml", "exports.upp", "unknown key"});
}

TEST(LoadScenario, RejectsATypoedKeyNamingItsLine) {
    std::string text = kValid;
    text.replace(text.find("radius = 3.0"), 12, "raduis = 3.0");
    expect_error(text, {"bad.toml", "line 16", "damage[0].raduis", "unknown key"});
}

TEST(LoadScenario, RejectsAWrongType) {
    std::string text = kValid;
    text.replace(text.find("azimuth_step = 45"), 17, "azimuth_step = \"45\"");
    expect_error(text, {"sweep.azimuth_step", "expected a number", "found a string"});
}

TEST(LoadScenario, AnInvalidOptionNamesTheFileLineAndKey) {
    // Checked by AnalysisOptions::validate (the one check the command line runs too), and
    // placed by its key: before any mesh is built.
    std::string text = kValid;
    text.replace(text.find("azimuth_step = 45"), 17, "azimuth_step = 400");
    expect_error(text, {"bad.toml", "line ", "sweep.azimuth_step = 400", "(0, 360]"});
    std::string loss = kValid;
    loss.replace(loss.find("[sweep]"), 7, "[registration]\nloss = \"bisquare\"\n\n[sweep]");
    expect_error(loss, {"bad.toml", "registration.loss", "bisquare"});
}

TEST(LoadScenario, RejectsANegativeSize) {
    std::string text = kValid;
    text.replace(text.find("depth = 0.5"), 11, "depth = -0.5");
    expect_error(text, {"damage[0].depth", "must be > 0"});
}

TEST(LoadScenario, RejectsAMissingReference) {
    expect_error("name = \"x\"\n", {"reference", "missing"});
}

TEST(LoadScenario, ReportsTomlSyntaxErrorsWithTheLine) {
    expect_error("name = \"x\"\n[reference\nphantom = 1\n", {"bad.toml", "line 2"});
}

// A partial scan and two fields of view (issue 24): keep_side cuts a surface along a plane,
// the reference's before the examined is derived, the examined's before its pose.
TEST(LoadScenario, KeepSideCutsTheScansAndIsRefusedWhereItCannotApply) {
    std::string partial = kValid;
    partial.replace(partial.find("[examined]"), 10,
                    "keep_side = [-8.0, 0.0, 0.0, 1.0, 0.0, 0.0]\n[examined]\n"
                    "keep_side = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0]");
    partial.replace(partial.find("scheme = \"uv\"\nresolution = 40\n"), 30, "");
    const Scenario sc = load_scenario(write_scenario("partial", partial), {});
    ASSERT_TRUE(sc.reference.cut && sc.examined.cut);
    const ScenarioMeshes m = build_scenario_meshes(sc);
    // The sphere of radius 10: the reference keeps x ≥ -8, the examined x ≥ 0 (in the
    // reference's frame, before its pose).
    for (const auto& p : m.reference.positions) EXPECT_GE(p.x(), -8.0f);
    const Rigid back = m.true_reference_from_examined;
    for (const auto& p : m.examined.positions) EXPECT_GE((back * p.cast<double>()).x(), -1e-4);
    EXPECT_LT(m.examined.vertex_count(), m.reference.vertex_count() * 6 / 10);
    ASSERT_EQ(m.truth.size(), m.reference.vertex_count());
    bool noted = false;
    for (const auto& n : m.notes) noted |= n.find("examined: a partial scan") != std::string::npos;
    EXPECT_TRUE(noted);

    std::string zero = kValid;
    zero.replace(zero.find("[examined]"), 10, "[examined]\nkeep_side = [0, 0, 0, 0, 0, 0]");
    expect_error(zero, {"keep_side", "normal", "must not be zero"});
    std::string missing = kValid;
    missing.replace(missing.find("[examined]"), 10,
                    "[examined]\nkeep_side = [100.0, 0.0, 0.0, 1.0, 0.0, 0.0]");
    EXPECT_THROW((void)build_scenario_meshes(load_scenario(write_scenario("miss", missing), {})),
                 InputError);
}

// The keys of fitting a scaled pair and a part against a whole (issue 53) and of the region
// listed first (issue 50): read when sane, refused with the key and what was expected.
TEST(LoadScenario, ScaleCropBallAndFirstRegionKeysAreCheckedAndRead) {
    std::string good = kValid;
    good.replace(good.find("[examined]"), 10,
                 "crop_ball = [10.0, 0.0, 0.0, 6.0]\n[examined]\nscale = 1.01");
    good.replace(good.find("[expect]"), 8,
                 "[expect]\nfirst_kind = \"surface gone\"\nmin_first_area = 10.0\n"
                 "max_first_area = 20.0\nmin_first_volume_lost = 5.0");
    const Scenario sc = load_scenario(write_scenario("good", good), {});
    ASSERT_TRUE(sc.reference.crop_ball);
    EXPECT_DOUBLE_EQ((*sc.reference.crop_ball)[3], 6.0);
    EXPECT_DOUBLE_EQ(sc.examined_scale, 1.01);
    EXPECT_EQ(sc.expect.first_kind.value_or(""), "surface gone");
    EXPECT_DOUBLE_EQ(sc.expect.min_first_area.value_or(0), 10.0);
    EXPECT_DOUBLE_EQ(sc.expect.max_first_area.value_or(0), 20.0);
    EXPECT_DOUBLE_EQ(sc.expect.min_first_volume_lost.value_or(0), 5.0);
    std::string p_value = kValid;
    p_value.replace(p_value.find("[expect]"), 8, "[expect]\nmax_p_value = 0.001");
    EXPECT_DOUBLE_EQ(load_scenario(write_scenario("p", p_value), {}).expect.max_p_value.value_or(0),
                     0.001);
    std::string bad_p = kValid;
    bad_p.replace(bad_p.find("[expect]"), 8, "[expect]\nmax_p_value = 0.0");
    expect_error(bad_p, {"max_p_value", "a probability in (0, 1]"});

    std::string kind = kValid;
    kind.replace(kind.find("[expect]"), 8, "[expect]\nfirst_kind = \"hole\"");
    expect_error(kind, {"bad.toml", "expect.first_kind", "surface gone, dent, bump or missing"});
    std::string scale = kValid;
    scale.replace(scale.find("[examined]"), 10, "[examined]\nscale = -1.0");
    expect_error(scale, {"examined.scale", "must be > 0"});
    std::string radius = kValid;
    radius.replace(radius.find("[examined]"), 10, "crop_ball = [0.0, 0.0, 0.0, 0.0]\n[examined]");
    expect_error(radius, {"reference.crop_ball", "radius (number 4) must be > 0"});
    std::string on_examined = kValid;
    on_examined.replace(on_examined.find("[examined]"), 10,
                        "[examined]\ncrop_ball = [0.0, 0.0, 0.0, 5.0]");
    expect_error(on_examined, {"examined.crop_ball", "keep_side"});
}

// The CT pair generator's keys (volume_noise, volume_noise_seed, voxel_size) need a volume
// reference and sane values.
TEST(LoadScenario, AcquisitionKeysNeedAVolumeAndSaneValues) {
    std::string noise = kValid;
    noise.replace(noise.find("[examined]"), 10, "[examined]\nvolume_noise = 20.0");
    expect_error(noise, {"volume_noise", "needs a volume reference"});
    std::string voxel = kValid;
    voxel.replace(voxel.find("[examined]"), 10, "[examined]\nvoxel_size = [0.8, 0.8, 0.8]");
    expect_error(voxel, {"voxel_size", "needs a volume reference"});
    const std::string volume = R"(
name = "ct"
[reference]
mesh = "head.mha"
iso = 500.0
volume_noise = 20.0
[examined]
voxel_size = [0.8, 0.0, 0.8]
)";
    expect_error(volume, {"voxel_size", "every size must be > 0"});
    std::string negative = volume;
    negative.replace(negative.find("volume_noise = 20.0"), 19, "volume_noise = -1.0");
    expect_error(negative, {"volume_noise", "must be ≥ 0"});
    std::string good = volume;
    good.replace(good.find("[0.8, 0.0, 0.8]"), 15, "[0.8, 0.9, 1.0]\nvolume_noise_seed = 9");
    const Scenario sc = load_scenario(write_scenario("good", good), {});
    EXPECT_EQ(sc.reference.acquisition.noise, 20.0);
    ASSERT_TRUE(sc.examined.acquisition.voxel_size.has_value());
    EXPECT_EQ(*sc.examined.acquisition.voxel_size, Vec3d(0.8, 0.9, 1.0));
    EXPECT_EQ(sc.examined.acquisition.noise_seed, 9u);
    EXPECT_TRUE(sc.resample_volume);
    // Surfaces handed on as mesh files (issue 50): only a volume pair has any to hand on.
    std::string files = kValid;
    files.replace(files.find("[examined]"), 10, "[examined]\nas_mesh_files = true");
    expect_error(files, {"as_mesh_files", "volume pair"});
    std::string volume_files = good;
    volume_files.replace(volume_files.find("[examined]"), 10, "[examined]\nas_mesh_files = true");
    EXPECT_TRUE(load_scenario(write_scenario("files", volume_files), {}).as_mesh_files);
}

// A mesh or phantom scanned as CT (issue 50, item 6): both scans image the reference's solid,
// the examined one under the motion with its erosions; the examined scan takes what it does not
// say from the reference, with its own noise realisation.
constexpr const char* kCtOfPhantom = R"(
name = "ct-of-condyle"
[reference]
phantom = "condyle"
scan_as_ct = true
voxel_size = [0.3, 0.3, 0.3]
psf_fwhm = 0.5
volume_noise = 40.0
noise_correlation = 0.3
volume_noise_seed = 5
[examined]
pose = [1.0, -1.0, 2.0, 0.5, 0.0, -0.5]
erode = [0.0, 0.0, 10.0, 3.0]
erode_to = 1040.0
voxel_size = [0.4, 0.4, 0.4]
)";

TEST(LoadScenario, AMeshScannedAsCtTakesAcquisitionKeysAndTheExaminedInheritsThem) {
    const Scenario sc = load_scenario(write_scenario("ct", kCtOfPhantom), {});
    EXPECT_TRUE(sc.reference.scan_as_ct);
    ASSERT_TRUE(sc.reference.surface.iso.has_value());
    EXPECT_EQ(*sc.reference.surface.iso, 1420.0);  // the middle of [1040, 1800]
    EXPECT_EQ(sc.examined.acquisition.noise, 40.0);
    EXPECT_EQ(sc.examined.acquisition.psf_fwhm, 0.5);
    EXPECT_EQ(sc.examined.acquisition.noise_correlation, 0.3);
    EXPECT_EQ(sc.examined.acquisition.noise_seed, 6u);  // its own realisation
    EXPECT_EQ(*sc.examined.acquisition.voxel_size, Vec3d(0.4, 0.4, 0.4));
    EXPECT_TRUE(sc.resample_volume);
    ASSERT_EQ(sc.erosions.size(), 1u);
    // Without [examined]: the same acquisition, the next seed.
    std::string bare = kCtOfPhantom;
    bare.erase(bare.find("[examined]"));
    const Scenario b = load_scenario(write_scenario("bare", bare), {});
    EXPECT_EQ(*b.examined.acquisition.voxel_size, Vec3d(0.3, 0.3, 0.3));
    EXPECT_EQ(b.examined.acquisition.noise_seed, 6u);
    EXPECT_TRUE(b.resample_volume);
    std::string values = kCtOfPhantom;
    values.replace(values.find("scan_as_ct = true"), 17,
                   "scan_as_ct = true\nct_values = [0.0, 1000.0]\niso = 400.0");
    const Scenario v = load_scenario(write_scenario("values", values), {});
    EXPECT_EQ(v.reference.ct_background, 0.0f);
    EXPECT_EQ(v.reference.ct_object, 1000.0f);
    EXPECT_EQ(*v.reference.surface.iso, 400.0);
}

TEST(LoadScenario, ScanAsCtIsRefusedWhereItCannotApply) {
    std::string no_voxels = kCtOfPhantom;
    no_voxels.replace(no_voxels.find("voxel_size = [0.3, 0.3, 0.3]"), 28, "");
    expect_error(no_voxels, {"scan_as_ct", "needs voxel_size"});
    std::string volume = kCtOfPhantom;
    volume.replace(volume.find("phantom = \"condyle\""), 19, "mesh = \"head.mha\"");
    expect_error(volume, {"scan_as_ct", "is a volume already"});
    std::string values = kCtOfPhantom;
    values.replace(values.find("scan_as_ct = true"), 17,
                   "scan_as_ct = true\nct_values = [5.0, 5.0]");
    expect_error(values, {"ct_values", "two different finite values"});
    std::string loose = kValid;
    loose.replace(loose.find("[reference]"), 11, "[reference]\nct_values = [0.0, 1.0]");
    expect_error(loose, {"ct_values", "needs scan_as_ct"});
    std::string examined = kValid;
    examined.replace(examined.find("[examined]"), 10, "[examined]\nscan_as_ct = true");
    expect_error(examined, {"scan_as_ct", "belongs in [reference]"});
    std::string psf = kCtOfPhantom;
    psf.replace(psf.find("psf_fwhm = 0.5"), 14, "psf_fwhm = -0.5");
    expect_error(psf, {"psf_fwhm", "must be ≥ 0 mm"});
    std::string blur_on_mesh = kValid;
    blur_on_mesh.replace(blur_on_mesh.find("[examined]"), 10, "[examined]\npsf_fwhm = 0.5");
    expect_error(blur_on_mesh, {"psf_fwhm", "scan_as_ct"});
}

TEST(BuildScenario, ACtOfAPhantomIsAPairOfScansWithTheErosionAsTruth) {
    std::string small = kCtOfPhantom;  // coarser voxels keep the test quick
    small.replace(small.find("[0.3, 0.3, 0.3]"), 15, "[0.5, 0.5, 0.5]");
    small.replace(small.find("[0.4, 0.4, 0.4]"), 15, "[0.6, 0.6, 0.6]");
    const Scenario sc = load_scenario(write_scenario("ct", small), {});
    const ScenarioMeshes m = build_scenario_meshes(sc);
    ASSERT_GT(m.reference.vertex_count(), 1000u);
    ASSERT_GT(m.examined.vertex_count(), 1000u);
    EXPECT_TRUE(m.reference.voxel_axes.has_value());  // surfaces of scans carry their grid
    EXPECT_TRUE(m.has_truth_pose);
    std::size_t truth = 0;
    for (auto t : m.truth) truth += t;
    EXPECT_GT(truth, 10u);
    // The truth is what the noiseless scans show of the erosion (erosion_truth): every vertex
    // deep in the ball, none beyond it and the partial-volume ramp of its edge (half a voxel).
    std::size_t deep = 0, deep_labelled = 0, beyond = 0;
    for (std::size_t v = 0; v < m.truth.size(); ++v) {
        const double r = (m.reference.positions[v].cast<double>() - Vec3d(0, 0, 10)).norm();
        deep += r <= 2.0 ? 1 : 0;
        deep_labelled += r <= 2.0 && m.truth[v] ? 1 : 0;
        beyond += m.truth[v] && r > 3.0 + 0.6 ? 1 : 0;
    }
    EXPECT_GT(deep, 10u);
    EXPECT_EQ(deep_labelled, deep);
    EXPECT_EQ(beyond, 0u);
    // An erosion to a value above the iso value (1420) removes nothing the scans can show.
    std::string kept = small;
    kept.replace(kept.find("erode_to = 1040.0"), 17, "erode_to = 1700.0");
    const ScenarioMeshes none =
        build_scenario_meshes(load_scenario(write_scenario("kept", kept), {}));
    EXPECT_EQ(std::count(none.truth.begin(), none.truth.end(), std::uint8_t{1}), 0);
    // The examined scan holds the moved condyle: placed back, its surface lies on the
    // reference's away from the erosion (within a voxel and the noise).
    Mesh placed = m.examined;
    transform_mesh(placed, m.true_reference_from_examined);
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    for (const auto& p : m.reference.positions) a += p.cast<double>();
    for (const auto& p : placed.positions) b += p.cast<double>();
    a /= double(m.reference.vertex_count());
    b /= double(placed.vertex_count());
    EXPECT_LT((a - b).norm(), 0.1);
    bool noted = false;
    for (const auto& n : m.notes)
        noted |= n.find("CT of the reference's solid") != std::string::npos;
    EXPECT_TRUE(noted);
}

TEST(LoadScenario, AResampledExaminedScanTakesItsOwnFieldOfViewButNoOtherSurfaceKey) {
    const std::string volume = R"(
name = "ct"
[reference]
mesh = "head.mha"
iso = 500.0
surface_roi = "box:0,0,0,50,50,50"
[examined]
voxel_size = [0.8, 0.8, 0.8]
surface_roi = "box:0,0,8,50,50,42"
)";
    const Scenario sc = load_scenario(write_scenario("fov", volume), {});
    ASSERT_TRUE(sc.examined.surface.roi.has_value());
    EXPECT_EQ(sc.examined.surface.roi->min.z(), 8.0);
    EXPECT_EQ(sc.reference.surface.roi->min.z(), 0.0);
    std::string largest = volume;
    largest.replace(largest.find("voxel_size"), 10, "largest = true\nvoxel_size");
    expect_error(largest, {"largest", "surface keys need a volume file"});
    // On a phantom reference there is no scan to cut: one clear error when the pair is built.
    std::string phantom = kValid;
    phantom.replace(phantom.find("[examined]"), 10,
                    "[examined]\nsurface_roi = \"box:-20,-20,-20,20,20,0\"");
    const Scenario p = load_scenario(write_scenario("phantom", phantom), {});
    try {
        (void)build_scenario_meshes(p);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("surface_roi in [examined]"), std::string::npos)
            << e.what();
    }
}

TEST(LoadScenario, MissingFileIsAnIoError) {
    EXPECT_THROW((void)load_scenario("/nonexistent/scenario.toml", {}), IoError);
}

TEST(ReadNpyMask, ReadsBooleanVectorAndRejectsOtherFiles) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "npy";
    fs::create_directories(dir);
    // A v1.0 header padded so that the data starts at byte 128, as NumPy aligns it.
    std::string header = "{'descr': '|b1', 'fortran_order': False, 'shape': (5,), }";
    header.append(128 - 10 - header.size() - 1, ' ');
    header += '\n';
    std::string file = std::string("\x93NUMPY\x01\x00", 8);
    file += static_cast<char>(header.size() & 0xFF);
    file += static_cast<char>(header.size() >> 8);
    file += header;
    file += std::string("\x01\x00\x00\x01\x01", 5);
    write_file_atomically(dir / "mask.npy", file);
    EXPECT_EQ(read_npy_mask(dir / "mask.npy"), (std::vector<std::uint8_t>{1, 0, 0, 1, 1}));
    write_file_atomically(dir / "short.npy", file.substr(0, file.size() - 2));
    EXPECT_THROW((void)read_npy_mask(dir / "short.npy"), InputError);
    write_file_atomically(dir / "text.npy", "hello world, not numpy");
    EXPECT_THROW((void)read_npy_mask(dir / "text.npy"), InputError);
}

TEST(ReadNpyMask, RefusesLyingLengthsBeforeAllocating) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "npy";
    fs::create_directories(dir);
    auto expect_refused = [&](const std::string& name, const std::string& bytes,
                              const std::string& says) {
        write_file_atomically(dir / name, bytes);
        try {
            (void)read_npy_mask(dir / name);
            ADD_FAILURE() << name << " was read";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
        }
    };
    // A v2.0 header claiming 4 GiB, in a file of 20 bytes.
    expect_refused("huge_header.npy",
                   std::string("\x93NUMPY\x02\x00\xff\xff\xff\xff", 12) + "{'descr'",
                   "exceeds the file");
    // A shape of 10^18 values (and one that does not parse) in a file of 128 bytes.
    for (const std::string shape : {"1000000000000000000", "x"}) {
        std::string header =
            "{'descr': '|b1', 'fortran_order': False, 'shape': (" + shape + ",), }";
        header.append(128 - 10 - header.size() - 1, ' ');
        header += '\n';
        std::string file = std::string("\x93NUMPY\x01\x00", 8);
        file += static_cast<char>(header.size() & 0xFF);
        file += static_cast<char>(header.size() >> 8);
        // note: one file per shape: a file this process read is an input it never writes.
        expect_refused("huge_shape_" + shape + ".npy", file + header + "\x01", "the file holds 1");
    }
}

}  // namespace
}  // namespace glint
