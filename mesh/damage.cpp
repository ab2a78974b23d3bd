// Synthetic damage. Profiles (s = distance / radius, 0 at the centre, 1 at the rim):
//   dent / bump / groove / erosion envelope: (1 − s²)², C¹ at the centre and at the rim;
//   pit: flat bottom for s ≤ 0.6, then a smoothstep wall to 0 at s = 1.
// Distances are Euclidean from the snapped centre (or from the groove path); for radii
// small against the surface's curvature radius this is within a few percent of geodesic.
#include "mesh/damage.h"

#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/parse.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

namespace glint {

namespace {

double bump_profile(double s) {
    if (s >= 1.0) return 0.0;
    const double q = 1.0 - s * s;
    return q * q;
}

double smoothstep(double x) {
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

double pit_profile(double s) {
    // note: 0.6 makes the flat bottom 60% of the radius: steep walls, as a pit has.
    return s >= 1.0 ? 0.0 : smoothstep((1.0 - s) / 0.4);
}

// Deterministic 3D value noise in [0, 1]: hashed lattice values, trilinear with smoothstep.
double lattice(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull ^
                      static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^
                      static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull ^
                      (std::uint64_t{seed} << 17);
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return static_cast<double>(h >> 11) / static_cast<double>(1ull << 53);
}

double value_noise(const Vec3d& p, std::uint32_t seed) {
    const Vec3d f = p.array().floor();
    const Vec3d t = p - f;
    const auto x0 = static_cast<std::int64_t>(f.x()), y0 = static_cast<std::int64_t>(f.y()),
               z0 = static_cast<std::int64_t>(f.z());
    const double sx = smoothstep(t.x()), sy = smoothstep(t.y()), sz = smoothstep(t.z());
    double acc = 0.0;
    for (int dx = 0; dx < 2; ++dx)
        for (int dy = 0; dy < 2; ++dy)
            for (int dz = 0; dz < 2; ++dz) {
                const double w = (dx ? sx : 1 - sx) * (dy ? sy : 1 - sy) * (dz ? sz : 1 - sz);
                acc += w * lattice(x0 + dx, y0 + dy, z0 + dz, seed);
            }
    return acc;
}

std::size_t nearest_vertex(const Mesh& mesh, const Vec3d& p, double& distance) {
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::max();
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const double d2 = (mesh.positions[v].cast<double>() - p).squaredNorm();
        if (d2 < best_d2) {
            best_d2 = d2;
            best = v;
        }
    }
    distance = std::sqrt(best_d2);
    return best;
}

double distance_to_path(const Vec3d& p, const std::vector<Vec3d>& path) {
    double best = std::numeric_limits<double>::max();
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const Vec3d a = path[i];
        const Vec3d ab = path[i + 1] - a;
        const double len2 = ab.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (a + t * ab - p).norm());
    }
    return best;
}

std::string describe(const DamageSpec& d, std::size_t index) {
    return "damage " + std::to_string(index + 1) + " (" + to_string(d.kind) + ")";
}

void check_spec(const DamageSpec& d, std::size_t index) {
    auto positive = [&](double v, const char* field) {
        if (!(v > 0) || !std::isfinite(v))
            throw InputError(describe(d, index) + ": " + field + " = " + std::to_string(v) +
                             ", expected a number > 0");
    };
    if (d.kind == DamageKind::Noise) {
        positive(d.sigma, "sigma");
        return;
    }
    positive(d.radius, "radius");
    positive(d.depth, "depth");
    if (d.kind == DamageKind::Groove && d.path.size() < 2)
        throw InputError(describe(d, index) + ": path has " + std::to_string(d.path.size()) +
                         " point(s), expected at least 2");
    if (d.kind == DamageKind::Flatten && d.plane_normal && !(d.plane_normal->norm() > 0))
        throw InputError(describe(d, index) + ": normal must not be zero");
}

// `where` names the spec in messages: "damage spec 'dent:…'" or "pose '…'".
std::vector<double> numbers(const std::string& where, const std::string& key,
                            const std::string& text) {
    return parse_number_list(text, where + ": " + key);
}

Vec3d vec3(const std::string& where, const std::string& key, const std::string& text) {
    const auto v = numbers(where, key, text);
    if (v.size() != 3)
        throw InputError(where + ": " + key + ": expected x,y,z, found " +
                         std::to_string(v.size()) + " numbers");
    return {v[0], v[1], v[2]};
}

}  // namespace

std::string to_string(DamageKind kind) {
    switch (kind) {
        case DamageKind::Dent: return "dent";
        case DamageKind::Bump: return "bump";
        case DamageKind::Pit: return "pit";
        case DamageKind::Groove: return "groove";
        case DamageKind::Flatten: return "flatten";
        case DamageKind::Erosion: return "erosion";
        case DamageKind::Noise: return "noise";
    }
    return "?";
}

