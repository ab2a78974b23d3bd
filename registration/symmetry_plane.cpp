#include "registration/symmetry_plane.h"

#include "mesh/error.h"
#include "mesh/front_end.h"
#include "mesh/geometry.h"
#include "mesh/parse.h"
#include "mesh/surface_index.h"
#include "registration/closest_point.h"
#include "registration/detail/icp_core.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <utility>

namespace glint {

namespace {

Vec3d vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

// "x,y,z" → a point; `where` names the text in the error.
Vec3d parse_point(std::string_view text, const std::string& where) {
    const std::vector<double> v = parse_number_list(text, where);
    if (v.size() != 3)
        throw InputError(where + ": found " + std::to_string(v.size()) +
                         " numbers, expected three (x,y,z)");
    return vec3(v);
}

// Area centroid and principal axes (columns, largest spread first) of the surface.
std::pair<Vec3d, Eigen::Matrix3d> principal_axes(const Mesh& mesh) {
    const std::vector<double> areas = triangle_areas(mesh);
    double total = 0.0;
    Vec3d centroid = Vec3d::Zero();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        Vec3d c = Vec3d::Zero();
        for (auto v : mesh.triangles[t]) c += mesh.positions[v].cast<double>();
        centroid += areas[t] * c / 3.0;
        total += areas[t];
    }
    if (!(total > 0)) throw InputError("symmetry plane: the mesh has no surface area");
    centroid /= total;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (auto v : mesh.triangles[t]) {
            const Vec3d d = mesh.positions[v].cast<double>() - centroid;
            cov += areas[t] / 3.0 * d * d.transpose();
        }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    return {centroid, eig.eigenvectors().rowwise().reverse()};
}

// The hypotheses are told apart by a short fit; the plane kept is then refined in full.
// note: a wrong axis stays wrong after 3000 samples and 25 iterations (its residual is a
// sizeable share of the shape), while the right one is already within a degree.
constexpr int kQuickSamples = 3000;
constexpr int kQuickIterations = 25;

// One robust fit of the reflection about `plane` onto the surface, and the plane it implies.
struct MirrorFit {
    SymmetryPlane plane;
    RegistrationResult fit;
};

MirrorFit fit_mirror(const Mesh& mesh, const SymmetryPlane& plane, const Vec3d& centroid,
                     const SymmetryPlaneOptions& o,
                     const std::shared_ptr<const SurfaceIndex>& index, bool quick) {
    RegistrationOptions r = o.registration;
    if (quick) {
        r.samples = std::min(r.samples, kQuickSamples);
        r.max_iterations = std::min(r.max_iterations, kQuickIterations);
    }
    r.coarse = false;
    r.initial = Rigid::Identity();
    r.fit_scale = false;  // a mirror image has the surface's own size
    r.initial_scale = 1.0;
    r.measure_scale = false;
    const Mesh mirrored = reflect_mesh(mesh, plane);
    MirrorFit out;
    out.fit = register_meshes(mesh, mirrored, r, index);
    // surface point p → its mirror image S·p → fitted back onto the surface T·S·p.
    const Eigen::Affine3d mirror =
        Eigen::Affine3d(out.fit.reference_from_examined.matrix()) * plane.reflection();
    out.plane = plane_from_mirror(mirror, centroid);
    return out;
}

// How much of the surface has its mirror image on the surface, either face (see
// SymmetryPlaneResult::mirror_share): area-uniform samples inside the fit ROI, reflected about
// the plane, their closest surface points within the overlap distance.
void measure_mirror_share(SymmetryPlaneResult& r, const Mesh& mesh, const SymmetryPlaneOptions& o,
                          const std::shared_ptr<const SurfaceIndex>& index) {
    const RegistrationOptions& g = o.registration;
    const ClosestPointIndex surface =
        index ? ClosestPointIndex(mesh, index) : ClosestPointIndex::borrowing(mesh);
    std::vector<detail::Sample> samples = detail::sample_surface(mesh, g.samples, g.seed + 7);
    if (g.roi) {
        // A vertex mask has no point test: a sample is inside when a corner of its triangle is.
        std::vector<std::uint8_t> inside(samples.size(), 1);
        for (std::size_t i = 0; i < samples.size(); ++i) {
            if (g.roi->shape != Roi::Shape::VertexMask) {
                inside[i] = g.roi->contains_point(samples[i].point);
                continue;
            }
            const Triangle& t = mesh.triangles[surface.closest(samples[i].point).triangle];
            inside[i] =
                g.roi->vertex_mask[t[0]] || g.roi->vertex_mask[t[1]] || g.roi->vertex_mask[t[2]];
        }
        std::size_t k = 0;
        std::erase_if(samples, [&](const detail::Sample&) { return !inside[k++]; });
    }
    const Eigen::Affine3d s = r.plane.reflection();
    std::vector<Vec3d> images;
    images.reserve(samples.size());
    for (const auto& x : samples) images.push_back(s * x.point);
    const std::vector<ClosestPoint> near = surface.closest(images, g.overlap_distance * r.size);
    const double cos_max = std::cos(g.max_normal_angle_deg * detail::kDeg);
    std::size_t found = 0, opposite = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (!near[i].found) continue;
        ++found;
        if (near[i].normal.dot(s.linear() * samples[i].normal) < cos_max) ++opposite;
    }
    r.mirror_share = samples.empty() ? 0.0 : double(found) / double(samples.size());
    r.mirror_share_opposite = found ? double(opposite) / double(found) : 0.0;
}

