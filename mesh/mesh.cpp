#include "mesh/mesh.h"

#include "mesh/error.h"

#include <utility>

namespace glint {

const ScalarField* Mesh::find_scalar(const std::string& name) const {
    for (const auto& field : scalars)
        if (field.name == name) return &field;
    return nullptr;
}

ScalarField* Mesh::find_scalar(const std::string& name) {
    for (auto& field : scalars)
        if (field.name == name) return &field;
    return nullptr;
}

void Mesh::set_scalar(std::string name, std::vector<float> values) {
    GLINT_ASSERT(values.size() == positions.size(),
                 "scalar '" + name + "' has " + std::to_string(values.size()) + " values for " +
                     std::to_string(positions.size()) + " vertices");
    if (auto* field = find_scalar(name)) {
        field->values = std::move(values);
        return;
    }
    scalars.push_back({std::move(name), std::move(values)});
}

Bounds bounds(const Mesh& mesh) {
    Bounds box;
    for (const auto& p : mesh.positions) box.extend(p);
    return box;
}

std::vector<double> triangle_areas(const Mesh& mesh) {
    std::vector<double> areas(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3d a = mesh.positions[tri[0]].cast<double>();
        const Vec3d b = mesh.positions[tri[1]].cast<double>();
        const Vec3d c = mesh.positions[tri[2]].cast<double>();
        areas[t] = 0.5 * (b - a).cross(c - a).norm();
    }
    return areas;
}

std::vector<double> vertex_areas(const Mesh& mesh) {
    std::vector<double> areas(mesh.positions.size(), 0.0);
    const auto tri_areas = triangle_areas(mesh);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (auto v : mesh.triangles[t]) areas[v] += tri_areas[t] / 3.0;
    return areas;
}

double surface_area(const Mesh& mesh) {
    double total = 0.0;
    for (double a : triangle_areas(mesh)) total += a;
    return total;
}

Vec3f face_normal(const Mesh& mesh, std::size_t t) {
    const auto& tri = mesh.triangles[t];
    const Vec3d a = mesh.positions[tri[0]].cast<double>();
    const Vec3d b = mesh.positions[tri[1]].cast<double>();
    const Vec3d c = mesh.positions[tri[2]].cast<double>();
    const Vec3d n = (b - a).cross(c - a);
    const double len = n.norm();
    // note: a zero-area triangle has no direction; callers treat the zero vector as "none".
    if (!(len > 0.0)) return Vec3f::Zero();
    return (n / len).cast<float>();
}

}  // namespace glint
