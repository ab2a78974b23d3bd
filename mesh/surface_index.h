// One spatial index (an Embree BVH) over a mesh's triangles, built once per mesh per run and
// shared by everything that casts rays or asks for closest points on that surface: the fit and
// the shape distances (registration/closest_point.h), the sweep's CPU renderer and the
// pictures' (render/renderer.h, FrameOptions::surface_index). A run used to build five BVHs,
// three of them over the reference; with the index shared it builds one per mesh.
//
// No Embree type appears here: render/ and registration/ reach the scene through
// embree_scene() and include Embree's header themselves.
#pragma once

#include "mesh/mesh.h"

#include <cstddef>
#include <memory>
#include <span>

namespace glint {

/// Triangles above which the BVH is built compact: on 2M triangles it took 60 MB less (113
/// instead of 173 MB) for 6 % more time per ray, and the frames and closest points are the same.
inline constexpr std::size_t kCompactIndexTriangles = 500'000;

/// A BVH over a copy of a mesh's positions and triangles (the mesh may change or go away
/// afterwards). Watertight (Embree's robust mode): a ray through a vertex or an edge cannot
/// fall through between its triangles (without it, on AVX2 machines, a landmark picked exactly
/// at a vertex hit the far side of the surface; AVX-512 happened to close the crack). Immutable and thread-safe once built; share it with
/// std::shared_ptr.
class SurfaceIndex {
  public:
    /// \throw InputError a mesh without triangles; DeviceError Embree could not build it.
    explicit SurfaceIndex(const Mesh& mesh);
    ~SurfaceIndex();
    SurfaceIndex(const SurfaceIndex&) = delete;
    SurfaceIndex& operator=(const SurfaceIndex&) = delete;

    [[nodiscard]] std::span<const Vec3f> positions() const;
    [[nodiscard]] std::span<const Triangle> triangles() const;
    /// Whether this indexes `mesh` as it is now (the same positions and triangles).
    [[nodiscard]] bool indexes(const Mesh& mesh) const;
    /// The Embree scene (an RTCScene) for render/ and registration/.
    [[nodiscard]] void* embree_scene() const;

    /// BVHs built in this process so far (tests and benchmarks count them).
    [[nodiscard]] static std::size_t builds();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The index of a mesh, shared.
[[nodiscard]] std::shared_ptr<const SurfaceIndex> index_surface(const Mesh& mesh);

}  // namespace glint
