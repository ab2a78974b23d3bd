#include "mesh/write.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"

#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>

namespace glint {

namespace fs = std::filesystem;

namespace {

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
                throw InputError("cannot write \"" + path.string() + "\": triangle " + std::to_string(t) +
                                 " uses vertex " + std::to_string(i) + ", mesh has " +
                                 std::to_string(n) + " vertices");
}

// Appends raw values in little- or big-endian byte order.
template <bool BigEndian>
struct Bytes {
    std::string buffer;

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

void write_ply(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    check_sizes(mesh, path);
    const std::size_t n = mesh.positions.size();
    const bool normals = options.write_normals && mesh.has_normals();
    const bool colors = options.write_colors && mesh.colors.size() == n && n > 0;
    const bool labels = options.write_labels && mesh.labels.size() == n && n > 0;
    const bool scalars = options.write_scalars;

    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by glint\n";
    if (!mesh.unit.empty()) header += "comment unit " + mesh.unit + "\n";
    header += "element vertex " + std::to_string(n) + "\n";
    header += "property float x\nproperty float y\nproperty float z\n";
    if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (colors) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (scalars)
        for (const auto& f : mesh.scalars) header += "property float " + safe_name(f.name) + "\n";
    if (labels) header += "property int label\n";
    header += "element face " + std::to_string(mesh.triangles.size()) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";

    Bytes<false> body;
    std::size_t per_vertex = 12 + (normals ? 12 : 0) + (colors ? 3 : 0) + (labels ? 4 : 0) +
                             (scalars ? 4 * mesh.scalars.size() : 0);
    body.buffer.reserve(per_vertex * n + 13 * mesh.triangles.size());
    for (std::size_t v = 0; v < n; ++v) {
        for (int k = 0; k < 3; ++k) body.put(mesh.positions[v][k]);
        if (normals)
            for (int k = 0; k < 3; ++k) body.put(mesh.normals[v][k]);
        if (colors)
            for (auto c : mesh.colors[v]) body.put(c);
        if (scalars)
            for (const auto& f : mesh.scalars) body.put(f.values[v]);
        if (labels) body.put(mesh.labels[v]);
    }
    for (const auto& t : mesh.triangles) {
        body.put(std::uint8_t{3});
        for (auto i : t) body.put(i);
    }
    write_atomically(path, [&](std::ostream& out) {
        out.write(header.data(), static_cast<std::streamsize>(header.size()));
        out.write(body.buffer.data(), static_cast<std::streamsize>(body.buffer.size()));
    });
}

void write_vtk(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    check_sizes(mesh, path);
    const std::size_t n = mesh.positions.size();
    const bool normals = options.write_normals && mesh.has_normals();
    const bool colors = options.write_colors && mesh.colors.size() == n && n > 0;
    const bool labels = options.write_labels && mesh.labels.size() == n && n > 0;
    const bool scalars = options.write_scalars && !mesh.scalars.empty();

    // Legacy VTK, BINARY: every array is big endian and followed by a newline.
    Bytes<true> out;
    auto text = [&](const std::string& s) { out.buffer += s; };
    text("# vtk DataFile Version 3.0\nglint mesh" + (mesh.unit.empty() ? std::string() : " unit " + mesh.unit) +
         "\nBINARY\nDATASET POLYDATA\n");
    text("POINTS " + std::to_string(n) + " float\n");
    for (const auto& p : mesh.positions)
        for (int k = 0; k < 3; ++k) out.put(p[k]);
    text("\nPOLYGONS " + std::to_string(mesh.triangles.size()) + " " +
         std::to_string(4 * mesh.triangles.size()) + "\n");
    for (const auto& t : mesh.triangles) {
        out.put(std::int32_t{3});
        for (auto i : t) out.put(static_cast<std::int32_t>(i));
    }
    text("\n");
    if (normals || colors || labels || scalars) {
        text("POINT_DATA " + std::to_string(n) + "\n");
        if (normals) {
            text("NORMALS Normals float\n");
            for (const auto& nv : mesh.normals)
                for (int k = 0; k < 3; ++k) out.put(nv[k]);
            text("\n");
        }
        if (colors) {
            text("COLOR_SCALARS rgb 3\n");  // BINARY colour scalars are unsigned bytes
            for (const auto& c : mesh.colors)
                for (auto b : c) out.put(b);
            text("\n");
        }
        if (scalars) {
            for (const auto& f : mesh.scalars) {
                text("SCALARS " + safe_name(f.name) + " float 1\nLOOKUP_TABLE default\n");
                for (float v : f.values) out.put(v);
                text("\n");
            }
        }
        if (labels) {
            text("SCALARS label int 1\nLOOKUP_TABLE default\n");
            for (auto l : mesh.labels) out.put(l);
            text("\n");
        }
    }
    write_atomically(path, [&](std::ostream& s) {
        s.write(out.buffer.data(), static_cast<std::streamsize>(out.buffer.size()));
    });
}

void write_mesh(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".ply") return write_ply(mesh, path, options);
    if (ext == ".vtk") return write_vtk(mesh, path, options);
    throw InputError("cannot write \"" + path.string() + "\": unknown extension \"" +
                     path.extension().string() + "\", expected .ply or .vtk");
}

}  // namespace glint
