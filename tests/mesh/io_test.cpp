// load_mesh: every format loads, the fast PLY/STL readers return the same mesh as assimp,
// real files match the counts in shared/data/README.md.
#include "mesh/io.h"
#include "mesh/error.h"
#include "mesh/write.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path out_dir() { return test::output_dir("io_test"); }

fs::path write_bytes(const std::string& name, const std::string& bytes) {
    return test::write_bytes(out_dir(), name, bytes);
}

fs::path shared(const std::string& rel) { return fs::path(GLINT_SHARED_DATA_DIR) / rel; }

// A closed torus of rows x cols x 2 triangles with a little noise on every vertex, so no two
// positions coincide and no triangle is degenerate.
Mesh noisy_torus(int rows, int cols, unsigned seed) {
    Mesh m;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> noise(-0.01f, 0.01f);
    const float two_pi = 6.2831853f;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const float u = two_pi * static_cast<float>(i) / static_cast<float>(rows);
            const float v = two_pi * static_cast<float>(j) / static_cast<float>(cols);
            const float r = 1.0f + 0.3f * std::cos(v) + noise(rng);
            m.positions.emplace_back(r * std::cos(u), r * std::sin(u),
                                     0.3f * std::sin(v) + noise(rng));
        }
    auto id = [&](int i, int j) {
        return static_cast<std::uint32_t>((i % rows) * cols + (j % cols));
    };
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

std::string binary_stl(const Mesh& m) {
    std::string s(80, ' ');
    const auto n = static_cast<std::uint32_t>(m.triangles.size());
    s.append(reinterpret_cast<const char*>(&n), 4);
    for (const auto& t : m.triangles) {
        const float zero[3] = {0, 0, 0};
        s.append(reinterpret_cast<const char*>(zero), 12);
        for (auto i : t) s.append(reinterpret_cast<const char*>(m.positions[i].data()), 12);
        s.append(2, '\0');
    }
    return s;
}

std::string ascii_stl(const Mesh& m) {
    std::ostringstream s;
    s.precision(9);
    s << "solid torus\n";
    for (const auto& t : m.triangles) {
        s << "facet normal 0 0 0\nouter loop\n";
        for (auto i : t)
            s << "vertex " << m.positions[i].x() << " " << m.positions[i].y() << " "
              << m.positions[i].z() << "\n";
        s << "endloop\nendfacet\n";
    }
    s << "endsolid torus\n";
    return s.str();
}

// Vertex-order-free form of a mesh: sorted positions, and every triangle as its three corner
// positions rotated so the smallest comes first (winding kept), sorted.
using P = std::tuple<float, float, float>;
struct Canonical {
    std::vector<P> positions;
    std::vector<std::array<P, 3>> triangles;
    bool operator==(const Canonical&) const = default;
};

Canonical canonical(const Mesh& m) {
    Canonical c;
    auto p = [&](std::uint32_t i) {
        return P{m.positions[i].x(), m.positions[i].y(), m.positions[i].z()};
    };
    for (std::uint32_t v = 0; v < m.positions.size(); ++v) c.positions.push_back(p(v));
    std::sort(c.positions.begin(), c.positions.end());
    for (const auto& t : m.triangles) {
        std::array<P, 3> tri{p(t[0]), p(t[1]), p(t[2])};
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        c.triangles.push_back(tri);
    }
    std::sort(c.triangles.begin(), c.triangles.end());
    return c;
}

void expect_fast_equals_assimp(const fs::path& path, MeshReader fast_reader) {
    const LoadedMesh fast = load_mesh(path);
    const LoadedMesh slow = load_mesh_assimp(path);
    EXPECT_EQ(fast.report.reader, fast_reader);
    EXPECT_EQ(slow.report.reader, MeshReader::Assimp);
    EXPECT_EQ(fast.mesh.vertex_count(), slow.mesh.vertex_count());
    EXPECT_EQ(fast.mesh.triangle_count(), slow.mesh.triangle_count());
    EXPECT_EQ(fast.report.file_triangles, slow.report.file_triangles);
    EXPECT_EQ(fast.report.degenerate_triangles, slow.report.degenerate_triangles);
    EXPECT_EQ(fast.report.unused_vertices, slow.report.unused_vertices);
    EXPECT_TRUE(canonical(fast.mesh) == canonical(slow.mesh))
        << "fast and assimp meshes differ for " << path;
}

TEST(LoadMesh, FastPlyReturnsTheSameMeshAsAssimp) {
    const Mesh torus = noisy_torus(32, 32, 1);  // 2,048 triangles
    const auto path = out_dir() / "torus.ply";
    write_ply(torus, path, WriteOptions{.write_normals = false});
    expect_fast_equals_assimp(path, MeshReader::FastPly);
    EXPECT_TRUE(canonical(load_mesh(path).mesh) == canonical(torus));
}

TEST(LoadMesh, FastStlReturnsTheSameMeshAsAssimp) {
    const Mesh torus = noisy_torus(32, 32, 2);
    expect_fast_equals_assimp(write_bytes("torus_binary.stl", binary_stl(torus)),
                              MeshReader::FastStl);
    EXPECT_TRUE(canonical(load_mesh(out_dir() / "torus_binary.stl").mesh) == canonical(torus));
    // note: assimp's ASCII number parser (fast_atof) is not correctly rounded, so for ASCII the
    // reference is the generated mesh itself: 9 significant digits round-trip a float exactly.
    const LoadedMesh ascii = load_mesh(write_bytes("torus_ascii.stl", ascii_stl(torus)));
    EXPECT_EQ(ascii.report.format, "stl-ascii");
    EXPECT_TRUE(canonical(ascii.mesh) == canonical(torus));
}

