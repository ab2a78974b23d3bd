// Procedural phantoms. Every surface except the torus is star-shaped around a centre, so both
// tessellation schemes are built on the unit sphere (a latitude/longitude grid or a
// subdivided icosahedron) and mapped radially onto the exact surface: the two schemes then
// describe the same analytic surface, vertex for vertex on it.
#include "mesh/phantom.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>

namespace glint {

namespace {

constexpr double kPi = std::numbers::pi;

// Condyle phantom (mm, before scaling by radii.x()/10): the smooth union of an ovoid head
// (semi-axes 10 × 5 × 6 mm around (0, 0, 3)) and a neck (4.5 × 3.5 × 5.5 mm around
// (0, 0, −1)): 20 mm mediolateral (x), 10 mm anteroposterior (y), 15.5 mm high (z, from −6.5
// to 9). Both ellipsoids contain the ray origin (0, 0, 1.5), so the union is star-shaped
// around it.
const Vec3d kHeadCenter{0.0, 0.0, 3.0};
const Vec3d kHeadAxes{10.0, 5.0, 6.0};
const Vec3d kNeckCenter{0.0, 0.0, -1.0};
const Vec3d kNeckAxes{4.5, 3.5, 5.5};
const Vec3d kCondyleOrigin{0.0, 0.0, 1.5};
// note: 1.0 (in field units, ~ a fifth of the axes) blends the head into the neck with a
// wide fillet, as on a real condyle, and keeps the curvature there moderate.
constexpr double kBlend = 1.0;

double ellipsoid_field(const Vec3d& p, const Vec3d& c, const Vec3d& axes) {
    return ((p - c).array() / axes.array()).matrix().norm() - 1.0;
}

// Polynomial smooth minimum (C¹): equals min(a, b) when |a − b| ≥ k.
double smooth_min(double a, double b, double k) {
    const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
    return b + (a - b) * h - k * h * (1.0 - h);
}

double condyle_field(const Vec3d& p) {
    return smooth_min(ellipsoid_field(p, kHeadCenter, kHeadAxes),
                      ellipsoid_field(p, kNeckCenter, kNeckAxes), kBlend);
}

Vec3d condyle_gradient(const Vec3d& p) {
    // note: central differences with h = 1e-6 mm give the gradient to ~1e-9 relative, far
    // below the normal-agreement tolerances (0.01°) the tests use.
    constexpr double h = 1e-6;
    Vec3d g;
    for (int i = 0; i < 3; ++i) {
        Vec3d e = Vec3d::Zero();
        e[i] = h;
        g[i] = (condyle_field(p + e) - condyle_field(p - e)) / (2 * h);
    }
    return g;
}

// Distance along unit direction d from the condyle origin to the surface (the last sign
// change of the field, found by marching inwards then bisecting to 1e-12 mm).
double condyle_radius(const Vec3d& d) {
    double outside = 15.0;  // beyond every point of the shape
    double step = 0.25;
    double t = outside;
    while (condyle_field(kCondyleOrigin + t * d) > 0.0) {
        outside = t;
        t -= step;
        GLINT_ASSERT(t > 0.0, "condyle phantom is not star-shaped along a ray");
    }
    double lo = t;
    double hi = outside;
    for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {
        const double mid = 0.5 * (lo + hi);
        (condyle_field(kCondyleOrigin + mid * d) > 0.0 ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

struct SphereMesh {
    std::vector<Vec3d> directions;
    std::vector<Triangle> triangles;
};

SphereMesh uv_sphere(int rings) {
    SphereMesh s;
    const int segments = 2 * rings;
    s.directions.push_back({0, 0, 1});
    for (int i = 1; i < rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2 * kPi * j / segments;
            s.directions.push_back({std::sin(theta) * std::cos(phi),
                                    std::sin(theta) * std::sin(phi), std::cos(theta)});
        }
    }
    s.directions.push_back({0, 0, -1});
    const auto south = static_cast<std::uint32_t>(s.directions.size() - 1);
    auto id = [&](int ring, int j) {
        return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (j % segments));
    };
    for (int j = 0; j < segments; ++j) s.triangles.push_back({0, id(1, j), id(1, j + 1)});
    for (int i = 1; i < rings - 1; ++i)
        for (int j = 0; j < segments; ++j) {
            s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    for (int j = 0; j < segments; ++j)
        s.triangles.push_back({id(rings - 1, j), south, id(rings - 1, j + 1)});
    return s;
}

SphereMesh ico_sphere(int level) {
    SphereMesh s;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& p : v) s.directions.push_back(Vec3d(p[0], p[1], p[2]).normalized());
    s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            const auto idx = static_cast<std::uint32_t>(s.directions.size());
            s.directions.push_back((s.directions[a] + s.directions[b]).normalized());
            midpoint.emplace(key, idx);
            return idx;
        };
        std::vector<Triangle> next;
        next.reserve(s.triangles.size() * 4);
        for (const auto& tri : s.triangles) {
            const auto a = mid(tri[0], tri[1]);
            const auto b = mid(tri[1], tri[2]);
            const auto c = mid(tri[2], tri[0]);
            next.push_back({tri[0], a, c});
            next.push_back({tri[1], b, a});
            next.push_back({tri[2], c, b});
            next.push_back({a, b, c});
        }
        s.triangles = std::move(next);
    }
    return s;
}

// Torus around z: major radius R, tube radius r; u around z, v around the tube.
Vec3d torus_point(double R, double r, double u, double v) {
    return {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
            r * std::sin(v)};
}

Mesh torus(const PhantomOptions& o) {
    const double R = o.radii.x();
    const double r = o.radii.y();
    if (!(r < R))
        throw InputError("phantom torus: tube radius " + std::to_string(r) +
                         " must be below the major radius " + std::to_string(R));
    const int rings = std::max(3, o.resolution);  // around the tube
    const int segments = 2 * rings;               // around z
    const bool staggered = o.scheme == TessellationScheme::Ico;
    Mesh m;
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < rings; ++j) {
            // Ico scheme: every other ring of the tube turned by half a cell, so the grid is
            // made of different triangles than the Uv scheme's.
            const double shift = staggered && (i % 2) ? 0.5 : 0.0;
            m.positions.push_back(
                torus_point(R, r, 2 * kPi * i / segments, 2 * kPi * (j + shift) / rings)
                    .cast<float>());
        }
    auto id = [&](int i, int j) {
        return static_cast<std::uint32_t>(((i % segments + segments) % segments) * rings +
                                          ((j % rings + rings) % rings));
    };
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < rings; ++j) {
            const auto a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (!staggered || (i + j) % 2 == 0) {
                m.triangles.push_back({a, b, c});
                m.triangles.push_back({a, c, d});
            } else {
                m.triangles.push_back({a, b, d});
                m.triangles.push_back({b, c, d});
            }
        }
    return m;
}

}  // namespace

