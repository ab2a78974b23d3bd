// Closest-point and ray queries on a triangle mesh (an Embree BVH behind a wall: no Embree
// type appears here).
//
// Sign: the sign of p − c against the *angle-weighted pseudo-normal* of the feature the
// closest point c lies on (the face normal inside a face, the sum of the two face normals on
// an edge, the angle-weighted vertex normal at a vertex; Bærentzen & Aanæs 2005). Unlike the
// interpolated or the face normal, it never flips sign near edges and vertices of a closed
// surface. Positive = outside (on the side the normals point to).
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/surface_index.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

namespace glint {

/// Which feature of its triangle a closest point lies on.
enum class ClosestFeature : std::uint8_t { Face, Edge, Vertex };

struct ClosestPoint {
    bool found = false;    ///< false when nothing lies within the query radius
    Vec3d point{0, 0, 0};  ///< closest point on the mesh
    std::uint32_t triangle = 0;
    Vec3d barycentric{0, 0, 0};  ///< of `point` in `triangle`
    double distance = std::numeric_limits<double>::infinity();
    double signed_distance = std::numeric_limits<double>::infinity();  ///< + outside, − inside
    Vec3d normal{0, 0, 0};  ///< interpolated unit vertex normal at `point`
    ClosestFeature feature = ClosestFeature::Face;
};

struct RayHit {
    bool hit = false;
    double t = std::numeric_limits<double>::infinity();  ///< distance along the unit ray
    Vec3d point{0, 0, 0};
    std::uint32_t triangle = 0;
    Vec3d barycentric{0, 0, 0};
    Vec3d normal{0, 0, 0};  ///< interpolated unit vertex normal
};

/// A BVH over a mesh for many closest-point and ray queries. Move-only; thread-safe queries.
/// The index keeps a copy of the geometry (or, borrowing(), reads the caller's). Normals are
/// computed (angle-weighted) when absent.
class ClosestPointIndex {
  public:
    /// \throw InputError an empty mesh; DeviceError Embree could not build (its message).
    explicit ClosestPointIndex(const Mesh& mesh);
    /// An index that reads `mesh` in place instead of copying it (its BVH has its own copy of
    /// the positions): `mesh` must outlive the index, unchanged. A mesh without normals is
    /// copied as above. \throw as the constructor.
    [[nodiscard]] static ClosestPointIndex borrowing(const Mesh& mesh);
    /// An index over `mesh` (borrowed, as borrowing()) that queries a BVH built already and
    /// shared with the run's other users of the surface (mesh/surface_index.h).
    /// \pre `index` indexes `mesh`. \throw as the constructor.
    ClosestPointIndex(const Mesh& mesh, std::shared_ptr<const SurfaceIndex> index);
    ~ClosestPointIndex();
    ClosestPointIndex(ClosestPointIndex&&) noexcept;
    ClosestPointIndex& operator=(ClosestPointIndex&&) noexcept;
    ClosestPointIndex(const ClosestPointIndex&) = delete;
    ClosestPointIndex& operator=(const ClosestPointIndex&) = delete;

    /// Closest point to q within max_distance (found = false when none).
    [[nodiscard]] ClosestPoint closest(
        const Vec3d& q, double max_distance = std::numeric_limits<double>::infinity()) const;
    /// Many queries, in parallel over the machine's cores.
    [[nodiscard]] std::vector<ClosestPoint> closest(
        std::span<const Vec3d> queries,
        double max_distance = std::numeric_limits<double>::infinity()) const;
    /// First hit of a ray (direction need not be unit).
    [[nodiscard]] RayHit intersect(const Ray& ray) const;

    [[nodiscard]] const Mesh& mesh() const;

  private:
    ClosestPointIndex(const Mesh& mesh, bool borrow, std::shared_ptr<const SurfaceIndex> index);
    [[nodiscard]] ClosestPoint query(const Vec3d& q, double max_distance) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The pixel (u, v) of a camera as a surface point: ray picking.
[[nodiscard]] RayHit pick(const ClosestPointIndex& index, const Camera& camera, double u, double v);

/// Signed distance of every point to the mesh (see the sign rule above).
[[nodiscard]] std::vector<double> signed_distances(const ClosestPointIndex& index,
                                                   std::span<const Vec3d> points);

}  // namespace glint