void judge(SymmetryPlaneResult& r, const SymmetryPlaneOptions& o) {
    const double relative = r.size > 0 ? r.rms / r.size : 0.0;
    const bool shared = r.overlap >= o.min_overlap || r.mirror_share >= o.min_mirror_share;
    r.plausible = r.converged && relative <= o.max_relative_residual && shared;
    char b[600];
    std::snprintf(b, sizeof b,
                  "%s: the mirrored surface fits the surface with residual %.3g (%.2g of its size, "
                  "at most %.2g expected) and overlap %.1f%% (at least %.0f%% expected, or at "
                  "least %.0f%% of the surface with its mirror image on either face: %.1f%%, "
                  "%.0f%% of that on the wall's other face)%s",
                  r.plausible ? "plausibly mirror-symmetric" : "no plausible symmetry plane", r.rms,
                  relative, o.max_relative_residual, 100.0 * r.overlap, 100.0 * o.min_overlap,
                  100.0 * o.min_mirror_share, 100.0 * r.mirror_share,
                  100.0 * r.mirror_share_opposite, r.converged ? "" : "; the fit did not converge");
    r.verdict = b;
}

void take_fit(SymmetryPlaneResult& r, const RegistrationResult& fit) {
    r.rms = fit.rms;
    r.inlier_fraction = fit.inlier_fraction;
    r.overlap = fit.overlap;
    r.converged = fit.converged;
}

}  // namespace

Eigen::Affine3d SymmetryPlane::reflection() const {
    Eigen::Affine3d s = Eigen::Affine3d::Identity();
    s.linear() -= 2.0 * normal * normal.transpose();
    s.translation() = 2.0 * offset * normal;
    return s;
}

SymmetryPlane plane_through(const Vec3d& point, const Vec3d& normal) {
    if (!(normal.norm() > 0) || !normal.allFinite())
        throw InputError("plane: normal (" + std::to_string(normal.x()) + ", " +
                         std::to_string(normal.y()) + ", " + std::to_string(normal.z()) +
                         ") has no direction; expected a non-zero vector");
    SymmetryPlane p;
    p.normal = normal.normalized();
    p.offset = p.normal.dot(point);
    return p;
}