namespace {

// The damage's centre on the surface: the closest point on any triangle, not the nearest vertex,
// so the same damage lands on the same spot of two tessellations of one surface. A damage off
// the surface (or a groove path point) is an input error.
Vec3d place_on_surface(const Mesh& mesh, const DamageSpec& d, std::size_t k) {
    if (d.kind == DamageKind::Groove) {
        for (std::size_t p = 0; p < d.path.size(); ++p) {
            double dist = 0.0;
            nearest_vertex(mesh, d.path[p], dist);
            if (dist > d.radius)
                throw InputError(describe(d, k) + ": path point " + std::to_string(p + 1) +
                                 " lies " + std::to_string(dist) +
                                 " from the surface, outside the surface (radius " +
                                 std::to_string(d.radius) + ")");
        }
        return d.center;
    }
    const Vec3d center = closest_point_on_mesh(mesh, d.center);
    const double dist = (center - d.center).norm();
    if (dist > d.radius)
        throw InputError(describe(d, k) + ": centre lies " + std::to_string(dist) +
                         " from the surface, outside the surface (radius " +
                         std::to_string(d.radius) + ")");
    return center;
}

// One damage's move of every vertex (`offset`, mesh units) and its displacement along the
// vertex normal (`disp`, the ground truth).
void displace(const Mesh& mesh, const DamageSpec& d, const Vec3d& center,
              std::vector<Vec3d>& offset, std::vector<double>& disp) {
    Vec3d plane_n = Vec3d::UnitZ();
    if (d.kind == DamageKind::Flatten) {
        double unused = 0.0;
        plane_n =
            d.plane_normal
                ? d.plane_normal->normalized()
                : mesh.normals[nearest_vertex(mesh, center, unused)].cast<double>().normalized();
    }
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const Vec3d p = mesh.positions[v].cast<double>();
        const Vec3d normal = mesh.normals[v].cast<double>();
        const double dist =
            d.kind == DamageKind::Groove ? distance_to_path(p, d.path) : (p - center).norm();
        const double s = dist / d.radius;
        if (s >= 1.0) continue;
        double amount = 0.0;
        switch (d.kind) {
            case DamageKind::Dent: amount = -d.depth * bump_profile(s); break;
            case DamageKind::Bump: amount = d.depth * bump_profile(s); break;
            case DamageKind::Pit: amount = -d.depth * pit_profile(s); break;
            case DamageKind::Groove: amount = -d.depth * bump_profile(s); break;
            case DamageKind::Erosion: {
                // note: noise at ~3 cells per radius gives a rough floor with a few
                // lumps; 0.3 + 0.7·noise keeps every eroded vertex below the surface.
                const double rough = 0.3 + 0.7 * value_noise(p * (3.0 / d.radius), d.seed);
                amount = -d.depth * bump_profile(s) * rough;
                break;
            }
            case DamageKind::Flatten: {
                // Plane `depth` below the centre along its normal; vertices above it are
                // pushed onto it (along the plane normal), fading out over the outer 20%.
                const double above = (p - (center - d.depth * plane_n)).dot(plane_n);
                if (above <= 0) continue;
                const double fade = smoothstep((1.0 - s) / 0.2);
                const Vec3d move = -fade * above * plane_n;
                offset[v] += move;
                disp[v] = move.dot(normal);
                continue;
            }
            case DamageKind::Noise: break;
        }
        disp[v] = amount;
        offset[v] += amount * normal;
    }
}

}  // namespace

void apply_damage(Mesh& mesh, const std::vector<DamageSpec>& damages) {
    const std::size_t n = mesh.vertex_count();
    if (!mesh.has_normals()) compute_vertex_normals(mesh);
    for (std::size_t i = 0; i < damages.size(); ++i) check_spec(damages[i], i);

    std::vector<double> total(n, 0.0);
    std::vector<double> strongest(n, 0.0);
    if (mesh.labels.size() != n) mesh.labels.assign(n, 0);
    if (const auto* previous = mesh.find_scalar("gt_displacement"))
        for (std::size_t v = 0; v < n; ++v) total[v] = previous->values[v];
    std::vector<Vec3d> offset(n, Vec3d::Zero());

    for (std::size_t k = 0; k < damages.size(); ++k) {
        const DamageSpec& d = damages[k];
        if (d.kind == DamageKind::Noise) {
            std::mt19937 rng(d.seed);
            std::normal_distribution<double> gauss(0.0, d.sigma);
            for (std::size_t v = 0; v < n; ++v)
                offset[v] += gauss(rng) * mesh.normals[v].cast<double>();
            continue;
        }
        std::vector<double> disp(n, 0.0);
        displace(mesh, d, place_on_surface(mesh, d, k), offset, disp);
        const double label_at = kDamageLabelThreshold * d.depth;
        for (std::size_t v = 0; v < n; ++v) {
            total[v] += disp[v];
            if (std::abs(disp[v]) > label_at && std::abs(disp[v]) > strongest[v]) {
                strongest[v] = std::abs(disp[v]);
                mesh.labels[v] = static_cast<std::int32_t>(k + 1);
            }
        }
    }
    for (std::size_t v = 0; v < n; ++v)
        mesh.positions[v] = (mesh.positions[v].cast<double>() + offset[v]).cast<float>();
    std::vector<float> gt(n), label(n);
    for (std::size_t v = 0; v < n; ++v) {
        gt[v] = static_cast<float>(total[v]);
        label[v] = static_cast<float>(mesh.labels[v]);
    }
    mesh.set_scalar("gt_displacement", std::move(gt));
    mesh.set_scalar("gt_label", std::move(label));
    compute_vertex_normals(mesh);
}

