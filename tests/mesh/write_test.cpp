// Writers: PLY and VTK round trips keep every per-vertex array; inputs are never overwritten.
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/write.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("write_test"); }

// An octahedron with colours, two scalar fields and labels.
Mesh octahedron() {
    Mesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (std::size_t v = 0; v < 6; ++v) {
        m.colors.push_back({static_cast<std::uint8_t>(40 * v), 7, static_cast<std::uint8_t>(255 - v)});
        m.labels.push_back(static_cast<std::int32_t>(v % 2 ? -3 : 12));
    }
    m.set_scalar("damage", {0.0f, 0.25f, 0.5f, 1e-7f, -2.0f, 1e6f});
    m.set_scalar("quality", {1, 2, 3, 4, 5, 6});
    m.normals.assign(m.positions.begin(), m.positions.end());
    return m;
}

const LoadOptions kAsStored{.weld = false, .drop_degenerate = false, .drop_unused = false,
                            .compute_normals = false};

void expect_round_trip(const Mesh& in, const Mesh& out) {
    EXPECT_EQ(out.positions, in.positions);
    EXPECT_EQ(out.triangles, in.triangles);
    EXPECT_EQ(out.normals, in.normals);
    EXPECT_EQ(out.colors, in.colors);
    EXPECT_EQ(out.labels, in.labels);
    ASSERT_EQ(out.scalars.size(), in.scalars.size());
    for (std::size_t f = 0; f < in.scalars.size(); ++f) {
        EXPECT_EQ(out.scalars[f].name, in.scalars[f].name);
        EXPECT_EQ(out.scalars[f].values, in.scalars[f].values);  // floats stored bit-exactly
    }
}

TEST(WritePly, RoundTripKeepsPositionsNormalsColoursScalarsAndLabels) {
    const Mesh in = octahedron();
    const auto path = out_dir() / "octahedron.ply";
    write_ply(in, path);
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    EXPECT_EQ(loaded.report.format, "ply-binary-le");
    expect_round_trip(in, loaded.mesh);
}

TEST(WritePly, HeaderNamesEveryScalarAsAFloatProperty) {
    const auto path = out_dir() / "header.ply";
    write_ply(octahedron(), path);
    std::ifstream file(path, std::ios::binary);
    std::string header, line;
    while (std::getline(file, line) && line != "end_header") header += line + "\n";
    EXPECT_NE(header.find("property float damage\n"), std::string::npos) << header;
    EXPECT_NE(header.find("property float quality\n"), std::string::npos) << header;
    EXPECT_NE(header.find("property uchar red\n"), std::string::npos) << header;
    EXPECT_NE(header.find("property int label\n"), std::string::npos) << header;
}

TEST(WritePly, AssimpReadsTheWrittenGeometry) {
    const Mesh in = octahedron();
    const auto path = out_dir() / "octahedron_assimp.ply";
    write_ply(in, path);
    const LoadedMesh loaded = load_mesh_assimp(path, kAsStored);
    EXPECT_EQ(loaded.mesh.positions, in.positions);
    EXPECT_EQ(loaded.mesh.triangles, in.triangles);
}

TEST(WriteVtk, RoundTripKeepsPositionsNormalsColoursScalarsAndLabels) {
    const Mesh in = octahedron();
    const auto path = out_dir() / "octahedron.vtk";
    write_vtk(in, path);
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    EXPECT_EQ(loaded.report.format, "vtk-binary");
    expect_round_trip(in, loaded.mesh);
}

TEST(WriteMesh, ChoosesTheFormatByExtension) {
    const Mesh in = octahedron();
    write_mesh(in, out_dir() / "by_ext.PLY");
    write_mesh(in, out_dir() / "by_ext.vtk");
    EXPECT_EQ(load_mesh(out_dir() / "by_ext.PLY").report.format, "ply-binary-le");
    EXPECT_EQ(load_mesh(out_dir() / "by_ext.vtk").report.format, "vtk-binary");
    EXPECT_THROW(write_mesh(in, out_dir() / "by_ext.stl"), InputError);
}

TEST(WriteMesh, RefusesToOverwriteALoadedInput) {
    const auto path = out_dir() / "input.ply";
    write_ply(octahedron(), path);
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_THROW(write_ply(loaded.mesh, path), InputError);
    EXPECT_THROW(write_vtk(loaded.mesh, path), InputError);
}

TEST(WriteMesh, ThrowsIoErrorForAMissingFolderAndLeavesNothing) {
    const auto path = out_dir() / "no_such_folder" / "x.ply";
    EXPECT_THROW(write_ply(octahedron(), path), IoError);
    EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace glint