SymmetryPlane parse_plane_spec(const std::string& text) {
    // note: --plane "x=3" on the command line, plane='x=3' in Python (mesh/front_end.h).
    const std::string where = front_end() == FrontEnd::Python
                                  ? spell_option("plane", text)
                                  : spell_option("plane", "\"" + text + "\"");
    const auto eq = text.find('=');
    if (text.size() >= 2 && eq == 1 && std::string("xyz").find(text[0]) != std::string::npos) {
        const std::vector<double> c = parse_number_list(text.substr(2), where);
        if (c.size() != 1) throw InputError(where + ": expected one number after '='");
        Vec3d n = Vec3d::Zero();
        n[text[0] - 'x'] = 1.0;
        return plane_through(c[0] * n, n);
    }
    if (text.rfind("landmarks=", 0) == 0) {
        std::vector<Vec3d> p;
        std::string_view rest = std::string_view(text).substr(10);
        for (std::size_t start = 0; start <= rest.size();) {
            const std::size_t end = std::min(rest.find('/', start), rest.size());
            p.push_back(parse_point(rest.substr(start, end - start), where));
            start = end + 1;
        }
        if (p.size() != 3)
            throw InputError(where + ": found " + std::to_string(p.size()) +
                             " landmarks, expected three (x,y,z/x,y,z/x,y,z)");
        const Vec3d n = (p[1] - p[0]).cross(p[2] - p[0]);
        if (!(n.norm() > 1e-12 * (p[1] - p[0]).squaredNorm()))
            throw InputError(where + ": the three landmarks lie on one line; expected a triangle");
        return plane_through(p[0], n);
    }
    const auto semi = text.find(';');
    if (text.rfind("point=", 0) == 0 && semi != std::string::npos &&
        text.compare(semi + 1, 7, "normal=") == 0)
        return plane_through(parse_point(text.substr(6, semi - 6), where),
                             parse_point(text.substr(semi + 8), where));
    throw InputError(where +
                     ": expected x=C, y=C, z=C, point=x,y,z;normal=x,y,z or "
                     "landmarks=x,y,z/x,y,z/x,y,z");
}

std::string to_string(const SymmetryPlane& plane) {
    const Vec3d p = plane.point();
    const Vec3d& n = plane.normal;
    char b[200];
    std::snprintf(b, sizeof b, "point=%.9g,%.9g,%.9g;normal=%.9g,%.9g,%.9g", p.x(), p.y(), p.z(),
                  n.x(), n.y(), n.z());
    return b;
}

SymmetryPlane plane_from_mirror(const Eigen::Affine3d& mirror, const Vec3d& at) {
    const Eigen::Matrix3d l = mirror.linear();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (l + l.transpose()));
    // Eigenvalues ascending: the first is the one nearest −1. Its sign is free: the largest
    // component is made positive, so a plane near x = 0 reads as normal +x.
    Vec3d normal = eig.eigenvectors().col(0);
    Eigen::Index axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    if (normal[axis] < 0) normal = -normal;
    return plane_through(0.5 * (at + mirror * at), normal);
}

Mesh reflect_mesh(const Mesh& mesh, const SymmetryPlane& plane) {
    Mesh out = mesh;
    const Eigen::Affine3d s = plane.reflection();
    const Eigen::Matrix3d l = s.linear();
    for (auto& p : out.positions) p = (s * p.cast<double>()).cast<float>();
    for (auto& n : out.normals) n = (l * n.cast<double>()).cast<float>();
    for (auto& t : out.triangles) std::swap(t[1], t[2]);
    // Where the acquisition saw, and its grid, are reflected with the surface: the mirror of a
    // scan cut at one side is cut at the other (the comparison reads both, beyond_view).
    if (out.voxel_axes) *out.voxel_axes = l * *out.voxel_axes;
    Eigen::Isometry3d improper = Eigen::Isometry3d::Identity();
    improper.matrix() = s.matrix();
    out.field_of_view.transform(improper);
    return out;
}

