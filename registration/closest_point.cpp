#include "registration/closest_point.h"

#include "mesh/components.h"
#include "mesh/error.h"
#include "mesh/normals.h"
#include "mesh/surface_index.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace glint {

// Per-mesh data the queries read: normals for the sign and the interpolated normal.
// note: the pseudo-normals are made at query time from the mesh (the face normals as
// face_normal() gives them, the mesh's vertex normals), summed in double, exactly as a table
// of them in double would give: an edge's is the sum of the normals of the
// triangles sharing it, in triangle order, found through the triangles around its first
// corner. A per-edge table in double (72 bytes per triangle) and the hash map that built it
// cost more time and memory than the whole BVH.
struct ClosestPointIndexData {
    const Mesh* mesh = nullptr;
    VertexTriangles around;  // triangles around each vertex, ascending

    [[nodiscard]] Vec3d vertex_normal(std::uint32_t v) const {
        return mesh->normals[v].cast<double>();
    }
    [[nodiscard]] Vec3d face_normal(std::uint32_t t) const {
        return glint::face_normal(*mesh, t).cast<double>();
    }
    // Sum of the normals of the triangles sharing edge (a, b), in triangle order.
    [[nodiscard]] Vec3d edge_normal(std::uint32_t a, std::uint32_t b) const {
        Vec3d sum = Vec3d::Zero();
        for (std::uint32_t i = around.offsets[a]; i < around.offsets[a + 1]; ++i) {
            const std::uint32_t t = around.triangles[i];
            const auto& tri = mesh->triangles[t];
            if (tri[0] == b || tri[1] == b || tri[2] == b) sum += face_normal(t);
        }
        return sum;
    }
};

namespace {

struct QueryState {
    const ClosestPointIndexData* data;
    Vec3d query;
    ClosestPoint best;
    int feature_index = 0;
};

}  // namespace

struct ClosestPointIndex::Impl {
    std::shared_ptr<const SurfaceIndex> index;  // the BVH (mesh/surface_index.h)
    RTCScene scene = nullptr;                   // index's
    ClosestPointIndexData data;
    Mesh own_mesh;  // the copy the queries read (empty when the index reads the caller's mesh)
    double diagonal = 0.0;  // of the mesh's bounding box
};

namespace {

// The smallest float at or above d: Embree culls with a float radius, and a radius rounded
// down could cull a triangle closer (in double) than the best found so far, so the point
// found would depend on the order the BVH is walked in.
float float_above(double d) {
    const auto f = static_cast<float>(d);
    return static_cast<double>(f) >= d ? f
                                       : std::nextafter(f, std::numeric_limits<float>::infinity());
}

bool point_query_callback(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<QueryState*>(args->userPtr);
    const ClosestPointIndexData& d = *state->data;
    const Mesh& m = *d.mesh;
    const auto& tri = m.triangles[args->primID];
    const TrianglePoint tp = closest_point_on_triangle(
        state->query, m.positions[tri[0]].cast<double>(), m.positions[tri[1]].cast<double>(),
        m.positions[tri[2]].cast<double>());
    constexpr ClosestFeature kFeature[3] = {ClosestFeature::Face, ClosestFeature::Edge,
                                            ClosestFeature::Vertex};
    const double dist = (tp.point - state->query).norm();
    if (dist < state->best.distance) {
        state->best.found = true;
        state->best.distance = dist;
        state->best.point = tp.point;
        state->best.triangle = args->primID;
        state->best.barycentric = tp.barycentric;
        state->best.feature = kFeature[tp.feature];
        state->feature_index = tp.index;
        args->query->radius = float_above(dist);
        return true;
    }
    return false;
}

void finish_query(const ClosestPointIndexData& d, QueryState& s) {
    if (!s.best.found) return;
    const Mesh& m = *d.mesh;
    const auto& tri = m.triangles[s.best.triangle];
    const auto k = static_cast<std::size_t>(s.feature_index);
    Vec3d pseudo = Vec3d::Zero();
    switch (s.best.feature) {
        case ClosestFeature::Face: pseudo = d.face_normal(s.best.triangle); break;
        case ClosestFeature::Edge: pseudo = d.edge_normal(tri[k], tri[(k + 1) % 3]); break;
        case ClosestFeature::Vertex: pseudo = d.vertex_normal(tri[k]); break;
    }
    const double side = (s.query - s.best.point).dot(pseudo);
    s.best.signed_distance = side < 0 ? -s.best.distance : s.best.distance;
    Vec3d n = Vec3d::Zero();
    for (int c = 0; c < 3; ++c)
        n += s.best.barycentric[c] * d.vertex_normal(tri[static_cast<std::size_t>(c)]);
    s.best.normal = n.norm() > 0 ? Vec3d(n.normalized()) : d.face_normal(s.best.triangle);
}

}  // namespace

ClosestPointIndex::ClosestPointIndex(const Mesh& mesh) : ClosestPointIndex(mesh, false, nullptr) {}

ClosestPointIndex::ClosestPointIndex(const Mesh& mesh, std::shared_ptr<const SurfaceIndex> index)
    : ClosestPointIndex(mesh, true, std::move(index)) {}

ClosestPointIndex ClosestPointIndex::borrowing(const Mesh& mesh) {
    return ClosestPointIndex(mesh, true, nullptr);
}

