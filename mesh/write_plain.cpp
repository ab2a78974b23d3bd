// STL, OBJ and OFF: the geometry-only formats (mesh/write.h). They carry positions and
// triangles, and the unit in the comment glint's reader looks for (mesh/units.cpp
// unit_from_header); colours, scalars and labels have no place in them.
#include "mesh/atomic_file.h"
#include "mesh/detail/write_common.h"
#include "mesh/write.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <string>

namespace glint {

namespace fs = std::filesystem;

namespace {

void put_u32(detail::StreamBuffer& buffer, std::uint32_t value) {
    static_assert(std::endian::native == std::endian::little, "STL is little endian");
    char b[4];
    std::memcpy(b, &value, 4);
    buffer.append(b, 4);
}

void put_f32(detail::StreamBuffer& buffer, float value) {
    put_u32(buffer, std::bit_cast<std::uint32_t>(value));
}

// "%.9g" gives back every float32 exactly when read again.
void put_point(detail::StreamBuffer& buffer, const char* prefix, const Vec3f& p) {
    char line[96];
    std::snprintf(line, sizeof line, "%s%.9g %.9g %.9g\n", prefix, static_cast<double>(p.x()),
                  static_cast<double>(p.y()), static_cast<double>(p.z()));
    buffer += line;
}

// The comment naming the unit, when the mesh has one ("" otherwise).
std::string unit_comment(const Mesh& mesh) {
    return mesh.unit.empty() ? std::string() : "# unit " + mesh.unit + "\n";
}

}  // namespace

void write_stl(const Mesh& mesh, const fs::path& path) {
    detail::check_sizes(mesh, path);
    // The 80-byte header must not start with "solid" (readers would take it for ASCII STL).
    std::string header = "glint binary STL";
    if (!mesh.unit.empty()) header += ", unit " + mesh.unit;
    header.resize(80, ' ');
    write_atomically(path, [&](std::ostream& out) {
        detail::StreamBuffer buffer(out);
        buffer += header;
        put_u32(buffer, static_cast<std::uint32_t>(mesh.triangles.size()));
        for (const auto& t : mesh.triangles) {
            const Vec3f& a = mesh.positions[t[0]];
            const Vec3f& b = mesh.positions[t[1]];
            const Vec3f& c = mesh.positions[t[2]];
            const Vec3f normal = (b - a).cross(c - a).normalized();
            for (const Vec3f& p : {normal, a, b, c})
                for (int k = 0; k < 3; ++k) put_f32(buffer, std::isfinite(p[k]) ? p[k] : 0.0f);
            buffer += std::string_view("\0\0", 2);  // attribute byte count
        }
        buffer.flush();
    });
}

void write_obj(const Mesh& mesh, const fs::path& path) {
    detail::check_sizes(mesh, path);
    write_atomically(path, [&](std::ostream& out) {
        detail::StreamBuffer buffer(out);
        buffer += "# written by glint\n" + unit_comment(mesh);
        for (const Vec3f& p : mesh.positions) put_point(buffer, "v ", p);
        for (const auto& t : mesh.triangles)  // OBJ counts vertices from 1
            buffer += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
                      std::to_string(t[2] + 1) + "\n";
        buffer.flush();
    });
}

void write_off(const Mesh& mesh, const fs::path& path) {
    detail::check_sizes(mesh, path);
    write_atomically(path, [&](std::ostream& out) {
        detail::StreamBuffer buffer(out);
        buffer += "OFF\n" + unit_comment(mesh) + std::to_string(mesh.positions.size()) + " " +
                  std::to_string(mesh.triangles.size()) + " 0\n";
        for (const Vec3f& p : mesh.positions) put_point(buffer, "", p);
        for (const auto& t : mesh.triangles)
            buffer += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
                      std::to_string(t[2]) + "\n";
        buffer.flush();
    });
}

}  // namespace glint
