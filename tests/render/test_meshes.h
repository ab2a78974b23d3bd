// Meshes made in code for the render tests (STYLE.md §7): exact, small, any resolution.
#pragma once

#include "mesh/mesh.h"

namespace glint::test {

/// Icosphere: subdivided icosahedron projected onto a sphere; normals exact (p / r).
/// level 0 = 20 triangles, each level ×4.
Mesh make_icosphere(int level, double radius = 1.0);

/// Latitude/longitude sphere (`rings` latitude bands, 2·rings longitudes, fans at the
/// poles); normals exact.
Mesh make_uv_sphere(int rings, double radius = 1.0);

/// Square patch [-half, half]² in z = amplitude · sin(2π x / wavelength), n×n quads split
/// along alternating diagonals; normals exact (the analytic surface normal).
Mesh make_corrugated_plane(int n, double half, double amplitude, double wavelength);

/// Rectangular patch [-half_x, half_x] × [-half_y, half_y], nx × ny quads, same surface.
Mesh make_corrugated_strip(int nx, int ny, double half_x, double half_y, double amplitude,
                           double wavelength);

/// Bumpy closed surface (sphere with radius 1 + 0.15·sin(5θ)·cos(3φ)), angle-weighted
/// normals: a mesh with curvature everywhere for backend agreement.
Mesh make_bumpy_sphere(int level);

}  // namespace glint::test
