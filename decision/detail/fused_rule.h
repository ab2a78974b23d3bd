// The fused rule's steps (decision/decision.h). Internal to decision/decision.cpp.
#pragma once

#include "decision/decision.h"
#include "mesh/mesh.h"

#include <cstdint>
#include <vector>

namespace glint::detail {

/// Vertex neighbours through mesh edges, in compressed rows: neighbours of v are
/// index[offset[v] .. offset[v + 1]) (each shared edge listed once per triangle).
struct Adjacency {
    std::vector<std::uint32_t> offset;
    std::vector<std::uint32_t> index;
};
[[nodiscard]] Adjacency adjacency(const Mesh& mesh);

/// The damaged vertices under the fused rule (decision.h steps 2–5), before hole filling and
/// the size rule (find_regions does those). `excess` = shape excess per vertex.
[[nodiscard]] std::vector<std::uint8_t> fused_mask(const Mesh& reference,
                                                   const DecisionEvidence& evidence,
                                                   const std::vector<float>& excess,
                                                   const Floor& normal, const Floor& shape,
                                                   const DecisionOptions& options);

/// Fills Region::evidence: the strongest shape excess and normal deviation of each region
/// against their floors.
void describe_evidence(RegionResult& regions, const DecisionEvidence& evidence,
                       const std::vector<float>& excess, const Floor& normal, const Floor& shape);

}  // namespace glint::detail
