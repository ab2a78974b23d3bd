// Procedural surfaces with known geometry: the simulator's ground truth.
//
// Every phantom exists at any resolution and in two tessellation schemes, so the paper's
// claim "resolution and triangulation do not change the result" can be tested on the same
// analytic surface meshed differently.
#pragma once

#include "mesh/mesh.h"

#include <functional>
#include <optional>
#include <string>

namespace glint {

enum class PhantomKind { Sphere, Ellipsoid, Torus, Condyle };
enum class TessellationScheme {
    Uv,   ///< latitude/longitude grid (poles are fans); for the torus: (u, v) grid
    Ico,  ///< subdivided icosahedron projected onto the surface; for the torus: a grid
          ///< with alternating diagonals and a half-cell offset between rings
};

struct PhantomOptions {
    PhantomKind kind = PhantomKind::Sphere;
    TessellationScheme scheme = TessellationScheme::Ico;
    /// Resolution: Uv: number of latitude rings (longitudes = 2×); Ico: subdivision level
    /// (0 = 20 triangles, each level ×4). Torus: rings around the tube (segments = 2×).
    int resolution = 4;
    /// Sizes in mesh units (mm for the condyle). Sphere: radii.x(); ellipsoid: semi-axes;
    /// torus: x = major radius, y = minor radius. Condyle: fixed shape scaled by radii.x()/10.
    Vec3d radii{10.0, 10.0, 10.0};
};

/// Builds a phantom surface with angle-weighted normals, unit "mm", closed and manifold.
/// \throw InputError resolution out of range (< 0 or too many vertices) or radii not > 0.
[[nodiscard]] Mesh make_phantom(const PhantomOptions& options);

/// The analytic outward unit normal of a phantom at (or nearest to) a point on it; the
/// condyle, being an implicit blend, returns the normalised gradient of its field.
[[nodiscard]] Vec3d phantom_normal(const PhantomOptions& options, const Vec3d& point);

/// Parses "sphere", "ellipsoid", "torus", "condyle" / "uv", "ico". \throw InputError.
[[nodiscard]] PhantomKind parse_phantom_kind(const std::string& text);
[[nodiscard]] TessellationScheme parse_scheme(const std::string& text);
[[nodiscard]] std::string to_string(PhantomKind kind);
[[nodiscard]] std::string to_string(TessellationScheme scheme);

}  // namespace glint
