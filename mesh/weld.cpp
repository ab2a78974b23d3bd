#include "mesh/weld.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <tuple>
#include <vector>

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
    // note: sorting (position bits, index) and scanning runs of equal positions replaced a
    // hash map; with the sorted duplicate-triangle test below, a full load measured
    // (bench/mesh_io_bench.cpp, alternating runs): PLY 2M 2.8 s → 0.85 s, STL 2M 2.4 s →
    // 1.55 s, STL 200k unchanged (~0.14 s).
    const std::size_t n = mesh.positions.size();
    struct Keyed {
        PositionKey key;
        std::uint32_t vertex;
    };
    std::vector<Keyed> keyed(n);
    for (std::size_t v = 0; v < n; ++v) {
        const auto& p = mesh.positions[v];
        keyed[v] = {{float_bits(p.x()), float_bits(p.y()), float_bits(p.z())},
                    static_cast<std::uint32_t>(v)};
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
        return std::tie(a.key.x, a.key.y, a.key.z, a.vertex) <
               std::tie(b.key.x, b.key.y, b.key.z, b.vertex);
    });
    // The first vertex (lowest index) of each run of equal positions represents it.
    std::vector<std::uint32_t> representative(n);
    for (std::size_t i = 0; i < n; ++i) {
        const bool starts_run = i == 0 || !(keyed[i].key == keyed[i - 1].key);
        representative[keyed[i].vertex] =
            starts_run ? keyed[i].vertex : representative[keyed[i - 1].vertex];
    }
    // New ids in order of first appearance, as the vertices come in the file.
    std::vector<std::uint32_t> new_of_old(n);
    std::vector<std::uint32_t> old_of_new;
    old_of_new.reserve(n);
    for (std::size_t v = 0; v < n; ++v) {
        if (representative[v] == v) {
            new_of_old[v] = static_cast<std::uint32_t>(old_of_new.size());
            old_of_new.push_back(static_cast<std::uint32_t>(v));
        } else {
            new_of_old[v] = new_of_old[representative[v]];
        }
    }
    counts.welded_vertices += n - old_of_new.size();
    if (old_of_new.size() == n) return new_of_old;
    gather_vertex_arrays(mesh, old_of_new);
    for (auto& tri : mesh.triangles)
        for (auto& i : tri) i = new_of_old[i];
    return new_of_old;
}

void drop_degenerate_triangles(Mesh& mesh, RepairCounts& counts) {
    // Duplicates: the same vertices in the same cyclic order (rotated so the smallest id comes
    // first), found by sorting (key, index): the first triangle of each run is kept.
    struct Keyed {
        std::uint32_t a, b, c, triangle;
    };
    const std::size_t nt = mesh.triangles.size();
    std::vector<std::uint8_t> drop(nt, 0);
    std::vector<Keyed> keyed;
    keyed.reserve(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        const auto tri = mesh.triangles[t];
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            ++counts.degenerate_triangles;
            drop[t] = 1;
            continue;
        }
        const Vec3d a = mesh.positions[tri[0]].cast<double>();
        const Vec3d b = mesh.positions[tri[1]].cast<double>();
        const Vec3d c = mesh.positions[tri[2]].cast<double>();
        if ((b - a).cross(c - a).squaredNorm() == 0.0) {
            ++counts.degenerate_triangles;
            drop[t] = 1;
            continue;
        }
        const int k = tri[0] < tri[1] ? (tri[0] < tri[2] ? 0 : 2) : (tri[1] < tri[2] ? 1 : 2);
        keyed.push_back(
            {tri[static_cast<std::size_t>(k)], tri[static_cast<std::size_t>((k + 1) % 3)],
             tri[static_cast<std::size_t>((k + 2) % 3)], static_cast<std::uint32_t>(t)});
    }
    std::sort(keyed.begin(), keyed.end(), [](const Keyed& x, const Keyed& y) {
        return std::tie(x.a, x.b, x.c, x.triangle) < std::tie(y.a, y.b, y.c, y.triangle);
    });
    for (std::size_t i = 1; i < keyed.size(); ++i) {
        const Keyed& p = keyed[i - 1];
        const Keyed& q = keyed[i];
        if (p.a == q.a && p.b == q.b && p.c == q.c) {
            drop[q.triangle] = 1;
            ++counts.duplicate_triangles;
        }
    }
    std::size_t out = 0;
    for (std::size_t t = 0; t < nt; ++t)
        if (!drop[t]) mesh.triangles[out++] = mesh.triangles[t];
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
