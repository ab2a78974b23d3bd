#include "scenario/detail/partial_scan.h"

#include "mesh/error.h"
#include "mesh/weld.h"

#include <map>
#include <numeric>
#include <sstream>
#include <utility>

namespace glint::detail {

namespace {

// Vertices where the kept triangles meet in more than one fan (more than two border edges):
// a cut leaves such bow-ties where it passes a vertex between two kept triangles. Remeshing and
// every scanner's own output are manifold there, so the triangles around them go, until none
// is left. Returns the triangles dropped.
std::size_t drop_bow_ties(Mesh& mesh) {
    std::size_t dropped = 0;
    for (int pass = 0; pass < 32; ++pass) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const Triangle& t : mesh.triangles)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                ++uses[{std::min(a, b), std::max(a, b)}];
            }
        std::vector<int> border(mesh.vertex_count(), 0);
        for (const auto& [e, n] : uses)
            if (n == 1) {
                ++border[e.first];
                ++border[e.second];
            }
        std::vector<Triangle> kept;
        for (const Triangle& t : mesh.triangles)
            if (border[t[0]] <= 2 && border[t[1]] <= 2 && border[t[2]] <= 2) kept.push_back(t);
        if (kept.size() == mesh.triangle_count()) break;
        dropped += mesh.triangle_count() - kept.size();
        mesh.triangles = std::move(kept);
    }
    return dropped;
}

}  // namespace

std::optional<Eigen::Vector4d> read_crop_ball(TableReader& r) {
    const auto v = r.numbers("crop_ball", 4, 4);
    if (!v) return std::nullopt;
    if (!((*v)[3] > 0))
        r.fail(r.get("crop_ball"), "crop_ball", "the radius (number 4) must be > 0: [x, y, z, r]");
    return Eigen::Vector4d((*v)[0], (*v)[1], (*v)[2], (*v)[3]);
}

std::string crop_reference(ScenarioMeshes& out, const Eigen::Vector4d& ball) {
    Mesh& mesh = out.reference;
    const Vec3d center = ball.head<3>();
    const double area = surface_area(mesh);
    const std::size_t triangles = mesh.triangle_count();
    std::vector<bool> keep(mesh.vertex_count());
    for (std::size_t v = 0; v < keep.size(); ++v)
        keep[v] = (mesh.positions[v].cast<double>() - center).norm() <= ball[3];
    std::vector<std::uint32_t> id = compact_vertices(mesh, keep);
    std::vector<bool> used(mesh.vertex_count(), false);
    for (const Triangle& t : mesh.triangles)
        for (std::uint32_t v : t) used[v] = true;
    const std::vector<std::uint32_t> second = compact_vertices(mesh, used);
    for (auto& n : id)
        if (n != kInvalidVertex) n = second[n];
    if (mesh.triangle_count() == 0 || mesh.triangle_count() == triangles) {
        std::ostringstream what;
        what << "reference crop_ball: the ball at (" << center.transpose() << ") of radius "
             << ball[3] << " holds " << (mesh.triangle_count() == 0 ? "no" : "every")
             << " triangle of the reference; expected a ball around a part of it";
        throw InputError(what.str());
    }
    // The per-vertex truth of the whole follows its kept vertices.
    auto follow = [&](auto& values) {
        if (values.size() != id.size()) return;
        std::remove_reference_t<decltype(values)> kept(mesh.vertex_count());
        for (std::size_t v = 0; v < id.size(); ++v)
            if (id[v] != kInvalidVertex) kept[id[v]] = values[v];
        values = std::move(kept);
    };
    follow(out.truth);
    follow(out.truth_damage);
    follow(out.true_distance);
    std::ostringstream note;
    note.precision(3);
    note << "reference: cropped to the ball at (" << center.transpose() << ") of radius " << ball[3]
         << ": " << mesh.triangle_count() << " of " << triangles << " triangles, "
         << 100.0 * surface_area(mesh) / area << " % of the area; the examined keeps the whole";
    return note.str();
}

std::optional<ScanCut> read_scan_cut(TableReader& r) {
    const auto v = r.numbers("keep_side", 6, 6);
    if (!v) return std::nullopt;
    ScanCut cut{Vec3d((*v)[0], (*v)[1], (*v)[2]), Vec3d((*v)[3], (*v)[4], (*v)[5])};
    if (!(cut.normal.norm() > 0))
        r.fail(r.get("keep_side"), "keep_side",
               "the normal (numbers 4 to 6) must not be zero: [x, y, z, nx, ny, nz]");
    cut.normal.normalize();
    return cut;
}

std::string cut_scan(Mesh& mesh, const ScanCut& cut, const std::string& role) {
    const std::vector<double> before = triangle_areas(mesh);
    const double area = std::accumulate(before.begin(), before.end(), 0.0);
    std::vector<bool> keep(mesh.vertex_count());
    for (std::size_t v = 0; v < keep.size(); ++v)
        keep[v] = cut.normal.dot(mesh.positions[v].cast<double>() - cut.point) >= 0.0;
    const std::size_t triangles = mesh.triangle_count();
    (void)compact_vertices(mesh, keep);  // triangles with a corner on the other side go too
    drop_bow_ties(mesh);
    std::vector<bool> used(mesh.vertex_count(), false);
    for (const Triangle& t : mesh.triangles)
        for (std::uint32_t v : t) used[v] = true;
    (void)compact_vertices(mesh, used);
    const std::vector<double> after = triangle_areas(mesh);
    const double kept = std::accumulate(after.begin(), after.end(), 0.0);
    std::ostringstream plane;
    plane << "the plane through (" << cut.point.transpose() << ") with normal ("
          << cut.normal.transpose() << ")";
    if (mesh.triangle_count() == 0 || mesh.triangle_count() == triangles)
        throw InputError(role + " keep_side: " + plane.str() + " keeps " +
                         (mesh.triangle_count() == 0 ? "nothing" : "every triangle") + " of the " +
                         role + " surface; expected a plane across it");
    std::ostringstream note;
    note.precision(3);
    note << role << ": a partial scan, the side of " << plane.str() << ": " << mesh.triangle_count()
         << " of " << triangles << " triangles, " << 100.0 * kept / area << " % of the area";
    return note.str();
}

void cut_pair(const Scenario& sc, ScenarioMeshes& out, const Rigid& examined_from_reference) {
    if (sc.reference.cut)
        out.notes.push_back(cut_scan(out.reference, *sc.reference.cut, "reference"));
    if (!sc.examined.cut) return;
    const ScanCut moved{examined_from_reference * sc.examined.cut->point,
                        examined_from_reference.linear() * sc.examined.cut->normal};
    out.notes.push_back(cut_scan(out.examined, moved, "examined"));
}

}  // namespace glint::detail
