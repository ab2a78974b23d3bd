// Reading volumes: every format glint reads gives the same surface from the same generated
// volume; a DICOM series written through GDCM reads back in the right frame; every kind of bad
// input is one InputError naming the file.
#include "volume/load.h"

#include "mesh/error.h"
#include "volume/phantom.h"

#include <gtest/gtest.h>

#include <fstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "volume" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// A small ellipsoid on a rotated grid (proper rotation, so DICOM can hold it), integer
// values (DICOM stores 16-bit integers).
Volume small_volume() {
    EllipsoidVolumeOptions o;
    o.grid.size = {24, 20, 16};
    o.grid.spacing = {0.7, 0.9, 1.3};
    o.grid.direction = Eigen::AngleAxisd(0.4, Vec3d(0.2, -1, 0.5).normalized()).toRotationMatrix();
    o.grid.origin = {-12.5, 30.25, 7.0};
    o.center = o.grid.physical_from_index(Vec3d(11.5, 9.5, 7.5));
    o.radii = {6, 5, 4};
    Volume v = make_ellipsoid_volume(o);
    for (float& x : v.voxels) x = std::round(x);
    return v;
}

void expect_same_surface(const Mesh& a, const Mesh& b, const std::string& what) {
    ASSERT_EQ(a.vertex_count(), b.vertex_count()) << what;
    ASSERT_EQ(a.triangle_count(), b.triangle_count()) << what;
    double worst = 0.0;
    for (std::size_t v = 0; v < a.vertex_count(); ++v) worst = std::max(worst, double((a.positions[v] - b.positions[v]).norm()));
    // DICOM writes positions as decimal strings of 16 characters; NIfTI stores float32.
    EXPECT_LT(worst, 1e-3) << what << ": largest vertex difference, mm";
}

TEST(ReadVolume, EveryFormatGivesTheSameSurface) {
    const Volume v = small_volume();
    const SurfaceOptions iso{.iso = 500.0};
    const Mesh expected = extract_surface(v, iso).mesh;
    const fs::path dir = fresh_dir("formats");
    for (const char* name : {"v.mha", "v.mhd", "v.nii", "v.nii.gz", "v.nrrd", "v.nhdr"}) {
        write_volume(v, dir / name);
        const LoadedSurface s = load_surface(dir / name, iso);
        expect_same_surface(expected, s.mesh, name);
        ASSERT_TRUE(s.geometry);
        EXPECT_LT((s.geometry->direction - v.geometry.direction).norm(), 1e-5) << name;
        EXPECT_LT((s.geometry->origin - v.geometry.origin).norm(), 1e-4) << name;
    }
    write_dicom_series(v, dir / "dicom");
    const LoadedSurface d = load_surface(dir / "dicom", iso);
    EXPECT_EQ(d.report.format, "volume-dicom");
    expect_same_surface(expected, d.mesh, "DICOM series");
}

TEST(ReadVolume, DicomSeriesReadsBackInTheRightFrame) {
    const Volume v = small_volume();
    const fs::path dir = fresh_dir("dicom") / "series";
    write_dicom_series(v, dir);
    const Volume back = read_volume(dir);
    EXPECT_EQ(back.geometry.size, v.geometry.size);
    EXPECT_LT((back.geometry.spacing - v.geometry.spacing).norm(), 1e-4);
    EXPECT_LT((back.geometry.origin - v.geometry.origin).norm(), 1e-4);
    EXPECT_LT((back.geometry.direction - v.geometry.direction).norm(), 1e-5);
    EXPECT_EQ(back.voxels, v.voxels);
    EXPECT_EQ(back.format, "dicom");
}

