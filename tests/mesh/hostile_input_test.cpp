// Hostile input (issue 16): counts the file cannot hold, scene graphs that nest or expand
// without bound, the triangle budget, and cancellation while loading. Each is refused at once
// with one line naming the file and the limit, never a crash, hang or runaway allocation.
// Inputs found by the fuzzers (fuzz/) are kept here as bytes.
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/io.h"

#include "tests/mesh/load_error.h"
#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <typeinfo>

namespace glint {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

fs::path write_bytes(const std::string& name, const std::string& bytes) {
    return test::write_bytes(test::output_dir("hostile_input_test"), name, bytes);
}

using test::load_error;

const std::string kAsciiTriangle =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

// glTF 2.0 with `nodes` (JSON text) and one one-triangle mesh (3 positions, no buffer data:
// the checks run on the JSON before anything reads buffers).
std::string gltf(const std::string& nodes, const std::string& scene_nodes = "[0]") {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + scene_nodes +
           R"(}],"nodes":)" + nodes +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
           R"("accessors":[{"componentType":5126,"count":3,"type":"VEC3"}]})";
}

// A chain of `depth` nodes, each the child of the one before.
std::string chain(int depth) {
    std::string nodes = "[";
    for (int i = 0; i < depth; ++i) {
        if (i > 0) nodes += ',';
        nodes +=
            i + 1 < depth ? R"({"children":[)" + std::to_string(i + 1) + "]}" : R"({"mesh":0})";
    }
    return nodes + "]";
}

TEST(HostileInput, RefusesAsciiPlyElementOfTwoToThe63EmptyEntriesAtOnce) {
    const auto path =
        write_bytes("empty_entries.ply",
                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                    "property float y\nproperty float z\nelement junk 9223372036854775808\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n");
    const auto start = Clock::now();
    const std::string msg = load_error<InputError>(path);
    EXPECT_LT(Clock::now() - start, std::chrono::seconds(1));
    EXPECT_CONTAINS(msg, path.string());
    EXPECT_CONTAINS(msg, "element \"junk\" declares 9223372036854775808 items");
    EXPECT_CONTAINS(msg, "bytes follow");
}

TEST(HostileInput, RefusesAsciiPlyCountTheBodyCannotHold) {
    std::string text = kAsciiTriangle;
    text.replace(text.find("vertex 3"), 8, "vertex 4000000000");
    const auto path = write_bytes("huge_ascii.ply", text);
    const std::string msg = load_error<InputError>(path);
    EXPECT_CONTAINS(msg, "element \"vertex\" declares 4000000000 items of at least 6 byte(s)");
}

TEST(HostileInput, RefusesBinaryPlyCountOfEmptyItemsBeyondTheFile) {
    const auto path =
        write_bytes("empty_binary.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
                    "property float y\nproperty float z\nelement nothing 18446744073709551615\n"
                    "end_header\n" +
                        std::string(12, '\0'));
    EXPECT_CONTAINS(load_error<InputError>(path),
                    "element \"nothing\" declares 18446744073709551615");
}

TEST(HostileInput, RefusesGltfNodesNestedThousandsDeep) {
    const auto path = write_bytes("deep.gltf", gltf(chain(5000)));
    const std::string msg = load_error<InputError>(path);
    EXPECT_CONTAINS(msg, path.string());
    EXPECT_CONTAINS(msg, "nest 5000 levels deep");
    EXPECT_CONTAINS(msg, "limit 64");
}

TEST(HostileInput, AcceptsGltfNestedWithinTheLimit) {
    // note: assimp then fails on the missing buffer; the nesting check itself passes.
    const auto path = write_bytes("shallow.gltf", gltf(chain(64)));
    const std::string msg = load_error<InputError>(path);
    EXPECT_EQ(msg.find("levels deep"), std::string::npos) << msg;
}

TEST(HostileInput, RefusesGltfNodeDagExpandingToTwoToThe40Instances) {
    // Node i has node i+1 twice as its child: 41 nodes, 2^41 - 1 instances once expanded.
    std::string nodes = "[";
    for (int i = 0; i < 40; ++i)
        nodes += R"({"children":[)" + std::to_string(i + 1) + "," + std::to_string(i + 1) + "]},";
    nodes += R"({"mesh":0}])";
    const auto path = write_bytes("dag.gltf", gltf(nodes));
    const std::string msg = load_error<InputError>(path);
    EXPECT_CONTAINS(msg, "expands to 2199023255551 node instances");
    EXPECT_CONTAINS(msg, "limit 100000");
}

TEST(HostileInput, RefusesGltfNodeCycle) {
    const auto path = write_bytes("cycle.gltf", gltf(R"([{"children":[1]},{"children":[0]}])"));
    EXPECT_CONTAINS(load_error<InputError>(path), "cycle");
}

// fuzz_gltf: assimp 5.2 read a line loop past its index buffer (SIGSEGV); fuzz_glb: a line strip
// without positions made it allocate 68 GB. glint reads surfaces: line primitives and
// primitives without positions are refused before assimp sees them.
TEST(HostileInput, RefusesGltfLinePrimitivesAndPrimitivesWithoutPositions) {
    const std::string line_loop =
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":2}]}],)"
        R"("accessors":[{"componentType":5126,"count":3,"type":"VEC3"},)"
        R"({"componentType":5123,"count":3,"type":"SCALAR"}]})";
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("line_loop.gltf", line_loop)),
        "glTF mesh 0 primitive 0: mode 2 (lines), expected 0 (points) or 4, 5, 6 (triangles)");
    std::string no_positions = line_loop;
    no_positions.replace(no_positions.find(R"("attributes")"), 12, R"("atqributes")");
    no_positions.replace(no_positions.find(R"("mode":2)"), 8, R"("mode":4)");
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("no_positions.gltf", no_positions)),
                    "no POSITION accessor");
    // fuzz_glb: a triangle strip whose index accessor counts 0 made assimp allocate 2^64 bytes
    // (regression seed fuzz/corpus/glb/regression_strip_of_no_vertices.glb).
    std::string empty_strip = line_loop;
    empty_strip.replace(empty_strip.find(R"("mode":2)"), 8, R"("mode":5)");
    empty_strip.replace(empty_strip.rfind(R"("count":3)"), 9, R"("count":0)");
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("empty_strip.gltf", empty_strip)),
        "glTF mesh 0 primitive 0: draws 0 vertices (indices accessor count), expected at least 3");
}

