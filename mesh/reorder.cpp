#include "mesh/reorder.h"

#include "mesh/error.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <numeric>

namespace glint {

namespace {

// A triangle up to rotation of its corners: the smallest id first, winding kept.
std::array<std::uint32_t, 3> canonical(const Triangle& t) {
    const std::size_t k = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
    return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
}

template <class T>
void permute(std::vector<T>& values, const std::vector<std::uint32_t>& old_of_new) {
    if (values.empty()) return;
    std::vector<T> out(old_of_new.size());
    for (std::size_t i = 0; i < old_of_new.size(); ++i) out[i] = values[old_of_new[i]];
    values = std::move(out);
}

}  // namespace

ReorderMap reorder_for_locality(Mesh& mesh) {
    const std::size_t nv = mesh.positions.size();
    const std::size_t nt = mesh.triangles.size();
    ReorderMap map;
    if (nt == 0) {
        map.original_vertex.resize(nv);
        std::iota(map.original_vertex.begin(), map.original_vertex.end(), 0u);
        return map;
    }
    const auto* indices = reinterpret_cast<const unsigned int*>(mesh.triangles.data());
    const std::size_t index_count = nt * 3;
    std::vector<unsigned int> cache(index_count);
    meshopt_optimizeVertexCache(cache.data(), indices, index_count, nv);
    std::vector<unsigned int> overdraw(index_count);
    // note: 1.05 lets the vertex-cache order worsen by at most 5% to reduce overdraw
    // (meshoptimizer's documented default).
    meshopt_optimizeOverdraw(overdraw.data(), cache.data(), index_count,
                             reinterpret_cast<const float*>(mesh.positions.data()), nv,
                             sizeof(Vec3f), 1.05f);

    // Which original triangle each new triangle is: the optimisers emit whole triangles,
    // possibly with rotated corners, so match on the canonical rotation.
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> keyed(nt);
    for (std::size_t t = 0; t < nt; ++t)
        keyed[t] = {canonical(mesh.triangles[t]), static_cast<std::uint32_t>(t)};
    std::sort(keyed.begin(), keyed.end());
    std::vector<bool> taken(nt, false);
    map.original_triangle.resize(nt);
    std::vector<Triangle> new_triangles(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        const Triangle tri{overdraw[3 * t], overdraw[3 * t + 1], overdraw[3 * t + 2]};
        const auto key = canonical(tri);
        auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, 0u));
        while (it != keyed.end() && it->first == key && taken[it - keyed.begin()]) ++it;
        GLINT_ASSERT(it != keyed.end() && it->first == key, "reordered triangle not found");
        taken[static_cast<std::size_t>(it - keyed.begin())] = true;
        map.original_triangle[t] = it->second;
        new_triangles[t] = tri;
    }

    // Vertex fetch order; vertices no triangle uses keep their relative order at the end.
    std::vector<unsigned int> remap(nv);
    const std::size_t used =
        meshopt_optimizeVertexFetchRemap(remap.data(), overdraw.data(), index_count, nv);
    std::uint32_t next = static_cast<std::uint32_t>(used);
    for (auto& r : remap)
        if (r == ~0u) r = next++;
    map.original_vertex.resize(nv);
    for (std::size_t v = 0; v < nv; ++v)
        map.original_vertex[remap[v]] = static_cast<std::uint32_t>(v);
    for (auto& tri : new_triangles)
        for (auto& i : tri) i = remap[i];
    mesh.triangles = std::move(new_triangles);

    const auto& order = map.original_vertex;
    permute(mesh.positions, order);
    if (mesh.normals.size() == nv) permute(mesh.normals, order);
    if (mesh.colors.size() == nv) permute(mesh.colors, order);
    if (mesh.labels.size() == nv) permute(mesh.labels, order);
    for (auto& field : mesh.scalars)
        if (field.values.size() == nv) permute(field.values, order);
    return map;
}

std::vector<float> to_original_order(const ReorderMap& map, const std::vector<float>& values) {
    GLINT_ASSERT(values.size() == map.original_vertex.size(),
                 "values do not match the reordered mesh");
    std::vector<float> out(values.size());
    for (std::size_t v = 0; v < values.size(); ++v) out[map.original_vertex[v]] = values[v];
    return out;
}

}  // namespace glint