// The error's message is one line naming the file and containing `says`.
void expect_input_error(const fs::path& path, const std::string& says, const SurfaceOptions& options = {.iso = 500.0}) {
    try {
        (void)load_surface(path, options);
        FAIL() << path << ": no error";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        EXPECT_NE(m.find(path.filename().string()), std::string::npos) << m;
        EXPECT_NE(m.find(says), std::string::npos) << m;
    }
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

TEST(ReadVolume, RejectsTruncatedRawData) {
    const fs::path dir = fresh_dir("truncated");
    write_volume(small_volume(), dir / "v.mhd");
    fs::resize_file(dir / "v.raw", fs::file_size(dir / "v.raw") / 2);
    expect_input_error(dir / "v.mhd", "bytes");
}

TEST(ReadVolume, RejectsAHeaderThatLiesAboutSizes) {
    const fs::path dir = fresh_dir("lying");
    write_text(dir / "v.raw", std::string(8 * 8 * 8 * 2, '\0'));
    write_text(dir / "v.mhd", "ObjectType = Image\nNDims = 3\nDimSize = 8 8 16\nElementType = MET_SHORT\n"
                              "ElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "needs 2048");
}

TEST(ReadVolume, RejectsAMissingSliceFile) {
    const fs::path dir = fresh_dir("slices");
    for (int k = 1; k <= 3; ++k)
        if (k != 2) write_text(dir / ("s." + std::to_string(k)), std::string(8 * 8 * 2, '\0'));
    write_text(dir / "v.mhd", "ObjectType = Image\nNDims = 3\nDimSize = 8 8 3\nElementType = MET_SHORT\n"
                              "ElementDataFile = s.%d 1 3 1\n");
    expect_input_error(dir / "v.mhd", "s.2\" is missing");
}

TEST(ReadVolume, RejectsA2DImage) {
    const fs::path dir = fresh_dir("image2d");
    write_text(dir / "v.raw", std::string(8 * 8 * 2, '\0'));
    write_text(dir / "v.mhd", "ObjectType = Image\nNDims = 2\nDimSize = 8 8\nElementType = MET_SHORT\nElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "2D image");
}

TEST(ReadVolume, RejectsA4DImage) {
    const fs::path dir = fresh_dir("image4d");
    write_text(dir / "v.raw", std::string(8 * 8 * 8 * 3 * 2, '\0'));
    write_text(dir / "v.mhd",
               "ObjectType = Image\nNDims = 4\nDimSize = 8 8 8 3\nElementType = MET_SHORT\nElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "4D image");
}

TEST(ReadVolume, RejectsAFolderWithoutDicom) {
    const fs::path dir = fresh_dir("no_dicom");
    write_text(dir / "notes.txt", "not a DICOM file\n");
    expect_input_error(dir, "no DICOM series");
}

TEST(LoadSurface, AVolumeWithoutIsoAsksForItAndGivesTheRange) {
    const fs::path dir = fresh_dir("no_iso");
    write_volume(small_volume(), dir / "v.mha");
    expect_input_error(dir / "v.mha", "needs --iso", {});
    expect_input_error(dir / "v.mha", "0 … 1000", {});
}

TEST(LoadSurface, IsoOutsideTheRangeNamesTheFile) {
    const fs::path dir = fresh_dir("bad_iso");
    write_volume(small_volume(), dir / "v.nrrd");
    expect_input_error(dir / "v.nrrd", "outside the data range 0 … 1000", {.iso = -5.0});
}

TEST(LoadSurface, SurfaceOptionsOnAMeshFileAreAnError) {
    EXPECT_THROW((void)load_surface(fs::path(GLINT_TEST_DATA_DIR) / "cube.obj", {.iso = 1.0}), InputError);
    EXPECT_EQ(load_surface(fs::path(GLINT_TEST_DATA_DIR) / "cube.obj", {}).mesh.triangle_count(), 12u);
}

TEST(ReadVolume, MissingFileIsBadInput) {
    EXPECT_THROW((void)read_volume(fs::path(GLINT_TEST_OUTPUT_DIR) / "none.nii.gz"), InputError);
}

}  // namespace
}  // namespace glint
