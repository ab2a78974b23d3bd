#include "mesh/components.h"

#include "mesh/error.h"

#include <algorithm>
#include <numeric>

namespace glint {

UnionFind::UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }

std::uint32_t UnionFind::find(std::uint32_t x) {
    while (parent_[x] != x) {
        parent_[x] = parent_[parent_[x]];  // path halving
        x = parent_[x];
    }
    return x;
}

void UnionFind::unite(std::uint32_t a, std::uint32_t b) {
    const auto ra = find(a);
    const auto rb = find(b);
    if (ra != rb) parent_[ra] = rb;
}

std::size_t masked_components(const Mesh& mesh, std::span<const std::uint8_t> mask,
                              std::vector<std::int32_t>& component) {
    const std::size_t n = mesh.vertex_count();
    GLINT_ASSERT(mask.size() == n, "component mask does not match the mesh");
    UnionFind sets(n);
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k];
            const auto b = tri[(k + 1) % 3];
            if (mask[a] && mask[b]) sets.unite(a, b);
        }
    component.assign(n, -1);
    std::vector<std::int32_t> of_root(n, -1);
    std::size_t count = 0;
    for (std::size_t v = 0; v < n; ++v) {
        if (!mask[v]) continue;
        const auto r = sets.find(static_cast<std::uint32_t>(v));
        if (of_root[r] < 0) of_root[r] = static_cast<std::int32_t>(count++);
        component[v] = of_root[r];
    }
    return count;
}

std::vector<std::uint8_t> border_vertices(const Mesh& mesh) {
    // Every edge as a sorted vertex pair; an edge that appears once is a border.
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k];
            const auto b = tri[(k + 1) % 3];
            edges.push_back((std::uint64_t{std::min(a, b)} << 32) | std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    std::vector<std::uint8_t> border(mesh.vertex_count(), 0);
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) {
            border[edges[i] >> 32] = 1;
            border[edges[i] & 0xFFFFFFFFu] = 1;
        }
        i = j;
    }
    return border;
}

}  // namespace glint