ClosestPointIndex::ClosestPointIndex(const Mesh& mesh_in, bool borrow,
                                     std::shared_ptr<const SurfaceIndex> index)
    : impl_(std::make_unique<Impl>()) {
    if (mesh_in.triangles.empty())
        throw InputError("closest-point index: the mesh has no triangles");
    // note: unless borrowing, the index keeps its own copy of the geometry, so it cannot
    // dangle when the caller's mesh goes away (a temporary, a moved-from vector).
    const bool copy = !borrow || !mesh_in.has_normals();
    const Mesh* mesh = &mesh_in;
    if (copy) {
        Mesh& own = impl_->own_mesh;
        own.positions = mesh_in.positions;
        own.triangles = mesh_in.triangles;
        own.normals = mesh_in.normals;
        if (!own.has_normals()) compute_vertex_normals(own);
        mesh = &own;
    }
    auto& d = impl_->data;
    d.mesh = mesh;
    impl_->diagonal = bounds(*mesh).diagonal();
    d.around = vertex_triangles(*mesh);
    // The BVH: the one given (shared with the run's other users of this surface), else one of
    // its own.
    if (index) {
        GLINT_ASSERT(index->triangles().size() == mesh->triangle_count() &&
                         index->positions().size() == mesh->vertex_count(),
                     "closest-point index: the surface index is of another mesh");
        impl_->index = std::move(index);
    } else {
        impl_->index = index_surface(*mesh);
    }
    impl_->scene = static_cast<RTCScene>(impl_->index->embree_scene());
}

ClosestPointIndex::~ClosestPointIndex() = default;
ClosestPointIndex::ClosestPointIndex(ClosestPointIndex&&) noexcept = default;
ClosestPointIndex& ClosestPointIndex::operator=(ClosestPointIndex&&) noexcept = default;

const Mesh& ClosestPointIndex::mesh() const { return *impl_->data.mesh; }

ClosestPoint ClosestPointIndex::closest(const Vec3d& q, double max_distance) const {
    // note: a query without a bound first looks within 2 % of the mesh's size, and looks
    // again without one only when it found nothing there: the BVH walk culls far nodes from
    // the start instead of after its first hits. Between triangles as close as rounding can
    // tell (a closest point on a shared vertex), which one is reported depends on the walk.
    const double hint = std::isfinite(max_distance) ? max_distance : 0.02 * impl_->diagonal;
    ClosestPoint c = query(q, hint);
    if (!c.found && hint < max_distance) c = query(q, max_distance);
    return c;
}

ClosestPoint ClosestPointIndex::query(const Vec3d& q, double max_distance) const {
    QueryState state{&impl_->data, q, {}, 0};
    RTCPointQuery query;
    query.x = static_cast<float>(q.x());
    query.y = static_cast<float>(q.y());
    query.z = static_cast<float>(q.z());
    query.time = 0.0f;
    query.radius = std::isfinite(max_distance) ? float_above(max_distance)
                                               : std::numeric_limits<float>::infinity();
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(impl_->scene, &query, &context, point_query_callback, &state);
    finish_query(impl_->data, state);
    return state.best;
}

std::vector<ClosestPoint> ClosestPointIndex::closest(std::span<const Vec3d> queries,
                                                     double max_distance) const {
    std::vector<ClosestPoint> out(queries.size());
    // note: contiguous chunks of 512 keep neighbouring queries (samples and vertices are
    // stored near their neighbours) on one thread, so the BVH nodes they visit stay in cache.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i)
                              out[i] = closest(queries[i], max_distance);
                      });
    return out;
}

RayHit ClosestPointIndex::intersect(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    const Vec3d dir = ray.direction.normalized();
    rh.ray.org_x = static_cast<float>(ray.origin.x());
    rh.ray.org_y = static_cast<float>(ray.origin.y());
    rh.ray.org_z = static_cast<float>(ray.origin.z());
    rh.ray.dir_x = static_cast<float>(dir.x());
    rh.ray.dir_y = static_cast<float>(dir.y());
    rh.ray.dir_z = static_cast<float>(dir.z());
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    RayHit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = rh.ray.tfar;
    hit.triangle = rh.hit.primID;
    hit.barycentric = {1.0 - rh.hit.u - rh.hit.v, rh.hit.u, rh.hit.v};
    const auto& tri = impl_->data.mesh->triangles[hit.triangle];
    hit.point = Vec3d::Zero();
    Vec3d n = Vec3d::Zero();
    for (int k = 0; k < 3; ++k) {
        hit.point += hit.barycentric[k] *
                     impl_->data.mesh->positions[tri[static_cast<std::size_t>(k)]].cast<double>();
        n += hit.barycentric[k] * impl_->data.vertex_normal(tri[static_cast<std::size_t>(k)]);
    }
    hit.normal = n.normalized();
    return hit;
}

RayHit pick(const ClosestPointIndex& index, const Camera& camera, double u, double v) {
    // Embree aborts on non-finite or huge ray coordinates: only pixels of the image are picked.
    if (!(u >= 0.0 && u <= camera.width && v >= 0.0 && v <= camera.height)) {
        std::ostringstream s;
        s << "pixel (" << u << ", " << v << "): expected u in 0.." << camera.width
          << " and v in 0.." << camera.height << " (a pixel of the " << camera.width << " x "
          << camera.height << " view)";
        throw InputError(s.str());
    }
    return index.intersect(camera.pixel_ray(u, v));
}

std::vector<double> signed_distances(const ClosestPointIndex& index,
                                     std::span<const Vec3d> points) {
    const auto cps = index.closest(points);
    std::vector<double> out(cps.size());
    for (std::size_t i = 0; i < cps.size(); ++i) out[i] = cps[i].signed_distance;
    return out;
}

}  // namespace glint
