#include "mesh/weld.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <unordered_map>
#include <unordered_set>

namespace glint {

namespace {

struct PositionKey {
    std::uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};

std::uint32_t float_bits(float f) {
    // note: +0 and -0 compare equal as positions, so both map to the bits of +0.
    if (f == 0.0f) f = 0.0f;
    return std::bit_cast<std::uint32_t>(f);
}

struct PositionKeyHash {
    std::size_t operator()(const PositionKey& k) const noexcept {
        std::uint64_t h = 0x9E3779B97F4A7C15ull;
        for (std::uint32_t v : {k.x, k.y, k.z}) {
            h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
            h *= 0xBF58476D1CE4E5B9ull;
        }
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

template <class T>
void gather(std::vector<T>& values, const std::vector<std::uint32_t>& old_of_new) {
    if (values.empty()) return;
    std::vector<T> out(old_of_new.size());
    for (std::size_t i = 0; i < old_of_new.size(); ++i) out[i] = values[old_of_new[i]];
    values = std::move(out);
}

// Keeps the vertices listed in old_of_new (in that order) for every per-vertex array.
void gather_vertex_arrays(Mesh& mesh, const std::vector<std::uint32_t>& old_of_new) {
    const std::size_t n = mesh.positions.size();
    gather(mesh.positions, old_of_new);
    if (mesh.normals.size() == n) gather(mesh.normals, old_of_new);
    if (mesh.colors.size() == n) gather(mesh.colors, old_of_new);
    if (mesh.labels.size() == n) gather(mesh.labels, old_of_new);
    for (auto& field : mesh.scalars)
        if (field.values.size() == n) gather(field.values, old_of_new);
}

}  // namespace

std::vector<std::uint32_t> weld_vertices(Mesh& mesh, RepairCounts& counts) {
    const std::size_t n = mesh.positions.size();
    std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> first;
    first.reserve(n);
    std::vector<std::uint32_t> new_of_old(n);
    std::vector<std::uint32_t> old_of_new;
    old_of_new.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        const auto& p = mesh.positions[v];
        const PositionKey key{float_bits(p.x()), float_bits(p.y()), float_bits(p.z())};
        auto [it, inserted] = first.try_emplace(key, static_cast<std::uint32_t>(old_of_new.size()));
        if (inserted) old_of_new.push_back(static_cast<std::uint32_t>(v));
        new_of_old[v] = it->second;
    }
    counts.welded_vertices += n - old_of_new.size();
    if (old_of_new.size() == n) return new_of_old;
    gather_vertex_arrays(mesh, old_of_new);
    for (auto& tri : mesh.triangles)
        for (auto& i : tri) i = new_of_old[i];
    return new_of_old;
}

void drop_degenerate_triangles(Mesh& mesh, RepairCounts& counts) {
    struct TriKey {
        std::uint32_t a, b, c;
        bool operator==(const TriKey&) const = default;
    };
    struct TriHash {
        std::size_t operator()(const TriKey& k) const noexcept {
            std::uint64_t h = (std::uint64_t{k.a} * 0x9E3779B97F4A7C15ull) ^
                              (std::uint64_t{k.b} * 0xC2B2AE3D27D4EB4Full) ^
                              (std::uint64_t{k.c} * 0x165667B19E3779F9ull);
            return static_cast<std::size_t>(h ^ (h >> 29));
        }
    };
    std::unordered_set<TriKey, TriHash> seen;
    seen.reserve(mesh.triangles.size());
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto tri = mesh.triangles[t];
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            ++counts.degenerate_triangles;
            continue;
        }
        const Vec3d a = mesh.positions[tri[0]].cast<double>();
        const Vec3d b = mesh.positions[tri[1]].cast<double>();
        const Vec3d c = mesh.positions[tri[2]].cast<double>();
        if ((b - a).cross(c - a).squaredNorm() == 0.0) {
            ++counts.degenerate_triangles;
            continue;
        }
        // Same vertices in the same cyclic order: rotate so the smallest id comes first.
        const int k = tri[0] < tri[1] ? (tri[0] < tri[2] ? 0 : 2) : (tri[1] < tri[2] ? 1 : 2);
        const TriKey key{tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)],
                         tri[static_cast<std::size_t>((k + 2) % 3)]};
        if (!seen.insert(key).second) {
            ++counts.duplicate_triangles;
            continue;
        }
        mesh.triangles[out++] = tri;
    }
    mesh.triangles.resize(out);
}

std::vector<std::uint32_t> compact_vertices(Mesh& mesh, const std::vector<bool>& keep) {
    const std::size_t n = mesh.positions.size();
    std::vector<std::uint32_t> new_of_old(n, kInvalidVertex);
    std::vector<std::uint32_t> old_of_new;
    old_of_new.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        if (keep[v]) {
            new_of_old[v] = static_cast<std::uint32_t>(old_of_new.size());
            old_of_new.push_back(static_cast<std::uint32_t>(v));
        }
    }
    std::size_t out = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        auto tri = mesh.triangles[t];
        bool ok = true;
        for (auto& i : tri) {
            i = new_of_old[i];
            ok = ok && i != kInvalidVertex;
        }
        if (ok) mesh.triangles[out++] = tri;
    }
    mesh.triangles.resize(out);
    if (old_of_new.size() != n) gather_vertex_arrays(mesh, old_of_new);
    return new_of_old;
}

std::vector<std::uint32_t> drop_unused_vertices(Mesh& mesh, RepairCounts& counts) {
    std::vector<bool> used(mesh.positions.size(), false);
    for (const auto& tri : mesh.triangles)
        for (auto i : tri) used[i] = true;
    const auto unused = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
    counts.unused_vertices += unused;
    return compact_vertices(mesh, used);
}

}  // namespace glint
