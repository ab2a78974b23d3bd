#include "mesh/write.h"

#include "mesh/atomic_file.h"
#include "mesh/detail/write_common.h"
#include "mesh/error.h"

#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace glint {

namespace fs = std::filesystem;
using detail::check_sizes;
using detail::safe_name;

namespace detail {

// Property / array names are single words in both formats: anything else becomes '_'.
std::string safe_name(const std::string& name) {
    std::string out = name.empty() ? std::string("scalar") : name;
    for (char& c : out)
        if (!std::isgraph(static_cast<unsigned char>(c))) c = '_';
    return out;
}

void check_sizes(const Mesh& mesh, const fs::path& path) {
    const std::size_t n = mesh.positions.size();
    auto bad = [&](const std::string& what, std::size_t count) {
        throw InputError("cannot write \"" + path.string() + "\": " + what + " has " +
                         std::to_string(count) + " values for " + std::to_string(n) + " vertices");
    };
    if (!mesh.normals.empty() && mesh.normals.size() != n) bad("normals", mesh.normals.size());
    if (!mesh.colors.empty() && mesh.colors.size() != n) bad("colors", mesh.colors.size());
    if (!mesh.labels.empty() && mesh.labels.size() != n) bad("labels", mesh.labels.size());
    for (const auto& f : mesh.scalars)
        if (f.values.size() != n) bad("scalar \"" + f.name + "\"", f.values.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (auto i : mesh.triangles[t])
            if (i >= n)
                throw InputError("cannot write \"" + path.string() + "\": triangle " +
                                 std::to_string(t) + " uses vertex " + std::to_string(i) +
                                 ", mesh has " + std::to_string(n) + " vertices");
}

}  // namespace detail

namespace {

// Appends raw values in little- or big-endian byte order.
template <bool BigEndian>
struct Bytes {
    detail::StreamBuffer& buffer;

    template <class T>
    void put(T value) {
        static_assert(sizeof(T) == 1 || sizeof(T) == 4);
        if constexpr (sizeof(T) == 1) {
            buffer.push_back(static_cast<char>(value));
        } else {
            auto u = std::bit_cast<std::uint32_t>(value);
            if constexpr (BigEndian) u = __builtin_bswap32(u);
            char b[4];
            std::memcpy(b, &u, 4);
            buffer.append(b, 4);
        }
    }
};

}  // namespace

namespace {

// The scalars a PLY carries, in order: every field under its own name (options: as
// scalar_<name>, the only names CloudCompare imports), then (options) the quality copy of one
// of them for MeshLab.
std::vector<std::pair<std::string, const ScalarField*>> ply_scalars(const Mesh& mesh,
                                                                    const fs::path& path,
                                                                    const WriteOptions& options) {
    std::vector<std::pair<std::string, const ScalarField*>> out;
    if (!options.write_scalars) return out;
    const std::string prefix = options.cloudcompare_names ? "scalar_" : "";
    for (const auto& f : mesh.scalars) out.emplace_back(prefix + safe_name(f.name), &f);
    if (!options.quality_scalar.empty()) {
        const ScalarField* q = mesh.find_scalar(options.quality_scalar);
        if (!q)
            throw InputError("cannot write \"" + path.string() + "\": quality scalar \"" +
                             options.quality_scalar + "\" is not a scalar of the mesh");
        if (!mesh.find_scalar("quality") || !prefix.empty()) out.emplace_back("quality", q);
    }
    return out;
}

}  // namespace

void write_ply(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    check_sizes(mesh, path);
    const std::size_t n = mesh.positions.size();
    const bool normals = options.write_normals && mesh.has_normals();
    const bool colors = options.write_colors && mesh.colors.size() == n && n > 0;
    const bool labels = options.write_labels && mesh.labels.size() == n && n > 0;
    const auto scalars = ply_scalars(mesh, path, options);

    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by glint\n";
    if (!mesh.unit.empty()) header += "comment unit " + mesh.unit + "\n";
    header += "element vertex " + std::to_string(n) + "\n";
    header += "property float x\nproperty float y\nproperty float z\n";
    if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (colors) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    for (const auto& [name, field] : scalars) header += "property float " + name + "\n";
    if (labels) header += "property int label\n";
    header += "element face " + std::to_string(mesh.triangles.size()) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";

    write_atomically(path, [&](std::ostream& out) {
        detail::StreamBuffer buffer(out);
        buffer += header;
        Bytes<false> body{buffer};
        for (std::size_t v = 0; v < n; ++v) {
            for (int k = 0; k < 3; ++k) body.put(mesh.positions[v][k]);
            if (normals)
                for (int k = 0; k < 3; ++k) body.put(mesh.normals[v][k]);
            if (colors)
                for (auto c : mesh.colors[v]) body.put(c);
            for (const auto& s : scalars) body.put(s.second->values[v]);
            if (labels) body.put(mesh.labels[v]);
        }
        for (const auto& t : mesh.triangles) {
            body.put(std::uint8_t{3});
            for (auto i : t) body.put(i);
        }
        buffer.flush();
    });
}

bool is_writable_mesh_path(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* known : {".ply", ".vtk", ".vtp", ".stl", ".obj", ".off"})
        if (ext == known) return true;
    return false;
}

void write_mesh(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".ply") return write_ply(mesh, path, options);
    if (ext == ".vtk") return write_vtk(mesh, path, options);
    if (ext == ".vtp") return write_vtp(mesh, path, options);
    if (ext == ".stl") return write_stl(mesh, path);
    if (ext == ".obj") return write_obj(mesh, path);
    if (ext == ".off") return write_off(mesh, path);
    throw InputError("cannot write \"" + path.string() + "\": unknown extension \"" +
                     path.extension().string() + "\", expected " + kWritableMeshExtensions);
}

}  // namespace glint