// fuzz_glb: an 18-byte file named .glb without the "glTF" magic made assimp try every importer
// it has by content, and one read past its buffer (regression seed
// fuzz/corpus/glb/regression_not_a_glb.glb). Only what assimp's glTF importers claim goes on:
// a GLB with its magic and version 1 or 2, glTF JSON whose asset.version starts with 1 or 2.
TEST(HostileInput, RefusesGltfThatAssimpsGltfImportersWouldNotClaim) {
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("not.glb", R"(as": {indexarrayon)")),
        "a .glb file that does not start with \"glTF\" (found \"as\":\"), expected a binary glTF");
    std::string glb = "glTF";
    const std::uint32_t header[4] = {7, 40, 20, 0x4E4F534Au};
    glb.append(reinterpret_cast<const char*>(header), sizeof header);
    glb += std::string(20, ' ');
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("v7.glb", glb)),
                    "GLB version 7, expected 1 or 2");
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("empty.gltf", "{}")),
                    "glTF JSON has no asset.version");
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("v3.gltf", R"({"asset":{"version":"3.0"}})")),
        "asset.version \"3.0\", expected \"1.0\" or \"2.0\"");
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("vnum.gltf", R"({"asset":{"version":2}})")),
                    "asset.version 2,");
}

// Formats glint does not document are not handed to assimp's other importers (unfuzzed here).
TEST(HostileInput, RefusesFormatsOutsideTheDocumentedOnes) {
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("model.3ds", std::string(64, '\x4d'))),
        "unknown mesh format (extension .3ds and no known signature); expected PLY, STL, OBJ, OFF, glTF/GLB or VTK");
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("scene.dae", "<?xml version=\"1.0\"?><COLLADA/>")),
        "unknown mesh format (extension .dae");
}

TEST(HostileInput, RefusesDeeplyNestedJson) {
    const auto path =
        write_bytes("nested.gltf", R"({"asset":{"extras":)" + std::string(100000, '[') + "}}");
    EXPECT_CONTAINS(load_error<InputError>(path), "deeper than 128 levels");
}

TEST(HostileInput, RefusesGlbWhoseJsonNestsTooDeep) {
    std::string json = gltf(chain(200));
    while (json.size() % 4 != 0) json += ' ';
    std::string glb = "glTF";
    auto u32 = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(static_cast<std::uint32_t>(20 + json.size()));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534Au);
    glb += json;
    const auto path = write_bytes("deep.glb", glb);
    EXPECT_CONTAINS(load_error<InputError>(path), "nest 200 levels deep");
}