TEST(LoadMesh, FastReadersMatchAssimpOnRealFiles) {
    const auto ply = shared("tooth_wear_edj/tooth_02/original.ply");
    const auto stl = shared("teeth_cbct_openfulljaw/Patient_26_tooth_19.stl");
    if (!fs::exists(ply) || !fs::exists(stl)) GTEST_SKIP() << "shared data not present";
    expect_fast_equals_assimp(ply, MeshReader::FastPly);
    expect_fast_equals_assimp(stl, MeshReader::FastStl);
}

TEST(LoadMesh, LoadsObjWithQuadsFromTheFixture) {
    const LoadedMesh loaded = load_mesh(fs::path(GLINT_TEST_DATA_DIR) / "cube.obj");
    EXPECT_EQ(loaded.report.format, "obj");
    EXPECT_EQ(loaded.report.reader, MeshReader::Assimp);
    EXPECT_EQ(loaded.mesh.vertex_count(), 8u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 12u);
    EXPECT_TRUE(loaded.mesh.has_normals());
}

TEST(LoadMesh, LoadsOff) {
    const auto path = write_bytes("tetra.off",
                                  "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                  "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n");
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.report.format, "off");
    EXPECT_EQ(loaded.mesh.vertex_count(), 4u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 4u);
}

// A tetrahedron as glTF 2.0: 4 float positions then 12 uint16 indices in one buffer.
std::string tetra_buffer() {
    const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::uint16_t idx[12] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    std::string b(reinterpret_cast<const char*>(p), sizeof p);
    b.append(reinterpret_cast<const char*>(idx), sizeof idx);
    return b;
}

std::string tetra_json(const std::string& buffer_uri) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
           R"("buffers":[{"byteLength":72)" +
           buffer_uri +
           R"(}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},)"
           R"({"buffer":0,"byteOffset":48,"byteLength":24}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
           R"("min":[0,0,0],"max":[1,1,1]},{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}]})";
}

std::string base64(const std::string& in) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
        std::uint32_t n = static_cast<std::uint8_t>(in[i]) << 16;
        if (i + 1 < in.size()) n |= static_cast<std::uint8_t>(in[i + 1]) << 8;
        if (i + 2 < in.size()) n |= static_cast<std::uint8_t>(in[i + 2]);
        out += k[(n >> 18) & 63];
        out += k[(n >> 12) & 63];
        out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
        out += i + 2 < in.size() ? k[n & 63] : '=';
    }
    return out;
}

TEST(LoadMesh, LoadsGltfWithAnEmbeddedBuffer) {
    const auto path =
        write_bytes("tetra.gltf", tetra_json(R"(,"uri":"data:application/octet-stream;base64,)" +
                                             base64(tetra_buffer()) + "\""));
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.report.format, "gltf");
    EXPECT_EQ(loaded.mesh.vertex_count(), 4u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 4u);
}

TEST(LoadMesh, LoadsGlb) {
    std::string json = tetra_json("");
    while (json.size() % 4) json += ' ';
    const std::string bin = tetra_buffer();  // 72 bytes, already a multiple of 4
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb =
        "glTF" + u32(2) + u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size())) +
        u32(static_cast<std::uint32_t>(json.size())) + "JSON" + json +
        u32(static_cast<std::uint32_t>(bin.size())) + std::string("BIN\0", 4) + bin;
    const LoadedMesh loaded = load_mesh(write_bytes("tetra.glb", glb));
    EXPECT_EQ(loaded.report.format, "glb");
    EXPECT_EQ(loaded.mesh.vertex_count(), 4u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 4u);
}

TEST(LoadMesh, LoadsObjWhoseMaterialLibraryIsMissingAndSaysSo) {
    const auto path = write_bytes(
        "with_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.mesh.triangle_count(), 1u);
    ASSERT_FALSE(loaded.report.warnings.empty());
    EXPECT_NE(loaded.report.warnings[0].find("nowhere.mtl"), std::string::npos);
}

TEST(LoadMesh, DetectsPlyByContentWhateverTheExtension) {
    const auto path = out_dir() / "torus_ply.mesh";
    write_ply(noisy_torus(8, 8, 3), out_dir() / "torus_small.ply");
    fs::copy_file(out_dir() / "torus_small.ply", path, fs::copy_options::overwrite_existing);
    EXPECT_EQ(load_mesh(path).report.format, "ply-binary-le");
}

TEST(LoadMesh, LoadsTheArtiSynthJawWithTheReadmeCounts) {
    const auto path = shared("mandible_cbct_artisynth/jaw_smooth.obj");
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
    const LoadedMesh loaded = load_mesh(path);
    EXPECT_EQ(loaded.mesh.vertex_count(), 20882u);
    EXPECT_EQ(loaded.mesh.triangle_count(), 41760u);
    // assimp hands OBJ over as one vertex per face corner; welding restores the shared ones,
    // which the report keeps apart from welds of the file's own vertices (there are none).
    EXPECT_EQ(loaded.report.importer_corner_vertices, 3u * 41760u);
    EXPECT_EQ(loaded.report.file_vertices, 20882u);
    EXPECT_EQ(loaded.report.welded_vertices, 0u);
}

}  // namespace
}  // namespace glint
