#include "analysis/asymmetry.h"

#include "mesh/error.h"
#include "mesh/units.h"
#include "registration/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace glint {

namespace {

// +1: the region's side has more than the mirrored other side (the mirror lies inside it,
// a "dent" of the examined = mirror), −1: less.
int sign_of(const Region& r) { return r.kind == RegionKind::Dent ? +1 : -1; }

double radius_of(const Region& r) { return std::sqrt(r.area / std::numbers::pi); }

// The unpaired region of the opposite sign nearest the mirror image of `r`'s centroid, within
// twice the larger radius; -1 when none.
int partner_of(const std::vector<Region>& regions, std::size_t i, const SymmetryPlane& plane,
               const std::vector<std::uint8_t>& paired) {
    const Region& r = regions[i];
    const Vec3d image = plane.reflection() * r.centroid;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < regions.size(); ++j) {
        const Region& q = regions[j];
        if (j == i || paired[j] || q.kind == RegionKind::MissingSurface || q.hole ||
            sign_of(q) == sign_of(r))
            continue;
        const double d = (q.centroid - image).norm();
        if (d <= 2.0 * std::max(radius_of(r), radius_of(q)) && d < best_distance) {
            best_distance = d;
            best = static_cast<int>(j);
        }
    }
    return best;
}

AsymmetryFinding finding_of(const Region& r, const Region* mirror, const SymmetryPlane& plane) {
    AsymmetryFinding f;
    f.region = r.id;
    f.mirror_region = mirror ? mirror->id : 0;
    f.side = plane.distance(r.centroid) >= 0 ? plane.normal : Vec3d(-plane.normal);
    // The examined surface is the mirror: its change against the surface is minus the
    // surface's change against its mirror.
    f.depth = -r.peak_depth;
    f.area = r.area;
    f.volume = -r.volume;
    f.centroid = r.centroid;
    // A hole (a dent of the mirror where it holds no surface, decision/comparison.h): the
    // mirrored side has no surface there; its depth is no measure of the difference.
    if (r.kind == RegionKind::MissingSurface || r.hole) {
        f.mirror_missing = true;
        f.depth = f.volume = std::numeric_limits<double>::quiet_NaN();
    }
    return f;
}

SymmetryFloor floor_of(const std::vector<float>& field, const std::vector<std::int32_t>& region) {
    std::vector<double> a;
    a.reserve(field.size());
    for (std::size_t v = 0; v < field.size(); ++v)
        if ((region.empty() || region[v] == 0) && std::isfinite(field[v]))
            a.push_back(std::abs(field[v]));
    SymmetryFloor f;
    if (a.empty()) return f;
    double sum = 0.0;
    for (double x : a) sum += x * x;
    f.rms = std::sqrt(sum / double(a.size()));
    const auto k = static_cast<std::ptrdiff_t>(0.95 * double(a.size() - 1));
    std::nth_element(a.begin(), a.begin() + k, a.end());
    f.p95 = a[std::size_t(k)];
    f.max = *std::max_element(a.begin(), a.end());
    return f;
}

// The umbrella curvature of each vertex: the mean of its edges along its normal over their mean
// squared length (NaN where it has no edge or the mesh no normals; empty without normals).
std::vector<double> umbrella_curvature(const Mesh& mesh) {
    if (!mesh.has_normals()) return {};
    const std::size_t n = mesh.vertex_count();
    std::vector<Vec3d> sum(n, Vec3d::Zero());
    std::vector<double> length2(n, 0.0);
    for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const auto a = t[std::size_t(k)], b = t[std::size_t((k + 1) % 3)];
            const Vec3d d = (mesh.positions[b] - mesh.positions[a]).cast<double>();
            sum[a] += d;
            sum[b] -= d;
            length2[a] += d.squaredNorm();
            length2[b] += d.squaredNorm();
        }
    std::vector<double> k(n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t v = 0; v < n; ++v)
        if (length2[v] > 0) k[v] = sum[v].dot(mesh.normals[v].cast<double>()) / length2[v];
    return k;
}

// How irregularly the surface bends over a set of vertices: the spread (standard deviation) of
// their umbrella curvature. A smooth surface bends evenly; a dent, a bump or a flattening on it
// turns its curvature over within the region.
double spread_of(const std::vector<double>& curvature, const std::vector<std::uint32_t>& vertices) {
    double sum = 0.0, sum2 = 0.0, count = 0.0;
    for (const auto v : vertices) {
        if (v >= curvature.size() || !std::isfinite(curvature[v])) continue;
        sum += curvature[v];
        sum2 += curvature[v] * curvature[v];
        count += 1.0;
    }
    return count > 1 ? std::sqrt(std::max(0.0, sum2 / count - std::pow(sum / count, 2))) : 0.0;
}

