// VTK legacy POLYDATA reader: sections, attributes, cell layouts, the real Smart-DOC files.
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("vtk_test"); }

fs::path write_text(const std::string& name, const std::string& text) {
    const fs::path path = out_dir() / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Repairs off: the mesh is exactly what the file stores.
const LoadOptions kAsStored{
    .weld = false, .drop_degenerate = false, .drop_unused = false, .compute_normals = false};

// A unit square of two triangles carrying every kind of section glint must read or skip.
const std::string kSquare =
    "# vtk DataFile Version 4.2\n3D Slicer output. SPACE=LPS\nASCII\nDATASET POLYDATA\n"
    "FIELD FieldData 2\nMaterialNames 1 2 string\nmtl1\nNO_MATERIAL\n\n"
    "MaterialLibraries 1 1 string\nx.mtl\n\n"
    "POINTS 4 double\n0 0 0 1 0 0\n1 1 0 0 1 0\n"
    "VERTICES 1 2\n1 0\nLINES 1 3\n2 0 1\n"
    "POLYGONS 2 8\n3 0 1 2\n3 0 2 3\n"
    "CELL_DATA 4\nSCALARS cellscalar int 1\nLOOKUP_TABLE default\n1 2 3 4\n"
    "FIELD FieldData 1\nMaterialIds 1 4 int\n0 0 0 0\n"
    "POINT_DATA 4\nSCALARS thickness float\nLOOKUP_TABLE default\n0.5 1.5 2.5 3.5\n"
    "SCALARS label int 1\nLOOKUP_TABLE default\n0 3 3 0\n"
    "NORMALS Normals float\n0 0 1 0 0 1 0 0 1 0 0 1\n"
    "VECTORS v float\n1 0 0 1 0 0 1 0 0 1 0 0\n"
    "COLOR_SCALARS rgb 3\n1 0 0 0 1 0 0 0 1 1 1 1\n"
    "FIELD FieldData 2\nquality%20index 1 4 double\n9 8 7 6\ntwo 2 4 float\n1 2 3 4 5 6 7 8\n";

TEST(VtkReader, ReadsPointDataAndSkipsEverythingElse) {
    const LoadedMesh loaded = load_mesh(write_text("square.vtk", kSquare), kAsStored);
    const Mesh& m = loaded.mesh;
    EXPECT_EQ(loaded.report.format, "vtk-ascii");
    EXPECT_EQ(loaded.report.reader, MeshReader::Vtk);
    ASSERT_EQ(m.vertex_count(), 4u);
    EXPECT_EQ(m.positions[2], Vec3f(1, 1, 0));
    ASSERT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.triangles[1], (Triangle{0, 2, 3}));
    ASSERT_NE(m.find_scalar("thickness"), nullptr);
    EXPECT_EQ(m.find_scalar("thickness")->values, (std::vector<float>{0.5f, 1.5f, 2.5f, 3.5f}));
    ASSERT_NE(m.find_scalar("quality index"), nullptr);
    EXPECT_EQ(m.find_scalar("quality index")->values, (std::vector<float>{9, 8, 7, 6}));
    EXPECT_EQ(m.find_scalar("two"), nullptr);         // 2 components: skipped, reported
    EXPECT_EQ(m.find_scalar("cellscalar"), nullptr);  // cell data: skipped
    EXPECT_EQ(m.labels, (std::vector<std::int32_t>{0, 3, 3, 0}));
    ASSERT_EQ(m.colors.size(), 4u);
    EXPECT_EQ(m.colors[0], (Rgb8{255, 0, 0}));
    EXPECT_EQ(m.colors[3], (Rgb8{255, 255, 255}));
    ASSERT_TRUE(m.has_normals());
    EXPECT_EQ(m.normals[1], Vec3f(0, 0, 1));
    std::string warnings;
    for (const auto& w : loaded.report.warnings) warnings += w + "\n";
    EXPECT_NE(warnings.find("VERTICES (1 cells) skipped"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("LINES (1 cells) skipped"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("\"two\""), std::string::npos) << warnings;
}

TEST(VtkReader, ConvertsTriangleStripsKeepingOrientation) {
    const auto path = write_text("strip.vtk",
                                 "# vtk DataFile Version 3.0\nstrip\nASCII\nDATASET POLYDATA\n"
                                 "POINTS 5 float\n0 0 0 0 1 0 1 0 0 1 1 0 2 0 0\n"
                                 "TRIANGLE_STRIPS 1 6\n5 0 1 2 3 4\n");
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    ASSERT_EQ(loaded.mesh.triangle_count(), 3u);
    EXPECT_EQ(loaded.mesh.triangles[0], (Triangle{0, 1, 2}));
    EXPECT_EQ(loaded.mesh.triangles[1], (Triangle{2, 1, 3}));
    EXPECT_EQ(loaded.mesh.triangles[2], (Triangle{2, 3, 4}));
    // All three face the same way (-z for this strip).
    for (std::size_t t = 0; t < 3; ++t) {
        const auto& tri = loaded.mesh.triangles[t];
        const Vec3f n = (loaded.mesh.positions[tri[1]] - loaded.mesh.positions[tri[0]])
                            .cross(loaded.mesh.positions[tri[2]] - loaded.mesh.positions[tri[0]]);
        EXPECT_LT(n.z(), 0.0f) << "triangle " << t;
    }
}

TEST(VtkReader, ReadsTheVtk51OffsetsAndConnectivityLayout) {
    const auto path =
        write_text("v51.vtk",
                   "# vtk DataFile Version 5.1\nnew\nASCII\nDATASET POLYDATA\n"
                   "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\n"
                   "POLYGONS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2 3\n");
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    EXPECT_EQ(loaded.mesh.triangle_count(), 2u);
    EXPECT_EQ(loaded.report.split_polygons, 1u);
}

// A fuzz_vtk finding (UBSan: the first of no words): a blank line between a cell section's
// header and its OFFSETS. The reader looks past blank lines there as it does elsewhere.
TEST(VtkReader, ABlankLineBeforeOffsetsIsSkipped) {
    const auto path =
        write_text("v51_blank.vtk",
                   "# vtk DataFile Version 5.1\nnew\nASCII\nDATASET POLYDATA\n"
                   "POINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\n"
                   "POLYGONS 2 4\n\nOFFSETS vtktypeint64\n0 4\n\nCONNECTIVITY vtktypeint64\n0 1 2 "
                   "3\n");
    EXPECT_EQ(load_mesh(path, kAsStored).mesh.triangle_count(), 2u);
    // The finding itself: refused with a message, whatever it says.
    const auto found =
        write_text("v51_finding.vtk",
                   "# vtk DataFile Version 5.1File Version 5.1\nt\nASCII\n"
                   "DATASET POLYDATA\nPOINTS 3 double\n0 0 0 1 0 0 0 1 0\n"
                   "POLYGONS  0 0 1 0\n\nOFFSETS vtktypeint64\n0 3\npeint64\n0 1 2\n");
    EXPECT_THROW((void)load_mesh(found, kAsStored), InputError);
}

fs::path shared(const std::string& rel) { return fs::path(GLINT_SHARED_DATA_DIR) / rel; }

struct RealVtk {
    const char* file;
    const char* format;
    std::size_t vertices;
    std::size_t triangles;
};

// Counts from shared/data/README.md (as stored in the file).
class RealVtkFiles : public ::testing::TestWithParam<RealVtk> {};

TEST_P(RealVtkFiles, LoadWithTheReadmeCounts) {
    const RealVtk& c = GetParam();
    const auto path = shared(std::string("condyle_skull_cbct_smartdoc/") + c.file);
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const LoadedMesh stored = load_mesh(path, kAsStored);
    EXPECT_EQ(stored.report.format, c.format);
    EXPECT_EQ(stored.mesh.vertex_count(), c.vertices);
    EXPECT_EQ(stored.mesh.triangle_count(), c.triangles);
    // With the default repairs every change is counted: file counts minus repairs.
    const LoadedMesh repaired = load_mesh(path);
    const LoadReport& r = repaired.report;
    EXPECT_EQ(r.file_vertices, c.vertices);
    EXPECT_EQ(r.file_triangles, c.triangles);
    EXPECT_EQ(repaired.mesh.vertex_count(), c.vertices - r.welded_vertices - r.unused_vertices);
    EXPECT_EQ(repaired.mesh.triangle_count(),
              c.triangles - r.degenerate_triangles - r.duplicate_triangles);
    // 3D Slicer's exports ("3D Slicer output. SPACE=LPS") are in millimetres (issue 51); the
    // condyle's header ("vtk output") says nothing.
    EXPECT_EQ(repaired.mesh.unit, c.file == std::string("condyle.vtk") ? "" : "mm");
}

INSTANTIATE_TEST_SUITE_P(SmartDoc, RealVtkFiles,
                         ::testing::Values(RealVtk{"skull.vtk", "vtk-binary", 47610, 94526},
                                           RealVtk{"skull_d.vtk", "vtk-ascii", 9552, 18904},
                                           RealVtk{"condyle.vtk", "vtk-ascii", 1002, 2000}),
                         [](const auto& param_info) {
                             std::string n = param_info.param.file;
                             return n.substr(0, n.find('.')) == "skull_d"
                                        ? std::string("SkullDecimated")
                                    : n.starts_with("skull") ? std::string("Skull")
                                                             : std::string("Condyle");
                         });

TEST(VtkReader, KeepsTheCondylesParaPhiScalar) {
    const auto path = shared("condyle_skull_cbct_smartdoc/condyle.vtk");
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const LoadedMesh loaded = load_mesh(path);
    const ScalarField* phi = loaded.mesh.find_scalar("_paraPhi");
    ASSERT_NE(phi, nullptr);
    EXPECT_NEAR(phi->values[0], 6.2831853f, 1e-5f);  // first value in the file
}

}  // namespace
}  // namespace glint
