#include "decision/comparison.h"

#include "decision/detail/fused_rule.h"
#include "mesh/components.h"
#include "mesh/error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <sstream>

namespace glint {

std::string to_string(CompareClass c) {
    switch (c) {
        case CompareClass::Compared: return "compared";
        case CompareClass::ReferenceBorder: return "reference border";
        case CompareClass::ExaminedBorder: return "examined border";
        case CompareClass::NotReached: return "not reached";
        case CompareClass::BelowResolution: return "below resolution";
    }
    return "?";
}

namespace {

double median_edge(const Mesh& mesh) {
    std::vector<double> e;
    e.reserve(3 * mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        for (std::size_t k = 0; k < 3; ++k)
            e.push_back(
                (mesh.positions[t[k]] - mesh.positions[t[(k + 1) % 3]]).cast<double>().norm());
    if (e.empty()) return 0.0;
    const auto mid = e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2);
    std::nth_element(e.begin(), mid, e.end());
    return *mid;
}

// Per gone group: the longest run of the reference's own open border inside it (`open`, in
// vertices: one loop of border vertices joined by edges) and how many of its vertices lie next
// to surface the examined scan reached (`closed`). The strip between two fields of view holds
// the reference's whole cut, about as long as its rim on the other side; a hole the scan
// covered around holds at most a few small openings of the reference (the EDJ crown's), each
// short against its rim. Vertices, not edge lengths: a triangulation's diagonals would weigh
// the closed side more.
void rim_counts(const detail::Adjacency& adj, const std::vector<std::int32_t>& group,
                std::size_t groups, const std::vector<std::uint8_t>& border,
                std::vector<double>& open, std::vector<double>& closed) {
    open.assign(groups, 0.0);
    closed.assign(groups, 0.0);
    std::vector<std::uint8_t> visited(group.size(), 0);
    std::vector<std::uint32_t> stack;
    for (std::size_t v = 0; v < group.size(); ++v) {
        if (group[v] < 0) continue;
        const auto g = static_cast<std::size_t>(group[v]);
        for (std::uint32_t i = adj.offset[v]; i < adj.offset[v + 1]; ++i)
            if (group[adj.index[i]] < 0) {
                closed[g] += 1.0;
                break;
            }
        if (!border[v] || visited[v]) continue;
        double run = 0.0;  // the border vertices of this group joined to v
        stack.assign(1, static_cast<std::uint32_t>(v));
        visited[v] = 1;
        while (!stack.empty()) {
            const std::uint32_t u = stack.back();
            stack.pop_back();
            run += 1.0;
            for (std::uint32_t i = adj.offset[u]; i < adj.offset[u + 1]; ++i) {
                const std::uint32_t w = adj.index[i];
                if (border[w] && !visited[w] && group[w] == group[v]) {
                    visited[w] = 1;
                    stack.push_back(w);
                }
            }
        }
        open[g] = std::max(open[g], run);
    }
}

// Vertices within `width` of a seed, along mesh edges (multi-source Dijkstra).
std::vector<std::uint8_t> band_of(const Mesh& mesh, const detail::Adjacency& adj,
                                  const std::vector<std::uint8_t>& seed, double width) {
    const std::size_t n = seed.size();
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, std::uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (std::size_t v = 0; v < n; ++v)
        if (seed[v]) {
            dist[v] = 0.0;
            queue.emplace(0.0, static_cast<std::uint32_t>(v));
        }
    while (!queue.empty()) {
        const auto [d, u] = queue.top();
        queue.pop();
        if (d > dist[u]) continue;
        for (std::uint32_t i = adj.offset[u]; i < adj.offset[u + 1]; ++i) {
            const std::uint32_t w = adj.index[i];
            const double dw = d + (mesh.positions[u] - mesh.positions[w]).cast<double>().norm();
            if (dw < dist[w] && dw <= width) {
                dist[w] = dw;
                queue.emplace(dw, w);
            }
        }
    }
    std::vector<std::uint8_t> band(n);
    for (std::size_t v = 0; v < n; ++v) band[v] = std::isfinite(dist[v]) ? 1 : 0;
    return band;
}

// The signed depth of the surface gone in one hole (see comparison.h): minus the height above
// the plane through its rim where the reference stood above it, or where the examined surface
// cannot drop out (`no_dropouts`), else 0 (depth unknown). Returns whether the hole is a loss.
bool hole_shape(const Mesh& mesh, const detail::Adjacency& adj,
                const std::vector<std::int32_t>& group, std::int32_t id,
                const std::vector<std::uint32_t>& members, const std::vector<double>& area,
                bool no_dropouts, std::vector<float>& depth) {
    Vec3d sum{0, 0, 0};
    std::vector<Vec3d> rim;
    for (const auto u : members)
        for (std::uint32_t i = adj.offset[u]; i < adj.offset[u + 1]; ++i) {
            const auto w = adj.index[i];
            if (group[w] != id) rim.push_back(mesh.positions[w].cast<double>());
        }
    if (rim.size() < 3) {
        for (const auto u : members) depth[u] = 0.0f;
        return no_dropouts;
    }
    for (const auto& p : rim) sum += p;
    const Vec3d c = sum / static_cast<double>(rim.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : rim) cov += (p - c) * (p - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    Vec3d normal = solver.eigenvectors().col(0);
    Vec3d facing{0, 0, 0};
    if (mesh.has_normals())
        for (const auto u : members) facing += area[u] * mesh.normals[u].cast<double>();
    if (normal.dot(facing) < 0) normal = -normal;
    double height = 0.0, weight = 0.0;
    for (const auto u : members) {
        height += area[u] * normal.dot(mesh.positions[u].cast<double>() - c);
        weight += area[u];
    }
    // Surface gone inside a rim the examined scan covered is a loss where the reference stood
    // above the plane through the rim (a worn cusp): its depth is the height above the plane,
    // a dent where it reaches the shape floor (decision.cpp). Over a flat or concave patch (a
    // scanner's dropout, a pit) the rim cannot tell removed material from surface never
    // captured, unless the examined surface cannot drop out: then it is a loss all the same,
    // at least as deep as the reference stood above the rim (the EDJ crown's mild cusp wear:
    // 140 vertices 0.02 mm below their rim's plane on average, up to 0.05 mm above it).
    // Else 0, "missing surface".
    const bool loss = (weight > 0 && height > 0) || no_dropouts;
    for (const auto u : members)
        depth[u] = loss ? static_cast<float>(
                              -std::max(0.0, normal.dot(mesh.positions[u].cast<double>() - c)))
                        : 0.0f;
    return loss;
}

std::string rule_text(const Comparison& c) {
    std::ostringstream s;
    s.precision(3);
    s << "not compared: within " << kBandEdges << " median edges (" << c.band
      << ") of a border of the reference, or of a part the examined surface did not reach (no "
         "examined surface behind most views, or its closest point on an examined border "
         "beyond half an edge); a part without examined surface that stays off the reference's "
         "borders (under a quarter of its area next to them, no run of them half as long as its "
         "rim), inside the examined scan's field of view where it is known (not within a voxel "
         "of its cut) "
         "and under "
      << 100.0 * (c.examined_encloses ? kMaxLossShare : kMaxHoleShare) << " % of its area"
      << (c.examined_encloses ? " (the examined surface encloses its solid: what it lacks is gone)"
                              : "")
      << " is a hole the examined scan covered around: compared (a loss where the "
         "reference stood above the hole's rim or where the examined surface is no one-view "
         "scan and so cannot drop out, at least as deep as the reference stood above the rim; "
         "else missing surface), unless the examined "
         "surface is a one-view scan that faced most of it beyond "
      << kGrazingDeg
      << "° (a scanner's dropout: not reached); a damaged group with more than half its area "
         "not compared is dropped";
    return s.str();
}

}  // namespace

bool encloses(const Mesh& surface) {
    const double area = surface_area(surface);
    return area > 0 && border_length(surface) <= kMaxEnclosedBorder * std::sqrt(area);
}

Comparison classify_comparison(const Mesh& mesh, const ComparisonInputs& in) {
    const std::size_t n = mesh.vertex_count();
    GLINT_ASSERT(in.seen && in.seen->size() == n && in.missing && in.missing->size() == n,
                 "comparison inputs do not match the mesh");
    Comparison c;
    c.edge = median_edge(mesh);
    c.band = kBandEdges * c.edge;
    c.examined_encloses = in.examined_encloses;
    c.rule = rule_text(c);
    const detail::Adjacency adj = detail::adjacency(mesh);
    const auto area = vertex_areas(mesh);
    for (const double a : area) c.reference_area += a;
    const bool have_distance = in.distance && in.distance->size() == n;
    const auto flagged = [&](const std::vector<std::uint8_t>* f, std::size_t v) {
        return have_distance && f && f->size() == n && (*f)[v] &&
               std::abs((*in.distance)[v]) > 0.5 * c.edge;
    };
    std::vector<std::uint8_t> gone(n, 0);
    for (std::size_t v = 0; v < n; ++v)
        gone[v] = ((*in.seen)[v] && (*in.missing)[v] > 0.5f) || flagged(in.at_border, v) ||
                  flagged(in.facing_away, v);
    // note: one edge along the reference's own borders — on the EDJ crown small borders lie
    // next to the cusps, and 4 edges cut worn cusps and a cusp erosion short (F1 0.65); where the
    // examined surface is cut as well, its not-reached strip carries the wide band.
    const auto border = border_vertices(mesh);
    const auto reference_band = band_of(mesh, adj, border, c.edge);
    std::vector<std::int32_t> group;
    const std::size_t groups = masked_components(mesh, gone, group);
    std::vector<double> group_area(groups, 0.0);
    std::vector<double> banded(groups, 0.0);  // area inside the reference's border band
    std::vector<std::vector<std::uint32_t>> members(groups);
    for (std::size_t v = 0; v < n; ++v) {
        if (group[v] < 0) continue;
        const auto g = static_cast<std::size_t>(group[v]);
        group_area[g] += area[v];
        if (reference_band[v]) banded[g] += area[v];
        members[g].push_back(static_cast<std::uint32_t>(v));
    }
    std::vector<double> open_rim, closed_rim;
    rim_counts(adj, group, groups, border, open_rim, closed_rim);
    // A group around the reference's own cut: a long run of its open border, and a surface that
    // turns round (its normals cancel: a band round a bone, not a cap worn off a cusp).
    const auto field_of_view = [&](std::size_t g) {
        if (!(open_rim[g] >= kMaxOpenRim * (open_rim[g] + closed_rim[g]))) return false;
        if (!mesh.has_normals()) return true;
        Vec3d sum = Vec3d::Zero();
        for (const auto u : members[g]) sum += area[u] * mesh.normals[u].cast<double>();
        return sum.norm() < kMinCapCoherence * group_area[g];
    };
    // A gone group the examined one-view scan saw at grazing incidence over most of its area.
    if (in.scan_view) c.scan_view = *in.scan_view;
    const double grazing_cos = std::cos(kGrazingDeg * std::numbers::pi / 180.0);
    const auto grazing = [&](std::size_t g) {
        if (!in.scan_view || !mesh.has_normals()) return false;
        double beyond = 0.0;
        for (const auto u : members[g])
            if (mesh.normals[u].cast<double>().dot(in.scan_view->direction) < grazing_cos)
                beyond += area[u];
        return beyond > 0.5 * group_area[g];
    };
    // A gone group the examined scan's field of view does not hold wholly.
    const bool have_view = in.beyond_view && in.beyond_view->size() == n;
    const auto beyond_view = [&](std::size_t g) {
        if (!have_view) return false;
        for (const auto u : members[g])
            if ((*in.beyond_view)[u]) return true;
        return false;
    };
    c.hole_depth.assign(n, std::numeric_limits<float>::quiet_NaN());
    c.in_hole.assign(n, 0);
    c.hole_loss.assign(n, 0);
    std::vector<std::uint8_t> not_reached(n, 0);
    for (std::size_t g = 0; g < groups; ++g) {
        // note: a quarter — a worn cusp of the EDJ crown reaches the band of a small border
        // of the reference with a sliver of its area; a strip beyond a field-of-view cut lies
        // mostly in the band of the reference's own cut. A wide strip (two fields of view 6 mm
        // apart) has little of its area in that band but a third or more of its rim on the cut.
        const bool cut_by_view = beyond_view(g);
        // An examined surface that encloses its solid holds surface wherever the object has
        // some: a larger part without it (a resection) is gone, not unscanned.
        const double max_share = in.examined_encloses ? kMaxLossShare : kMaxHoleShare;
        const bool hole = !cut_by_view && banded[g] <= 0.25 * group_area[g] && !field_of_view(g) &&
                          group_area[g] <= max_share * c.reference_area;
        if (cut_by_view) {
            ++c.beyond_view;
            c.beyond_view_area += group_area[g];
        } else if (hole && grazing(g)) {
            ++c.dropouts;
            c.dropout_area += group_area[g];
        } else if (hole) {
            ++c.holes;
            c.hole_area += group_area[g];
            const bool loss = hole_shape(mesh, adj, group, static_cast<std::int32_t>(g), members[g],
                                         area, !in.scan_view, c.hole_depth);
            if (loss) {
                ++c.lost_holes;
                c.lost_hole_area += group_area[g];
            }
            for (const auto u : members[g]) {
                c.in_hole[u] = 1;
                c.hole_loss[u] = loss ? 1 : 0;
            }
            continue;
        }
        for (const auto u : members[g]) not_reached[u] = 1;
    }
    const auto examined_band = band_of(mesh, adj, not_reached, c.band);
    const auto border_band = band_of(mesh, adj, border, c.band);
    c.vertex_class.assign(n, static_cast<std::uint8_t>(CompareClass::Compared));
    const bool unresolved = in.below_resolution && in.below_resolution->size() == n;
    for (std::size_t v = 0; v < n; ++v) {
        CompareClass k = CompareClass::Compared;
        if (not_reached[v]) k = CompareClass::NotReached;
        else if (c.in_hole[v]) k = CompareClass::Compared;  // a hole is compared, also at a border
        else if (border_band[v]) k = CompareClass::ReferenceBorder;
        else if (examined_band[v]) k = CompareClass::ExaminedBorder;
        else if (unresolved && (*in.below_resolution)[v]) k = CompareClass::BelowResolution;
        c.vertex_class[v] = static_cast<std::uint8_t>(k);
        double& sum = k == CompareClass::Compared          ? c.compared_area
                      : k == CompareClass::NotReached      ? c.not_reached_area
                      : k == CompareClass::ReferenceBorder ? c.reference_border_area
                      : k == CompareClass::ExaminedBorder  ? c.examined_border_area
                                                           : c.below_resolution_area;
        sum += area[v];
    }
    c.fraction = c.reference_area > 0 ? c.compared_area / c.reference_area : 0.0;
    return c;
}

namespace {

// The area below resolution and the whole area of each group's footprint: its vertices and
// those within `radius` of one (reached through mesh edges, each measured from the group vertex
// it was reached from), where evidence read over that radius comes from.
void footprint_areas(const Mesh& mesh, const std::vector<std::int32_t>& group, std::size_t groups,
                     const std::vector<double>& area, const Comparison& c, double radius,
                     std::vector<double>& total, std::vector<double>& thin) {
    const auto is_thin = [&](std::size_t v) {
        return c.vertex_class[v] == static_cast<std::uint8_t>(CompareClass::BelowResolution);
    };
    total.assign(groups, 0.0);
    thin.assign(groups, 0.0);
    const std::size_t n = mesh.vertex_count();
    std::vector<std::int32_t> reached_by(n, -1);  // the group that reached it (first wins)
    std::vector<std::uint32_t> source(n, 0);
    std::vector<std::uint32_t> queue;
    for (std::size_t v = 0; v < n; ++v)
        if (group[v] >= 0) {
            reached_by[v] = group[v];
            source[v] = static_cast<std::uint32_t>(v);
            queue.push_back(static_cast<std::uint32_t>(v));
        }
    if (radius > 0) {
        const detail::Adjacency adj = detail::adjacency(mesh);
        const double r2 = radius * radius;
        for (std::size_t head = 0; head < queue.size(); ++head) {
            const std::uint32_t u = queue[head];
            for (std::uint32_t k = adj.offset[u]; k < adj.offset[u + 1]; ++k) {
                const std::uint32_t w = adj.index[k];
                if (reached_by[w] >= 0 ||
                    (mesh.positions[w] - mesh.positions[source[u]]).squaredNorm() > r2)
                    continue;
                reached_by[w] = reached_by[u];
                source[w] = source[u];
                queue.push_back(w);
            }
        }
    }
    for (std::size_t v = 0; v < n; ++v) {
        if (reached_by[v] < 0) continue;
        const auto g = static_cast<std::size_t>(reached_by[v]);
        total[g] += area[v];
        if (is_thin(v)) thin[g] += area[v];
    }
}

}  // namespace

std::size_t drop_border_groups(const Mesh& mesh, std::vector<std::uint8_t>& damaged,
                               const Comparison& c, double radius) {
    const std::size_t n = mesh.vertex_count();
    if (c.vertex_class.size() != n || damaged.size() != n) return 0;
    const auto area = vertex_areas(mesh);
    for (std::size_t v = 0; v < n; ++v)
        if (c.vertex_class[v] == static_cast<std::uint8_t>(CompareClass::NotReached))
            damaged[v] = 0;
    std::vector<std::int32_t> group;
    const std::size_t groups = masked_components(mesh, damaged, group);
    std::vector<double> total(groups, 0.0), banded(groups, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
        if (group[v] < 0) continue;
        const auto g = static_cast<std::size_t>(group[v]);
        total[g] += area[v];
        if (!c.compared(v)) banded[g] += area[v];
    }
    std::vector<double> footprint, thin;
    footprint_areas(mesh, group, groups, area, c, radius, footprint, thin);
    std::size_t dropped = 0;
    std::vector<std::uint8_t> drop(groups, 0);
    for (std::size_t g = 0; g < groups; ++g)
        if (banded[g] > kBorderMajority * total[g] ||
            thin[g] > kBelowResolutionShare * footprint[g]) {
            drop[g] = 1;
            ++dropped;
        }
    for (std::size_t v = 0; v < n; ++v)
        if (group[v] >= 0 && drop[static_cast<std::size_t>(group[v])]) damaged[v] = 0;
    return dropped;
}

}  // namespace glint
