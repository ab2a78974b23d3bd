// The triangle mesh every glint module works on: flat arrays indexed by vertex / triangle id.
#pragma once

#include "mesh/field_of_view.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace glint {

using Vec3f = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;
/// The "no value" of per-vertex and per-pixel float fields (not seen, not compared).
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
/// Three vertex ids, counter-clockwise seen from outside (the normal side).
using Triangle = std::array<std::uint32_t, 3>;
/// 8-bit sRGB colour.
using Rgb8 = std::array<std::uint8_t, 3>;

/// A named per-vertex scalar field (PLY property / VTK point-data array).
struct ScalarField {
    std::string name;
    std::vector<float> values;  ///< one per vertex
};

/// Axis-aligned bounding box; empty when min > max.
struct Bounds {
    Vec3f min{Vec3f::Constant(std::numeric_limits<float>::max())};
    Vec3f max{Vec3f::Constant(-std::numeric_limits<float>::max())};

    [[nodiscard]] bool is_empty() const { return (min.array() > max.array()).any(); }
    [[nodiscard]] Vec3f extent() const { return is_empty() ? Vec3f::Zero() : Vec3f(max - min); }
    [[nodiscard]] Vec3f center() const { return 0.5f * (min + max); }
    [[nodiscard]] float diagonal() const { return extent().norm(); }
    void extend(const Vec3f& p) {
        min = min.cwiseMin(p);
        max = max.cwiseMax(p);
    }
};

/// Triangle mesh. Invariants after loading/validation: every index < positions.size(),
/// normals empty or one per vertex (unit length), every field one value per vertex.
struct Mesh {
    std::vector<Vec3f> positions;
    std::vector<Triangle> triangles;
    std::vector<Vec3f> normals;        ///< per vertex, unit; empty until computed
    std::vector<Rgb8> colors;          ///< per vertex; optional
    std::vector<ScalarField> scalars;  ///< named per-vertex scalars; optional
    std::vector<std::int32_t> labels;  ///< per-vertex label (0 = none); optional
    std::string unit;                  ///< "mm", "m", … or "" when unknown
    /// The voxel grid a surface extracted from a volume was sampled on: columns are the grid's
    /// axes i, j, k scaled by its spacing (mesh units), in the mesh's frame (transform_mesh
    /// turns them with it). Unset for a mesh read from a file. Where two sheets of surface lie
    /// closer than a voxel the scan cannot place them apart (analysis/resolution.h).
    std::optional<Eigen::Matrix3d> voxel_axes;
    /// Where the acquisition a surface was extracted from saw (mesh/field_of_view.h), in the
    /// mesh's frame: empty for a mesh read from a file.
    FieldOfView field_of_view;
    /// Per vertex of a surface extracted from a volume, 1 where the volume's values stay within
    /// a few noise σ of the iso value for a voxel on either side (volume/contrast.h): noise and
    /// partial volume place that surface. Empty for a mesh read from a file; ignored when its
    /// size is not the vertex count (a mesh edited since).
    std::vector<std::uint8_t> faint;

    [[nodiscard]] std::size_t vertex_count() const { return positions.size(); }
    [[nodiscard]] std::size_t triangle_count() const { return triangles.size(); }
    [[nodiscard]] bool has_normals() const { return normals.size() == positions.size(); }

    /// The scalar field of that name, or nullptr.
    [[nodiscard]] const ScalarField* find_scalar(const std::string& name) const;
    [[nodiscard]] ScalarField* find_scalar(const std::string& name);
    /// Adds or replaces a scalar field; values.size() must equal vertex_count().
    void set_scalar(std::string name, std::vector<float> values);
};

/// Bounding box of the positions (of all vertices, used or not).
[[nodiscard]] Bounds bounds(const Mesh& mesh);

/// Area of each triangle.
[[nodiscard]] std::vector<double> triangle_areas(const Mesh& mesh);

/// Area associated with each vertex: one third of the area of every triangle using it
/// (barycentric dual area). Sums to the surface area.
[[nodiscard]] std::vector<double> vertex_areas(const Mesh& mesh);

/// Total surface area.
[[nodiscard]] double surface_area(const Mesh& mesh);

/// Unit geometric normal of triangle t (zero for a degenerate triangle).
[[nodiscard]] Vec3f face_normal(const Mesh& mesh, std::size_t t);

}  // namespace glint
