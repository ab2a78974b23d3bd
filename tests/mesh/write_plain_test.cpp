// STL, OBJ and OFF writers: geometry and unit come back through glint's own reader.
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/write.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("write_plain_test"); }

// An octahedron in mm with coordinates that need all nine digits of a float.
Mesh octahedron_mm() {
    Mesh m;
    const float a = 1.0f / 3.0f;
    m.positions = {{a, 0, 0},  {-1, 0, 0},         {0, 1e-7f, 0},
                   {0, -1, 0}, {0, 0, 12345.678f}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    m.unit = "mm";
    return m;
}

const LoadOptions kAsStored{
    .weld = false, .drop_degenerate = false, .drop_unused = false, .compute_normals = false};

std::vector<Vec3f> sorted(std::vector<Vec3f> p) {
    std::sort(p.begin(), p.end(), [](const Vec3f& a, const Vec3f& b) {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    });
    return p;
}

// The triangles as their corners' positions: the same surface whatever the vertex order.
std::vector<std::array<float, 9>> corners(const Mesh& m) {
    std::vector<std::array<float, 9>> out;
    for (const auto& t : m.triangles) {
        std::array<float, 9> c{};
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) c[3 * k + d] = m.positions[t[k]][d];
        out.push_back(c);
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(WriteOff, KeepsPositionsTrianglesAndUnitExactly) {
    const Mesh in = octahedron_mm();
    const fs::path path = out_dir() / "octahedron.off";
    write_mesh(in, path);
    const LoadedMesh loaded = load_mesh(path, kAsStored);
    EXPECT_EQ(loaded.mesh.positions, in.positions);
    EXPECT_EQ(loaded.mesh.triangles, in.triangles);
    EXPECT_EQ(loaded.mesh.unit, "mm");
}

// OBJ (read by assimp, one vertex per corner) and STL (a vertex per corner) weld back.
TEST(WriteObjAndStl, GiveTheSameSurfaceAndUnitBack) {
    const Mesh in = octahedron_mm();
    for (const char* name : {"octahedron.obj", "octahedron.stl"}) {
        const fs::path path = out_dir() / name;
        write_mesh(in, path);
        const LoadedMesh loaded = load_mesh(path);
        EXPECT_EQ(loaded.mesh.unit, "mm") << name;
        EXPECT_EQ(sorted(loaded.mesh.positions), sorted(in.positions)) << name;
        EXPECT_EQ(corners(loaded.mesh), corners(in)) << name;
    }
}

TEST(WriteStl, IsBinaryWithTheUnitInItsHeader) {
    const Mesh in = octahedron_mm();
    const fs::path path = out_dir() / "header.stl";
    write_mesh(in, path);
    EXPECT_EQ(fs::file_size(path), 80u + 4u + 50u * in.triangles.size());
    std::ifstream file(path, std::ios::binary);
    std::string header(80, '\0');
    file.read(header.data(), 80);
    EXPECT_NE(header.rfind("solid", 0), 0u) << "an ASCII STL header: " << header;
    EXPECT_EQ(header.rfind("glint binary STL, unit mm", 0), 0u) << header;
}

TEST(WritePlain, RefusesToOverwriteALoadedInput) {
    for (const char* name : {"input.obj", "input.stl", "input.off"}) {
        const fs::path path = out_dir() / name;
        write_mesh(octahedron_mm(), path);
        const LoadedMesh loaded = load_mesh(path);
        EXPECT_THROW(write_mesh(loaded.mesh, path), InputError) << name;
    }
}

TEST(WriteMesh, KnowsItsExtensionsInAnyCase) {
    for (const char* name : {"a.ply", "a.VTK", "a.vtp", "a.Stl", "a.obj", "a.OFF"})
        EXPECT_TRUE(is_writable_mesh_path(name)) << name;
    for (const char* name : {"a.gltf", "a", "a.xyz"})
        EXPECT_FALSE(is_writable_mesh_path(name)) << name;
}

}  // namespace
}  // namespace glint
