// Reading volumes: every format glint reads gives the same surface from the same generated
// volume; a DICOM series written through GDCM reads back in the right frame; every kind of bad
// input is one InputError naming the file.
#include "volume/load.h"

#include "mesh/error.h"
#include "tests/mesh/test_files.h"
#include "volume/detail/dicom_check.h"
#include "volume/phantom.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) { return test::fresh_dir("volume", name); }

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
    for (std::size_t v = 0; v < a.vertex_count(); ++v)
        worst = std::max(worst, double((a.positions[v] - b.positions[v]).norm()));
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
void expect_input_error(const fs::path& path, const std::string& says,
                        const SurfaceOptions& options = {.iso = 500.0}) {
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

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

TEST(ReadVolume, RejectsTruncatedRawData) {
    const fs::path dir = fresh_dir("truncated");
    write_volume(small_volume(), dir / "v.mhd");
    fs::resize_file(dir / "v.raw", fs::file_size(dir / "v.raw") / 2);
    expect_input_error(dir / "v.mhd", "bytes");
}

TEST(ReadVolume, RejectsAHeaderThatLiesAboutSizes) {
    const fs::path dir = fresh_dir("lying");
    write_text(dir / "v.raw", std::string(8 * 8 * 8 * 2, '\0'));
    write_text(dir / "v.mhd",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 16\nElementType = MET_SHORT\n"
               "ElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "needs 2048");
}

TEST(ReadVolume, RejectsAMissingSliceFile) {
    const fs::path dir = fresh_dir("slices");
    for (int k = 1; k <= 3; ++k)
        if (k != 2) write_text(dir / ("s." + std::to_string(k)), std::string(8 * 8 * 2, '\0'));
    write_text(dir / "v.mhd",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 3\nElementType = MET_SHORT\n"
               "ElementDataFile = s.%d 1 3 1\n");
    expect_input_error(dir / "v.mhd", "s.2\" is missing");
}

TEST(ReadVolume, RefusesASlicePatternThatIsNotOneIntegerConversion) {
    // The pattern comes from the file and goes to snprintf: %s or %n there would read or write
    // memory, so anything but one %d is bad input.
    const fs::path dir = fresh_dir("slice_format");
    write_text(dir / "v.mhd",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 3\nElementType = MET_SHORT\n"
               "ElementDataFile = s.%s%n 1 3 1\n");
    expect_input_error(dir / "v.mhd", "expected a name with one %d");
    write_text(dir / "v.mhd",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 3\nElementType = MET_SHORT\n"
               "ElementDataFile = s.%d 1 9223372036854775806 1\n");
    expect_input_error(dir / "v.mhd", "expected 0 to 1000000");
}

// A NIfTI whose stored orientation is not finite, not normal or not 3D: ITK's matrix code
// would abort the process on it (fuzz_nii findings: an sform with NaN ended glint info in
// SIGABRT, one with a subnormal entry in an endless SVD).
TEST(ReadVolume, RefusesANiftiOrientationThatIsNotFiniteOrSingular) {
    const fs::path dir = fresh_dir("nifti_orientation");
    write_volume(small_volume(), dir / "v.nii");
    std::string bytes;
    {
        std::ifstream in(dir / "v.nii", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    ASSERT_GT(bytes.size(), 348u);
    auto with_floats = [&](std::size_t at, std::vector<float> values) {
        std::string b = bytes;
        b[254] = 1;  // sform_code: the sform is used
        b[255] = 0;
        for (std::size_t k = 0; k < values.size(); ++k) std::memcpy(&b[at + 4 * k], &values[k], 4);
        return b;
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    write_text(dir / "nan.nii", with_floats(280, {-1, 0, nan, nan}));
    expect_input_error(dir / "nan.nii", "srow_x[2] = nan");
    // A subnormal entry: ITK's float SVD of it never returned (a fuzz_nii timeout).
    write_text(dir / "subnormal.nii", with_floats(280, {-1, 0, 1.4349296e-42f, 0}));
    expect_input_error(dir / "subnormal.nii", "srow_x[2] = 1.43493e-42");
    // srow_x = srow_y: two axes the same, the grid is flat.
    write_text(dir / "flat.nii", with_floats(280, {1, 0, 0, 0, 1, 0, 0, 0}));
    expect_input_error(dir / "flat.nii", "expected finite axes that span 3D");
}

// niftilib writes its own "** ERROR" lines to stderr for these before ITK throws: glint refuses
// them first, so the user reads one line.
TEST(ReadVolume, RefusesANiftiDatatypeOrDimensionNiftilibWouldPrintAbout) {
    const fs::path dir = fresh_dir("nifti_datatype");
    write_volume(small_volume(), dir / "v.nii");
    std::string bytes;
    {
        std::ifstream in(dir / "v.nii", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::string bad = bytes;
    bad[70] = static_cast<char>(0x0f);  // datatype 9999 = 0x270f
    bad[71] = static_cast<char>(0x27);
    write_text(dir / "datatype.nii", bad);
    expect_input_error(dir / "datatype.nii", "NIfTI datatype 9999, expected one of NIfTI's codes");
    bad = bytes;
    bad[40] = 9;  // dim[0]
    write_text(dir / "dims.nii", bad);
    expect_input_error(dir / "dims.nii",
                       "expected 1 to 7 dimensions");  // read as swapped: 9 fits neither order
}

// A NUL inside a header key made MetaIO loop (a fuzz_mha timeout; the input is the regression
// seed fuzz/corpus/mha/regression_nul_in_header_key.mha): any control byte in the header is
// refused with its line, before MetaIO reads the file.
TEST(ReadVolume, RefusesAMetaImageHeaderThatIsNotKeyValueText) {
    const fs::path dir = fresh_dir("header_control_byte");
    std::string header =
        "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n"
        "ElementDataFile = LOCAL\n";
    header.insert(header.find("NDims") + 5, std::string("\0entDat\x01", 8));
    write_text(dir / "v.mha", header + std::string(8 * 8 * 8 * 2, '\0'));
    expect_input_error(dir / "v.mha", "MetaImage header line 2 holds the control byte 0x0");
    // A key or a value of a few hundred bytes overran MetaIO's 255-byte fields (libc aborted:
    // fuzz_mha; the seeds regression_long_header_key.mha and regression_long_header_value.mha):
    // lines are refused above 254 bytes, keys that are not identifiers of up to 64 characters.
    const std::string rest = "DimSize = 8 8 8\nElementType = MET_SHORT\nElementDataFile = LOCAL\n" +
                             std::string(1024, '\0');
    write_text(dir / "long.mha",
               "ObjectType = Image\nNDims" + std::string(300, '\xff') + " = 3\n" + rest);
    expect_input_error(dir / "long.mha", "MetaImage header line 2 is 309 bytes long");
    write_text(dir / "long.mha",
               "ObjectType = Image" + std::string(240, 'x') + "\nNDims = 3\n" + rest);
    expect_input_error(dir / "long.mha", "MetaImage header line 1 is 258 bytes long");
    write_text(dir / "key.mha",
               "ObjectType = Image\nNDims" + std::string(30, '\xff') + " = 3\n" + rest);
    expect_input_error(dir / "key.mha", "MetaImage header line 2 has the key \"NDims???");
    write_text(dir / "nodata.mha",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n");
    expect_input_error(dir / "nodata.mha", "no ElementDataFile");
    // MetaIO divided by the step of a data-file value with a space that is no slice pattern
    // (SIGFPE: fuzz_mha; the seed regression_data_file_not_a_pattern.mha).
    write_text(dir / "pattern.mha",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n"
               "ElementDataFile = LOCObjectType = Image%\n");
    expect_input_error(dir / "pattern.mha", "expected LOCAL, LIST, a file name or a slice pattern");
    write_text(dir / "pattern.mha",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n"
               "ElementDataFile = s.%d 1 8 0\n");
    expect_input_error(dir / "pattern.mha", "step > 0");
    // Binary voxels after ElementDataFile = LOCAL are not header: a clean file still reads.
    write_text(dir / "ok.mha",
               "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n"
               "ElementDataFile = LOCAL\n" +
                   std::string(8 * 8 * 8 * 2, '\x01'));
    EXPECT_EQ(read_volume(dir / "ok.mha").geometry.voxel_count(), 512u);
}

TEST(ReadVolume, RefusesAZeroSpacingOrASingularDirection) {
    const fs::path dir = fresh_dir("bad_geometry");
    write_text(dir / "v.raw", std::string(8 * 8 * 8 * 2, '\0'));
    const std::string header =
        "ObjectType = Image\nNDims = 3\nDimSize = 8 8 8\nElementType = MET_SHORT\n";
    write_text(dir / "zero.mhd", header + "ElementSpacing = 0 1 1\nElementDataFile = v.raw\n");
    expect_input_error(dir / "zero.mhd", "a spacing other than 0");
    write_text(dir / "flat.mhd",
               header + "TransformMatrix = 1 0 0 1 0 0 0 0 1\nElementDataFile = v.raw\n");
    expect_input_error(dir / "flat.mhd", "expected finite axes that span 3D");
}

// A header may declare terabytes of voxels in a file of a few hundred bytes (fuzz_mha and
// fuzz_nii findings: ITK tried to allocate 600 GB); refused before anything is allocated.
TEST(ReadVolume, RefusesMoreVoxelsThanTheFileOrTheBudgetHolds) {
    const fs::path dir = fresh_dir("budget");
    write_text(dir / "big.mha",
               "ObjectType = Image\nNDims = 3\nDimSize = 1000 1000 1000\nElementType = MET_SHORT\n"
               "ElementDataFile = LOCAL\n" +
                   std::string(64, '\0'));
    expect_input_error(dir / "big.mha", "-byte file \"big.mha\" can hold");
    write_volume(small_volume(), dir / "v.nii.gz");
    EXPECT_NO_THROW((void)read_volume(dir / "v.nii.gz"));
    try {
        (void)read_volume(dir / "v.nii.gz", 100);
        ADD_FAILURE() << "read past the voxel budget";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("more than the limit 100"), std::string::npos)
            << e.what();
    }
}

// MetaIO reads "NDims = = -3" as billions of array entries from a failed stream (a fuzz_mha
// timeout): NDims is refused first.
TEST(ReadVolume, RefusesAMetaImageNDimsThatIsNotASmallInteger) {
    const fs::path dir = fresh_dir("ndims");
    write_text(dir / "v.mha",
               "ObjectType = Image\nNDims = = -3\nDimSize = 6 6 4\nElementType = MET_SHORT\n"
               "ElementDataFile = LOCAL\n" +
                   std::string(288, '\0'));
    expect_input_error(dir / "v.mha", "NDims = \"= -3\", expected an integer from 1 to 4");
}

TEST(ReadVolume, RejectsA2DImage) {
    const fs::path dir = fresh_dir("image2d");
    write_text(dir / "v.raw", std::string(8 * 8 * 2, '\0'));
    write_text(
        dir / "v.mhd",
        "ObjectType = Image\nNDims = 2\nDimSize = 8 8\nElementType = MET_SHORT\nElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "2D image");
}

TEST(ReadVolume, RejectsA4DImage) {
    const fs::path dir = fresh_dir("image4d");
    write_text(dir / "v.raw", std::string(8 * 8 * 8 * 3 * 2, '\0'));
    write_text(
        dir / "v.mhd",
        "ObjectType = Image\nNDims = 4\nDimSize = 8 8 8 3\nElementType = MET_SHORT\nElementDataFile = v.raw\n");
    expect_input_error(dir / "v.mhd", "4D image");
}

TEST(ReadVolume, RejectsAFolderWithoutDicom) {
    const fs::path dir = fresh_dir("no_dicom");
    write_text(dir / "notes.txt", "not a DICOM file\n");
    expect_input_error(dir, "no DICOM series");
}

// Issue 23 item 6: a truncated file in a DICOM folder aborted inside GDCM (SIGABRT).
TEST(ReadVolume, RejectsAFolderHoldingOnlyATruncatedFileBeforeGdcmSeesIt) {
    const fs::path dir = fresh_dir("dicom_truncated");
    write_text(dir / "f", std::string("\x08\x00\x05\x00", 4));
    expect_input_error(
        dir, "no DICOM series in it (1 file(s) are not DICOM files; first \"f\": 4 bytes");
}

TEST(ReadVolume, ReadsADicomSeriesBesideATruncatedFile) {
    const Volume v = small_volume();
    const fs::path dir = fresh_dir("dicom_beside") / "series";
    write_dicom_series(v, dir);
    write_text(dir / "f", std::string("\x08\x00\x05\x00", 4));
    const Volume back = read_volume(dir);
    EXPECT_EQ(back.voxels, v.voxels);
}

// Issue 52: a series with a slice missing, or one refused as truncated, was read at 2.111 mm
// spacing instead of 2 mm without a word. It is refused, naming the gap.
TEST(ReadVolume, RefusesADicomSeriesWithASliceMissingOrCut) {
    const Volume v = small_volume();
    for (const bool cut : {false, true}) {
        const fs::path dir = fresh_dir(cut ? "dicom_gap_cut" : "dicom_gap") / "series";
        write_dicom_series(v, dir);
        if (cut) fs::resize_file(dir / "slice0007.dcm", 200);
        else fs::remove(dir / "slice0007.dcm");
        try {
            (void)read_volume(dir);
            ADD_FAILURE() << "a series with a gap was read";
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("the DICOM series has a gap: slices 7 and 8 of 15"), std::string::npos)
                << m;
            EXPECT_NE(m.find("2.6 mm apart, the others 1.3 mm"), std::string::npos) << m;
        }
    }
}

TEST(DicomCheck, NamesWhatIsWrongWithACutFile) {
    const Volume v = small_volume();
    const fs::path dir = fresh_dir("dicom_cut") / "series";
    write_dicom_series(v, dir);
    const fs::path slice = fs::directory_iterator(dir)->path();
    EXPECT_EQ(detail::dicom_file_problem(slice), "");
    fs::resize_file(slice, fs::file_size(slice) - 7);
    EXPECT_NE(detail::dicom_file_problem(slice).find("the file has"), std::string::npos)
        << detail::dicom_file_problem(slice);
    fs::resize_file(slice, 200);
    EXPECT_NE(detail::dicom_file_problem(slice), "");
    EXPECT_NE(detail::dicom_file_problem(dir).find("not a regular file"), std::string::npos);
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
    EXPECT_THROW((void)load_surface(fs::path(GLINT_TEST_DATA_DIR) / "cube.obj", {.iso = 1.0}),
                 InputError);
    EXPECT_EQ(load_surface(fs::path(GLINT_TEST_DATA_DIR) / "cube.obj", {}).mesh.triangle_count(),
              12u);
}

TEST(ReadVolume, MissingFileIsBadInput) {
    EXPECT_THROW((void)read_volume(fs::path(GLINT_TEST_OUTPUT_DIR) / "none.nii.gz"), InputError);
}

}  // namespace
}  // namespace glint
