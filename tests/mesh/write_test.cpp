// Writers: PLY and VTK round trips keep every per-vertex array; inputs are never overwritten.
#include "mesh/write.h"
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("write_test"); }

// An octahedron with colours, two scalar fields and labels.
Mesh octahedron() {
    Mesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (std::size_t v = 0; v < 6; ++v) {
        m.colors.push_back(
            {static_cast<std::uint8_t>(40 * v), 7, static_cast<std::uint8_t>(255 - v)});
        m.labels.push_back(static_cast<std::int32_t>(v % 2 ? -3 : 12));
    }
    m.set_scalar("damage", {0.0f, 0.25f, 0.5f, 1e-7f, -2.0f, 1e6f});
    m.set_scalar("quality", {1, 2, 3, 4, 5, 6});
    m.normals.assign(m.positions.begin(), m.positions.end());
    return m;
}

const LoadOptions kAsStored{
    .weld = false, .drop_degenerate = false, .drop_unused = false, .compute_normals = false};

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
    EXPECT_EQ(loaded.report.format, "vtk-ascii");  // CloudCompare refuses binary legacy VTK
    expect_round_trip(in, loaded.mesh);            // shortest round-trip text: floats exact
}

std::string read_text(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream s;
    s << file.rdbuf();
    return s.str();
}

std::size_t count(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

TEST(WriteVtk, EveryArrayHasItsOwnPointDataLineAndNaNIsANumber) {
    // CloudCompare 2.11 reads one array per POINT_DATA line, VTK refuses a POINT_DATA inside
    // point data but follows CELL_DATA and back; VTK's ASCII reader fails on "nan".
    Mesh in = octahedron();
    in.scalars[0].values[2] = std::numeric_limits<float>::quiet_NaN();
    const auto path = out_dir() / "nan.vtk";
    write_vtk(in, path, {.vtk_legacy_nan = -9999.0f});
    const std::string text = read_text(path);
    EXPECT_EQ(count(text, "POINT_DATA 6\n"), 5u);  // normals, colours, 2 scalars, labels
    EXPECT_EQ(count(text, "CELL_DATA 0\nPOINT_DATA 6\n"), 4u);  // VTK's way back into point data
    EXPECT_EQ(count(text, "nan"), 0u);
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    EXPECT_EQ(loaded.mesh.find_scalar("damage")->values[2], -9999.0f);
    EXPECT_EQ(loaded.mesh.find_scalar("damage")->values[1], 0.25f);
}

TEST(WritePly, AddsQualityForMeshLabAndScalarNamesForCloudCompare) {
    Mesh in = octahedron();
    in.scalars.erase(in.scalars.begin() + 1);  // no field named quality of its own
    const auto path = out_dir() / "viewers.ply";
    write_ply(in, path, {.quality_scalar = "damage", .cloudcompare_names = true});
    // Each scalar once, as CloudCompare names it, then MeshLab's quality: no other copy.
    const std::string header = read_text(path).substr(0, read_text(path).find("end_header"));
    EXPECT_EQ(count(header, "property float scalar_damage\n"), 1u) << header;
    EXPECT_EQ(count(header, "property float damage\n"), 0u) << header;
    EXPECT_EQ(count(header, "property float quality\n"), 1u) << header;
    EXPECT_LT(header.find("scalar_damage"), header.find("quality")) << "the field comes first";
    // glint reads CloudCompare's scalar_<name> back as <name>.
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    ASSERT_NE(loaded.mesh.find_scalar("quality"), nullptr);
    ASSERT_NE(loaded.mesh.find_scalar("damage"), nullptr);
    EXPECT_EQ(loaded.mesh.find_scalar("scalar_damage"), nullptr);
    EXPECT_EQ(loaded.mesh.find_scalar("quality")->values, in.find_scalar("damage")->values);
    EXPECT_EQ(loaded.mesh.find_scalar("damage")->values, in.find_scalar("damage")->values);
    EXPECT_THROW(write_ply(in, out_dir() / "bad_quality.ply", {.quality_scalar = "nope"}),
                 InputError);
}

// Decodes the n-th inline binary DataArray of a .vtp as floats (after its UInt32 byte count).
std::vector<float> vtp_floats(const std::string& xml, const std::string& name) {
    const auto open = xml.find("Name=\"" + name + "\"");
    const auto begin = xml.find('>', open) + 1;
    const std::string b64 = xml.substr(begin, xml.find('<', begin) - begin);
    std::string bytes;
    int bits = 0, buffer = 0;
    for (char c : b64) {
        const auto at =
            std::string("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/").find(c);
        if (at == std::string::npos) break;
        buffer = (buffer << 6) | static_cast<int>(at);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            bytes.push_back(static_cast<char>((buffer >> bits) & 0xFF));
        }
    }
    std::uint32_t size = 0;
    std::memcpy(&size, bytes.data(), 4);
    std::vector<float> out(size / 4);
    std::memcpy(out.data(), bytes.data() + 4, size);
    return out;
}

TEST(WriteVtp, ArraysAreExactIncludingNaN) {
    Mesh in = octahedron();
    in.scalars[0].values[2] = std::numeric_limits<float>::quiet_NaN();
    const auto path = out_dir() / "octahedron.vtp";
    write_vtp(in, path);
    const std::string xml = read_text(path);
    EXPECT_NE(xml.find("NumberOfPoints=\"6\""), std::string::npos);
    EXPECT_NE(xml.find("NumberOfPolys=\"8\""), std::string::npos);
    const auto damage = vtp_floats(xml, "damage");
    ASSERT_EQ(damage.size(), 6u);
    EXPECT_TRUE(std::isnan(damage[2]));
    EXPECT_EQ(damage[5], 1e6f);
    const auto points = vtp_floats(xml, "Points");
    ASSERT_EQ(points.size(), 18u);
    EXPECT_EQ(points[3], -1.0f);  // vertex 1 = (-1, 0, 0)
}

// The first scalar is the one a viewer opens on: VTK makes the first SCALARS block the active
// scalars (a COLOR_SCALARS block before it would be), VTP names it in PointData's Scalars.
TEST(WriteVtkAndVtp, TheFirstScalarComesFirst) {
    const Mesh in = octahedron();
    write_vtk(in, out_dir() / "first.vtk");
    const std::string vtk = read_text(out_dir() / "first.vtk");
    EXPECT_LT(vtk.find("SCALARS damage"), vtk.find("NORMALS"));
    EXPECT_LT(vtk.find("SCALARS damage"), vtk.find("COLOR_SCALARS"));
    EXPECT_LT(vtk.find("SCALARS damage"), vtk.find("SCALARS quality"));
    write_vtp(in, out_dir() / "first.vtp");
    const std::string vtp = read_text(out_dir() / "first.vtp");
    EXPECT_NE(vtp.find("<PointData Scalars=\"damage\""), std::string::npos);
    EXPECT_LT(vtp.find("Name=\"damage\""), vtp.find("Name=\"Normals\""));
}

TEST(WriteMesh, ChoosesTheFormatByExtension) {
    const Mesh in = octahedron();
    write_mesh(in, out_dir() / "by_ext.PLY");
    write_mesh(in, out_dir() / "by_ext.vtk");
    EXPECT_EQ(load_mesh(out_dir() / "by_ext.PLY").report.format, "ply-binary-le");
    EXPECT_EQ(load_mesh(out_dir() / "by_ext.vtk").report.format, "vtk-ascii");
    EXPECT_THROW(write_mesh(in, out_dir() / "by_ext.xyz"), InputError);
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
