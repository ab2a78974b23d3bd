// Vertex normals that do not depend on tessellation.
//
// Each triangle contributes its unit normal weighted by its interior angle at the vertex
// (Thürmer & Wüthrich 1998, "Computing vertex normals from polygonal facets"). Unlike
// area or uniform weighting, the result does not change when a triangle fan is split
// differently, which is what the paper's resolution claim needs.
#pragma once

#include "mesh/mesh.h"

namespace glint {

/// Computes angle-weighted unit vertex normals into mesh.normals. A vertex used by no
/// (non-degenerate) triangle gets (0,0,0).
void compute_vertex_normals(Mesh& mesh);

}  // namespace glint