void SymmetryPlaneOptions::validate() const {
    registration.validate();
    if (refinements < 0 || refinements > 10)
        throw OptionError("refinements", refinements, "must be in [0, 10]");
    if (!(max_relative_residual > 0))
        throw OptionError("max_relative_residual", max_relative_residual, "must be > 0");
    if (!(min_overlap >= 0 && min_overlap <= 1))
        throw OptionError("min_overlap", min_overlap, "must be in [0, 1]");
    if (!(min_mirror_share >= 0 && min_mirror_share <= 1))
        throw OptionError("min_mirror_share", min_mirror_share, "must be in [0, 1]");
}

SymmetryPlaneResult estimate_symmetry_plane(const Mesh& mesh, const SymmetryPlaneOptions& o) {
    o.validate();
    if (mesh.triangles.empty()) throw InputError("symmetry plane: the mesh has no triangles");
    const auto [centroid, axes] = principal_axes(mesh);
    const auto index = std::make_shared<const SurfaceIndex>(mesh);
    SymmetryPlaneResult r;
    r.size = bounds(mesh).diagonal();
    static const char* const kSpread[] = {"largest", "middle", "smallest"};
    MirrorFit best;
    double best_score = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const MirrorFit f =
            fit_mirror(mesh, plane_through(centroid, axes.col(a)), centroid, o, index, true);
        SymmetryHypothesis h{
            .name = "principal axis " + std::to_string(a + 1) + " (" + kSpread[a] + " spread)",
            .plane = f.plane,
            .rms = f.fit.rms,
            .overlap = f.fit.overlap,
            .converged = f.fit.converged};
        // A fit that matched less of the surface is worse: residual over matched share².
        const double score =
            h.overlap > 0 ? h.rms / (h.overlap * h.overlap) : std::numeric_limits<double>::max();
        if (score < best_score) {
            best_score = score;
            best = f;
            r.source = h.name;
        }
        r.hypotheses.push_back(std::move(h));
    }
    for (int i = 0; i < o.refinements; ++i)
        best = fit_mirror(mesh, best.plane, centroid, o, index, false);
    r.plane = best.plane;
    take_fit(r, best.fit);
    measure_mirror_share(r, mesh, o, index);
    judge(r, o);
    return r;
}

SymmetryPlaneResult check_symmetry_plane(const Mesh& mesh, const SymmetryPlane& plane,
                                         const SymmetryPlaneOptions& o) {
    o.validate();
    if (mesh.triangles.empty()) throw InputError("symmetry plane: the mesh has no triangles");
    // A plane that does not cut the surface's box has no mirror image to fit: --plane x=1e12
    // spent 15-50 s in closest-point queries deaf to SIGINT, then said "do not overlap … check
    // the fit" (issue 52). Refused before any query, in words about the plane.
    const Bounds box = bounds(mesh);
    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3d p((corner & 1 ? box.max : box.min).x(), (corner & 2 ? box.max : box.min).y(),
                      (corner & 4 ? box.max : box.min).z());
        lowest = std::min(lowest, plane.distance(p));
        highest = std::max(highest, plane.distance(p));
    }
    if (!(lowest <= 0 && highest >= 0))
        throw InputError("symmetry plane " + to_string(plane) + ": lies " +
                         std::to_string(std::min(std::fabs(lowest), std::fabs(highest))) +
                         " mesh units off the surface (its bounding box, " +
                         std::to_string(box.diagonal()) +
                         " across, lies wholly on one side); expected a plane through the surface");
    const Vec3d centroid = principal_axes(mesh).first;
    SymmetryPlaneResult r;
    r.size = box.diagonal();
    r.source = "given";
    r.plane = plane;
    const MirrorFit f = fit_mirror(mesh, plane, centroid, o, nullptr, false);
    take_fit(r, f.fit);
    r.hypotheses.push_back({.name = "the plane the fit from the given one implies",
                            .plane = f.plane,
                            .rms = f.fit.rms,
                            .overlap = f.fit.overlap,
                            .converged = f.fit.converged});
    measure_mirror_share(r, mesh, o, nullptr);
    judge(r, o);
    return r;
}

}  // namespace glint