// The vertices of each region, by region id.
std::vector<std::vector<std::uint32_t>> vertices_of(const RegionResult& rr, std::size_t regions) {
    std::vector<std::vector<std::uint32_t>> out(regions + 1);
    for (std::size_t v = 0; v < rr.region_of_vertex.size(); ++v) {
        const auto r = rr.region_of_vertex[v];
        if (r > 0 && std::size_t(r) < out.size()) out[std::size_t(r)].push_back(std::uint32_t(v));
    }
    return out;
}

// The surface at the mirror image of `vertices`: for each mirrored vertex the nearest vertex of
// the triangle its closest surface point lies on, each once.
std::vector<std::uint32_t> mirror_image_vertices(const ClosestPointIndex& index,
                                                 const SymmetryPlane& plane,
                                                 const std::vector<std::uint32_t>& vertices) {
    const Mesh& mesh = index.mesh();
    std::vector<Vec3d> queries;
    queries.reserve(vertices.size());
    const Eigen::Affine3d reflection = plane.reflection();
    for (const auto v : vertices) queries.push_back(reflection * mesh.positions[v].cast<double>());
    std::vector<std::uint32_t> out;
    out.reserve(vertices.size());
    for (const ClosestPoint& c : index.closest(queries)) {
        if (!c.found) continue;
        Eigen::Index corner = 0;
        c.barycentric.maxCoeff(&corner);
        out.push_back(mesh.triangles[c.triangle][std::size_t(corner)]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The finding of a lone region shown at its mirror image: this side against the mirrored other
// side there is minus the region's side against its mirror.
AsymmetryFinding at_mirror_image(AsymmetryFinding f, const SymmetryPlane& plane) {
    f.side = -f.side;
    f.centroid = plane.reflection() * f.centroid;
    f.depth = -f.depth;
    f.volume = -f.volume;
    f.at_mirror_image = true;
    return f;
}

}  // namespace

AsymmetryPlane prepare_asymmetry(const Mesh& mesh, const AsymmetryOptions& options) {
    options.validate();
    AsymmetryPlane out;
    out.plane = options.given_plane
                    ? check_symmetry_plane(mesh, *options.given_plane, options.plane)
                    : estimate_symmetry_plane(mesh, options.plane);
    // A plane given by hand is the user's decision: the surface is compared with its mirror
    // whatever the verdict (which still says how well it fits).
    if (out.plane.plausible || options.given_plane)
        out.mirror = reflect_mesh(mesh, out.plane.plane);
    return out;
}

AsymmetryFindings pair_findings(const Mesh& mesh, const SymmetryPlane& plane,
                                const AnalysisResult& result, std::size_t zoom) {
    AsymmetryFindings out;
    out.field.resize(result.distance.size());
    for (std::size_t v = 0; v < result.distance.size(); ++v) out.field[v] = -result.distance[v];
    if (zoom >= result.decisions.size()) {
        out.floor = floor_of(out.field, {});
        return out;
    }
    const RegionResult& rr = result.decisions[zoom].regions;
    const std::vector<Region>& regions = rr.regions;
    const std::vector<double> curvature = rr.region_of_vertex.size() == mesh.vertex_count()
                                              ? umbrella_curvature(mesh)
                                              : std::vector<double>();
    const auto members = vertices_of(rr, regions.size());
    std::vector<double> rough(members.size(), 0.0);
    for (std::size_t r = 1; r < members.size(); ++r) rough[r] = spread_of(curvature, members[r]);
    const auto clearly_rougher = [](double a, double b) {
        return std::max(a, b) > kRoughnessRatio * std::min(a, b);
    };
    // The surface's closest points, for lone regions' mirror images: the run's BVH when it kept
    // one of this surface, else one built when first needed.
    std::optional<ClosestPointIndex> index;
    const auto surface = [&]() -> const ClosestPointIndex& {
        if (!index) {
            if (result.reference_index && result.reference_index->indexes(mesh))
                index.emplace(mesh, result.reference_index);
            else index.emplace(ClosestPointIndex::borrowing(mesh));
        }
        return *index;
    };
    std::vector<std::uint8_t> paired(regions.size(), 0);
    for (std::size_t i = 0; i < regions.size(); ++i) {
        if (paired[i]) continue;
        const int j = partner_of(regions, i, plane, paired);
        paired[i] = 1;
        const Region& r = regions[i];
        if (j < 0) {
            AsymmetryFinding f = finding_of(r, nullptr, plane);
            if (f.mirror_missing || curvature.empty() || std::size_t(r.id) >= members.size() ||
                members[std::size_t(r.id)].empty()) {
                out.findings.push_back(f);
                continue;
            }
            // Weighed as a pair is, against the surface at its mirror image.
            const double own = rough[std::size_t(r.id)];
            const double image = spread_of(
                curvature, mirror_image_vertices(surface(), plane, members[std::size_t(r.id)]));
            const bool by_shape = clearly_rougher(own, image);
            const bool show_own = by_shape ? own > image : sign_of(r) < 0;
            if (!show_own) f = at_mirror_image(f, plane);
            f.roughness = show_own ? own : image;
            f.mirror_roughness = show_own ? image : own;
            f.side_by_shape = by_shape;
            out.findings.push_back(f);
            continue;
        }
        paired[std::size_t(j)] = 1;
        // Shown on the side that bends less evenly there, when clearly so; else where the
        // surface has less than the mirrored other side.
        const double ri = rough[std::size_t(r.id)];
        const double rj = rough[std::size_t(regions[std::size_t(j)].id)];
        const bool by_shape = clearly_rougher(ri, rj);
        const bool show_i = by_shape ? ri > rj : sign_of(r) < 0;
        const Region& shown = show_i ? r : regions[std::size_t(j)];
        const Region& image = show_i ? regions[std::size_t(j)] : r;
        AsymmetryFinding f = finding_of(shown, &image, plane);
        f.roughness = show_i ? ri : rj;
        f.mirror_roughness = show_i ? rj : ri;
        f.side_by_shape = by_shape;
        out.findings.push_back(f);
    }
    out.floor = floor_of(out.field, rr.region_of_vertex);
    out.floor.min_depth = result.decisions[zoom].scale.min_depth;
    out.floor.min_area = result.decisions[zoom].scale.min_area;
    return out;
}

void as_side_against_mirror(AnalysisResult& result) {
    for (float& d : result.distance) d = -d;
    for (auto& decision : result.decisions) {
        // Where the mirror has a hole the other side has no surface: no depth of this side
        // was gone there (the pictures and the atlas field show no value, not a loss).
        Comparison& c = decision.comparison;
        for (std::size_t v = 0; v < c.in_hole.size() && v < c.hole_depth.size(); ++v)
            if (c.in_hole[v]) c.hole_depth[v] = std::numeric_limits<float>::quiet_NaN();
        std::fill(c.hole_loss.begin(), c.hole_loss.end(), std::uint8_t{0});
        c.lost_holes = 0;  // report.json's holes.losses: none on this side
        c.lost_hole_area = 0.0;
        for (Region& r : decision.regions.regions) {
            // A hole of the mirror is no loss of this side: the other side has no surface there.
            if (r.hole) r.kind = RegionKind::MissingSurface;
            if (r.kind == RegionKind::MissingSurface) continue;
            r.kind = r.kind == RegionKind::Dent ? RegionKind::Bump : RegionKind::Dent;
            r.peak_depth = -r.peak_depth;
            r.mean_depth = -r.mean_depth;
            r.volume = -r.volume;
            // the decision's sentence gives the signed change: "shape change -0.415 mm beyond …"
            constexpr std::string_view kShape = "shape change ";
            if (r.evidence.starts_with(kShape) && r.evidence.size() > kShape.size()) {
                char& sign = r.evidence[kShape.size()];
                sign = sign == '+' ? '-' : sign == '-' ? '+' : sign;
            }
        }
    }
}

std::string describe(const AsymmetryFinding& f, const std::string& side_name,
                     const std::string& other_name, const std::string& unit) {
    if (f.mirror_missing)
        return side_name + ": no mirrored " + other_name +
               " surface to compare with (missing, or outside the scan), area " +
               with_unit(f.area, unit, 2, "%.3g") + " (region " + std::to_string(f.region) + ")";
    const std::string id = std::to_string(f.region);
    return side_name + ": " + with_unit(std::abs(f.depth), unit, 1, "%.3g") +
           (f.depth < 0 ? " less" : " more") + " than the mirrored " + other_name + ", area " +
           with_unit(f.area, unit, 2, "%.3g") + ", volume " +
           with_unit(std::abs(f.volume), unit, 3, "%.3g") +
           // note: the region lies on the other side, at this place's mirror image: said in
           // that order, so that a reader who finds the region there is not told it is here
           // (issue 51).
           (f.at_mirror_image ? " (found as region " + id + " on the " + other_name +
                                    ", the mirror image of this place; this side has no region "
                                    "of its own)"
            : f.mirror_region ? " (region " + id + ", its mirror image region " +
                                    std::to_string(f.mirror_region) + ")"
                              : " (region " + id + ", no mirror-image region found)");
}

}  // namespace glint