DamageSpec parse_damage_spec(const std::string& text) {
    DamageSpec d;
    const std::string where = "damage spec '" + text + "'";
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    if (kind == "dent") d.kind = DamageKind::Dent;
    else if (kind == "bump") d.kind = DamageKind::Bump;
    else if (kind == "pit") d.kind = DamageKind::Pit;
    else if (kind == "groove" || kind == "scratch") d.kind = DamageKind::Groove;
    else if (kind == "flatten" || kind == "flattening") d.kind = DamageKind::Flatten;
    else if (kind == "erosion") d.kind = DamageKind::Erosion;
    else if (kind == "noise") d.kind = DamageKind::Noise;
    else
        throw InputError("damage spec '" + text + "': unknown kind '" + kind +
                         "', expected dent, bump, pit, groove, flatten, erosion or noise");
    if (colon == std::string::npos) return d;
    // Keys are separated by ';' or by spaces ("dent:center=0,0,10 radius=2 depth=0.3"), the
    // latter being easier to type in shells and build scripts.
    std::string keys = text.substr(colon + 1);
    std::replace(keys.begin(), keys.end(), ' ', ';');
    std::stringstream ss(keys);
    std::string item;
    while (std::getline(ss, item, ';')) {
        if (item.empty()) continue;
        const auto eq = item.find('=');
        if (eq == std::string::npos)
            throw InputError("damage spec '" + text + "': '" + item + "' is not key=value");
        const std::string key = item.substr(0, eq);
        const std::string value = item.substr(eq + 1);
        auto scalar = [&]() {
            const auto v = numbers(where, key, value);
            if (v.size() != 1)
                throw InputError("damage spec '" + text + "': " + key + ": expected one number");
            return v[0];
        };
        if (key == "center") d.center = vec3(where, key, value);
        else if (key == "radius") d.radius = scalar();
        else if (key == "depth") d.depth = scalar();
        else if (key == "sigma") d.sigma = scalar();
        else if (key == "seed") d.seed = static_cast<std::uint32_t>(scalar());
        else if (key == "normal") d.plane_normal = vec3(where, key, value);
        else if (key == "path") {
            std::stringstream ps(value);
            std::string point;
            while (std::getline(ps, point, '/')) d.path.push_back(vec3(where, key, point));
        } else
            throw InputError("damage spec '" + text + "': unknown key '" + key +
                             "', expected center, radius, depth, path, normal, sigma or seed");
    }
    return d;
}

Rigid parse_pose_spec(const std::string& text) {
    const double deg = std::numbers::pi / 180.0;
    Rigid pose = Rigid::Identity();
    if (text.find('=') == std::string::npos) {
        const auto v = numbers("pose '" + text + "'", "pose", text);
        if (v.size() != 6)
            throw InputError("pose '" + text +
                             "': expected rx,ry,rz,tx,ty,tz (degrees, mesh units), found " +
                             std::to_string(v.size()) + " numbers");
        pose.linear() = (Eigen::AngleAxisd(v[2] * deg, Vec3d::UnitZ()) *
                         Eigen::AngleAxisd(v[1] * deg, Vec3d::UnitY()) *
                         Eigen::AngleAxisd(v[0] * deg, Vec3d::UnitX()))
                            .toRotationMatrix();
        pose.translation() = Vec3d(v[3], v[4], v[5]);
        return pose;
    }
    Vec3d axis = Vec3d::UnitZ();
    double angle = 0.0;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ';')) {
        const auto eq = item.find('=');
        const std::string key = item.substr(0, eq);
        const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
        if (key == "axis") axis = vec3("pose '" + text + "'", key, value);
        else if (key == "angle") {
            const auto v = numbers("pose '" + text + "'", key, value);
            if (v.size() != 1)
                throw InputError("pose '" + text + "': angle: expected one number (degrees)");
            angle = v[0];
        } else if (key == "t") pose.translation() = vec3("pose '" + text + "'", key, value);
        else
            throw InputError("pose '" + text + "': unknown key '" + key +
                             "', expected axis, angle or t");
    }
    if (!(axis.norm() > 0)) throw InputError("pose '" + text + "': axis must not be zero");
    pose.linear() = Eigen::AngleAxisd(angle * deg, axis.normalized()).toRotationMatrix();
    return pose;
}

}  // namespace glint
