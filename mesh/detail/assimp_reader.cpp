#include "mesh/detail/assimp_reader.h"

#include "mesh/detail/scan.h"
#include "mesh/error.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <string_view>

namespace glint::detail {

namespace {

std::string extension_without_dot(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

struct Collector {
    Mesh mesh;
    const aiScene* scene = nullptr;
    std::size_t skipped_primitives = 0;
    bool colors_seen = false;
    bool normals_missing = false;

    std::string source;
    std::uint64_t max_triangles = 0;

    // Walks the node tree with an explicit stack (a deep tree must not overflow ours).
    void add_nodes(const aiNode* root) {
        std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{root, aiMatrix4x4()}};
        std::uint64_t visited = 0;
        while (!stack.empty()) {
            poll_cancel(++visited);
            const auto [node, parent] = stack.back();
            stack.pop_back();
            const aiMatrix4x4 world = parent * node->mTransformation;
            aiMatrix3x3 normal_matrix(world);
            normal_matrix.Inverse().Transpose();
            for (unsigned m = 0; m < node->mNumMeshes; ++m)
                if (node->mMeshes[m] < scene->mNumMeshes)
                    add_mesh(scene->mMeshes[node->mMeshes[m]], world, normal_matrix);
            for (unsigned c = node->mNumChildren; c-- > 0;)
                stack.emplace_back(node->mChildren[c], world);
        }
    }

    void add_mesh(const aiMesh* in, const aiMatrix4x4& world, const aiMatrix3x3& normal_matrix) {
        std::uint64_t faces = in->mNumFaces;
        check_triangle_budget(mesh.triangles.size() + faces, max_triangles, source,
                              "the scene's meshes add up to at least");
        throw_if_cancelled();
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        const bool has_normals = in->HasNormals();
        for (unsigned v = 0; v < in->mNumVertices; ++v) {
            const aiVector3D p = world * in->mVertices[v];
            mesh.positions.emplace_back(p.x, p.y, p.z);
            if (has_normals) {
                aiVector3D n = normal_matrix * in->mNormals[v];
                n.Normalize();
                mesh.normals.emplace_back(n.x, n.y, n.z);
            }
        }
        if (!has_normals) normals_missing = true;  // partial normals are dropped below
        if (in->HasVertexColors(0)) {
            colors_seen = true;
            mesh.colors.resize(base);
            for (unsigned v = 0; v < in->mNumVertices; ++v) {
                const aiColor4D& c = in->mColors[0][v];
                auto byte = [](float x) {
                    return static_cast<std::uint8_t>(std::clamp(x * 255.0f + 0.5f, 0.0f, 255.0f));
                };
                mesh.colors.push_back({byte(c.r), byte(c.g), byte(c.b)});
            }
        }
        for (unsigned f = 0; f < in->mNumFaces; ++f) {
            const aiFace& face = in->mFaces[f];
            if (face.mNumIndices < 3) {
                ++skipped_primitives;
                continue;
            }
            // note: aiProcess_Triangulate leaves only triangles among faces with >= 3 corners;
            // fan-split anyway so a file assimp did not triangulate cannot lose faces.
            if (face.mNumIndices > 3)
                check_triangle_budget(mesh.triangles.size() + face.mNumIndices - 2, max_triangles,
                                      source, "the scene's polygons split into at least");
            for (unsigned k = 2; k < face.mNumIndices; ++k)
                mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[k - 1],
                                          base + face.mIndices[k]});
        }
    }
};

// OBJ files name their material library; assimp loads the geometry without it. Say so.
void note_missing_mtl(const std::filesystem::path& path, LoadReport& report) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::string_view s(line);
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
        if (!s.starts_with("mtllib")) continue;
        s.remove_prefix(6);
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
        while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.remove_suffix(1);
        if (s.empty()) continue;
        const auto mtl = path.parent_path() / std::string(s);
        std::error_code ec;
        if (!std::filesystem::exists(mtl, ec))
            report.warnings.push_back("material library \"" + std::string(s) +
                                      "\" not found; materials ignored");
    }
}

}  // namespace

Mesh read_assimp(const std::filesystem::path& path, const std::string& source, LoadReport& report,
                 const LoadOptions& options) {
    Assimp::Importer importer;
    // note: ValidateDataStructure runs before Triangulate and rejects out-of-range indices;
    // without it assimp 5.2 crashes inside Triangulate on a PLY whose header lies about counts.
    const aiScene* scene =
        importer.ReadFile(path.string(), aiProcess_ValidateDataStructure | aiProcess_Triangulate);
    if (scene == nullptr || scene->mRootNode == nullptr)
        throw InputError(quoted_mesh(source) +
                         ": assimp cannot read it: " + importer.GetErrorString());
    report.format = extension_without_dot(path);
    report.reader = MeshReader::Assimp;
    if (report.format == "obj") note_missing_mtl(path, report);
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
        report.warnings.push_back("assimp marked the scene incomplete");

    Collector c;
    c.scene = scene;
    c.source = source;
    c.max_triangles = options.max_triangles;
    c.add_nodes(scene->mRootNode);
    if (c.normals_missing || c.mesh.normals.size() != c.mesh.positions.size())
        c.mesh.normals.clear();
    if (c.colors_seen) c.mesh.colors.resize(c.mesh.positions.size(), Rgb8{0, 0, 0});
    if (c.skipped_primitives > 0)
        report.warnings.push_back(std::to_string(c.skipped_primitives) +
                                  " point/line primitives skipped");
    report.file_vertices = c.mesh.positions.size();
    report.file_triangles = c.mesh.triangles.size();
    return std::move(c.mesh);
}

}  // namespace glint::detail