TEST(HostileInput, RefusesGltfWhoseInstancesExceedTheTriangleBudget) {
    const auto path = write_bytes("budget.gltf", gltf(R"([{"children":[1,1,1]},{"mesh":0}])"));
    const std::string msg = load_error<InputError>(path, LoadOptions{.max_triangles = 2});
    EXPECT_CONTAINS(msg, "3 triangles, more than the limit 2 (--max-triangles)");
}

TEST(HostileInput, RefusesOffCountsTheFileCannotHold) {
    const auto path = write_bytes("huge.off", "OFF\n100000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_CONTAINS(load_error<InputError>(path), "OFF vertex list declares 100000000 items");
}

TEST(HostileInput, EveryReaderHonoursTheTriangleBudget) {
    const LoadOptions one{.max_triangles = 1};
    std::string two = kAsciiTriangle;
    two.replace(two.find("face 1"), 6, "face 2");
    two += "3 0 2 1\n";
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("two.ply", two), one),
                    "limit 1 (--max-triangles)");
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("quad.obj",
                                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
                                           "f 1 3 4\n"),
                               one),
        "limit 1");
    const std::string facet =
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\n";
    EXPECT_CONTAINS(load_error<InputError>(
                        write_bytes("two.stl", "solid x\n" + facet + facet + "endsolid x\n"), one),
                    "limit 1");
    std::string binary_stl(80, ' ');
    const std::uint32_t facets = 2;
    binary_stl.append(reinterpret_cast<const char*>(&facets), 4);
    binary_stl += std::string(100, '\0');
    EXPECT_CONTAINS(load_error<InputError>(write_bytes("two_binary.stl", binary_stl), one),
                    "binary STL declares 2 triangles, more than the limit 1");
    EXPECT_CONTAINS(
        load_error<InputError>(write_bytes("two.vtk",
                                           "# vtk DataFile Version 3.0\nx\nASCII\n"
                                           "DATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 "
                                           "1 1 0 0 1 0\nPOLYGONS 1 5\n4 0 1 2 3\n"),
                               one),
        "limit 1");
    EXPECT_NO_THROW((void)load_mesh(write_bytes("one.ply", kAsciiTriangle), one));
}

TEST(HostileInput, LoadingStopsWhenCancelled) {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 20000\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n";
    for (int i = 0; i < 20000; ++i) text += "0 0 0\n";
    const auto path = write_bytes("cancel.ply", text);
    request_cancel(15);
    EXPECT_THROW((void)load_mesh(path, LoadOptions{.allow_points_only = true}), Cancelled);
    reset_cancel();
    EXPECT_NO_THROW((void)load_mesh(path, LoadOptions{.allow_points_only = true}));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Found by fuzz/fuzz_off (libFuzzer timeout: assimp read "2222222222222222" glued to "OFF"
// as the vertex count and ran for minutes).
TEST(HostileInput, RefusesOffCountGluedToTheKeyword) {
    const std::string bytes(
        "OFF2222222222222222\n3 1\x0c\x0c\x0c 0\n0-  1 0 p 0 25z#502 \xff\xff\xffz q", 55);
    const auto path = test::write_bytes(test::output_dir("hostile_input_test"), "glued.off", bytes);
    EXPECT_CONTAINS(load_error<InputError>(path),
                    "OFF vertex list declares 2222222222222222 items");
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Found by fuzz/fuzz_off in CI (AddressSanitizer out of memory: 39 GB): after "nOFF" assimp
// reads a dimension first, so "nOFF 1 1 N" is 1 vertex and N faces, and it allocates N faces
// before reading any. The plain reading (1 vertex, 1 face) let it through.
TEST(HostileInput, RefusesOffFaceCountAsAssimpReadsIt) {
    const auto path = test::write_bytes(test::output_dir("hostile_input_test"), "dimension.off",
                                        "nOFF 1 1 2443364828\n0 0 0\n3 0 0 0\n");
    EXPECT_CONTAINS(load_error<InputError>(path),
                    "OFF face list (as assimp reads the header) declares 2443364828 items");
}

// A 2-D "nOFF" file that assimp reads (dimension 2, then the counts) still loads.
TEST(HostileInput, LoadsTwoDimensionalOff) {
    const auto path = test::write_bytes(test::output_dir("hostile_input_test"), "flat.off",
                                        "nOFF\n2\n3 1 0\n0 0\n1 0\n0 1\n3 0 1 2\n");
    EXPECT_EQ(load_mesh(path).mesh.triangle_count(), 1u);
}

}  // namespace
}  // namespace glint