Mesh make_phantom(const PhantomOptions& o) {
    std::ostringstream where;
    where << "phantom " << to_string(o.kind) << " (" << to_string(o.scheme) << ", resolution "
          << o.resolution << ")";
    if ((o.radii.array() <= 0).any() || !o.radii.allFinite())
        throw InputError(where.str() + ": sizes must be > 0, found (" +
                         std::to_string(o.radii.x()) + ", " + std::to_string(o.radii.y()) + ", " +
                         std::to_string(o.radii.z()) + ")");
    // note: the limits keep a phantom below ~5M triangles (≈ 200 MB as a Mesh).
    const bool ico = o.scheme == TessellationScheme::Ico && o.kind != PhantomKind::Torus;
    const int lo = ico ? 0 : (o.kind == PhantomKind::Torus ? 3 : 2);
    const int hi = ico ? 9 : 1500;
    if (o.resolution < lo || o.resolution > hi)
        throw InputError(where.str() + ": resolution must be in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]");

    Mesh m;
    if (o.kind == PhantomKind::Torus) {
        m = torus(o);
    } else {
        const SphereMesh s = ico ? ico_sphere(o.resolution) : uv_sphere(o.resolution);
        m.triangles = s.triangles;
        m.positions.reserve(s.directions.size());
        const double scale = o.radii.x() / 10.0;
        for (const auto& d : s.directions) {
            Vec3d p;
            switch (o.kind) {
                case PhantomKind::Sphere: p = o.radii.x() * d; break;
                case PhantomKind::Ellipsoid:
                    p = d / (d.array() / o.radii.array()).matrix().norm();
                    break;
                default: p = scale * (kCondyleOrigin + condyle_radius(d) * d); break;
            }
            m.positions.push_back(p.cast<float>());
        }
    }
    m.unit = "mm";
    compute_vertex_normals(m);
    return m;
}

Vec3d phantom_normal(const PhantomOptions& o, const Vec3d& p) {
    switch (o.kind) {
        case PhantomKind::Sphere: return p.normalized();
        case PhantomKind::Ellipsoid:
            return (p.array() / (o.radii.array() * o.radii.array())).matrix().normalized();
        case PhantomKind::Torus: {
            const double R = o.radii.x();
            const Vec3d ring = Vec3d(p.x(), p.y(), 0.0).normalized() * R;
            return (p - ring).normalized();
        }
        case PhantomKind::Condyle: {
            const double scale = o.radii.x() / 10.0;
            return condyle_gradient(p / scale).normalized();
        }
    }
    return Vec3d::Zero();
}

PhantomKind parse_phantom_kind(const std::string& text) {
    if (text == "sphere") return PhantomKind::Sphere;
    if (text == "ellipsoid") return PhantomKind::Ellipsoid;
    if (text == "torus") return PhantomKind::Torus;
    if (text == "condyle") return PhantomKind::Condyle;
    throw InputError("phantom kind '" + text + "': expected sphere, ellipsoid, torus or condyle");
}

TessellationScheme parse_scheme(const std::string& text) {
    if (text == "uv") return TessellationScheme::Uv;
    if (text == "ico") return TessellationScheme::Ico;
    throw InputError("tessellation scheme '" + text + "': expected uv or ico");
}

std::string to_string(PhantomKind kind) {
    switch (kind) {
        case PhantomKind::Sphere: return "sphere";
        case PhantomKind::Ellipsoid: return "ellipsoid";
        case PhantomKind::Torus: return "torus";
        case PhantomKind::Condyle: return "condyle";
    }
    return "?";
}

std::string to_string(TessellationScheme scheme) {
    return scheme == TessellationScheme::Uv ? "uv" : "ico";
}

}  // namespace glint
