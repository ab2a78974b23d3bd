// Which way a surface's triangles face: outward (counter-clockwise seen from outside, as glint
// and every format's convention expect) or inside out, as some STL exporters write them
// (issue 53). An inside-out surface has every normal reversed: its fit finds no compatible
// pairs and every dent would read as a bump.
#pragma once

#include "mesh/mesh.h"

namespace glint {

/// How outward the triangles face, in [-1, 1]: Σ area·n·(c − o) / Σ area·|c − o| over the
/// triangles (n unit normal, c centroid, o the surface's area-weighted centroid). For a closed
/// surface the numerator is 3 × its enclosed volume (the divergence theorem), so any closed
/// surface facing outward scores > 0 and inside out < 0 wherever o lies; a sphere scores ±1.
/// An open patch scores by its shape (a cap facing out near +1, a bowl seen from inside < 0).
/// 0 for a surface without area.
[[nodiscard]] double outward_score(const Mesh& mesh);

/// Whether every edge is shared by exactly two triangles (no border, no non-manifold edge).
[[nodiscard]] bool is_closed(const Mesh& mesh);

/// Reverses every triangle's winding and recomputes the vertex normals (they reverse too).
void reverse_winding(Mesh& mesh);

}  // namespace glint
