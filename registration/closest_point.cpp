#include "registration/closest_point.h"

#include "mesh/error.h"
#include "mesh/normals.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <unordered_map>

namespace glint {

// Per-mesh data the queries read: normals for the sign and the interpolated normal.
struct ClosestPointIndexData {
    const Mesh* mesh = nullptr;
    std::vector<Vec3d> vertex_normals;               // angle-weighted: pseudo-normals at vertices
    std::vector<Vec3d> face_normals;
    std::vector<std::array<Vec3d, 3>> edge_normals;  // per triangle, edge k = corner k → k+1
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
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<float> vertices;  // x y z per vertex + 1 float of padding at the end (Embree)
    ClosestPointIndexData data;
    Mesh own_mesh;  // positions, triangles and normals the BVH and queries read

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void embree_error(void* user, RTCError code, const char* message) {
    auto* text = static_cast<std::string*>(user);
    *text = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

bool point_query_callback(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<QueryState*>(args->userPtr);
    const ClosestPointIndexData& d = *state->data;
    const Mesh& m = *d.mesh;
    const auto& tri = m.triangles[args->primID];
    const TrianglePoint tp = closest_point_on_triangle(state->query, m.positions[tri[0]].cast<double>(),
                                                       m.positions[tri[1]].cast<double>(), m.positions[tri[2]].cast<double>());
    constexpr ClosestFeature kFeature[3] = {ClosestFeature::Face, ClosestFeature::Edge, ClosestFeature::Vertex};
    const double dist = (tp.point - state->query).norm();
    if (dist < state->best.distance) {
        state->best.found = true;
        state->best.distance = dist;
        state->best.point = tp.point;
        state->best.triangle = args->primID;
        state->best.barycentric = tp.barycentric;
        state->best.feature = kFeature[tp.feature];
        state->feature_index = tp.index;
        args->query->radius = static_cast<float>(dist);
        return true;
    }
    return false;
}

void finish_query(const ClosestPointIndexData& d, QueryState& s) {
    if (!s.best.found) return;
    const Mesh& m = *d.mesh;
    const auto& tri = m.triangles[s.best.triangle];
    Vec3d pseudo = Vec3d::Zero();
    switch (s.best.feature) {
        case ClosestFeature::Face: pseudo = d.face_normals[s.best.triangle]; break;
        case ClosestFeature::Edge: pseudo = d.edge_normals[s.best.triangle][static_cast<std::size_t>(s.feature_index)]; break;
        case ClosestFeature::Vertex: pseudo = d.vertex_normals[tri[static_cast<std::size_t>(s.feature_index)]]; break;
    }
    const double side = (s.query - s.best.point).dot(pseudo);
    s.best.signed_distance = side < 0 ? -s.best.distance : s.best.distance;
    Vec3d n = Vec3d::Zero();
    for (int k = 0; k < 3; ++k) n += s.best.barycentric[k] * d.vertex_normals[tri[static_cast<std::size_t>(k)]];
    s.best.normal = n.norm() > 0 ? Vec3d(n.normalized()) : d.face_normals[s.best.triangle];
}

}  // namespace

ClosestPointIndex::ClosestPointIndex(const Mesh& mesh_in) : impl_(std::make_unique<Impl>()) {
    if (mesh_in.triangles.empty()) throw InputError("closest-point index: the mesh has no triangles");
    // note: the index keeps its own copy of the geometry, so it cannot dangle when the
    // caller's mesh goes away (a temporary, a moved-from vector).
    impl_->own_mesh.positions = mesh_in.positions;
    impl_->own_mesh.triangles = mesh_in.triangles;
    impl_->own_mesh.normals = mesh_in.normals;
    if (!impl_->own_mesh.has_normals()) compute_vertex_normals(impl_->own_mesh);
    const Mesh* mesh = &impl_->own_mesh;
    auto& d = impl_->data;
    d.mesh = mesh;
    d.vertex_normals.resize(mesh->vertex_count());
    for (std::size_t v = 0; v < mesh->vertex_count(); ++v) d.vertex_normals[v] = mesh->normals[v].cast<double>();
    d.face_normals.resize(mesh->triangle_count());
    for (std::size_t t = 0; t < mesh->triangle_count(); ++t) d.face_normals[t] = face_normal(*mesh, t).cast<double>();
    // Edge pseudo-normals: the sum of the normals of the triangles sharing the edge.
    std::unordered_map<std::uint64_t, Vec3d> edge_sum;
    edge_sum.reserve(mesh->triangle_count() * 2);
    auto key = [](std::uint32_t a, std::uint32_t b) {
        return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    };
    for (std::size_t t = 0; t < mesh->triangle_count(); ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            auto [it, fresh] = edge_sum.try_emplace(key(mesh->triangles[t][k], mesh->triangles[t][(k + 1) % 3]), Vec3d::Zero());
            it->second += d.face_normals[t];
        }
    d.edge_normals.resize(mesh->triangle_count());
    for (std::size_t t = 0; t < mesh->triangle_count(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
            d.edge_normals[t][k] = edge_sum[key(mesh->triangles[t][k], mesh->triangles[t][(k + 1) % 3])];

    std::string error;
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device) throw DeviceError("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(impl_->device, embree_error, &error);
    impl_->scene = rtcNewScene(impl_->device);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    impl_->vertices.resize(mesh->vertex_count() * 3 + 1);  // note: Embree reads 16 bytes per vertex
    for (std::size_t v = 0; v < mesh->vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) impl_->vertices[3 * v + static_cast<std::size_t>(k)] = mesh->positions[v][k];
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, impl_->vertices.data(), 0,
                               3 * sizeof(float), mesh->vertex_count());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh->triangles.data(), 0,
                               3 * sizeof(std::uint32_t), mesh->triangle_count());
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(impl_->scene);
    if (!error.empty()) throw DeviceError("closest-point index: " + error);
    rtcSetDeviceErrorFunction(impl_->device, nullptr, nullptr);
}

ClosestPointIndex::~ClosestPointIndex() = default;
ClosestPointIndex::ClosestPointIndex(ClosestPointIndex&&) noexcept = default;
ClosestPointIndex& ClosestPointIndex::operator=(ClosestPointIndex&&) noexcept = default;

const Mesh& ClosestPointIndex::mesh() const { return *impl_->data.mesh; }

ClosestPoint ClosestPointIndex::closest(const Vec3d& q, double max_distance) const {
    QueryState state{&impl_->data, q, {}, 0};
    RTCPointQuery query;
    query.x = static_cast<float>(q.x());
    query.y = static_cast<float>(q.y());
    query.z = static_cast<float>(q.z());
    query.time = 0.0f;
    query.radius = std::isfinite(max_distance) ? static_cast<float>(max_distance) : std::numeric_limits<float>::infinity();
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(impl_->scene, &query, &context, point_query_callback, &state);
    finish_query(impl_->data, state);
    return state.best;
}

std::vector<ClosestPoint> ClosestPointIndex::closest(std::span<const Vec3d> queries, double max_distance) const {
    std::vector<ClosestPoint> out(queries.size());
    const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(),
                                                   static_cast<unsigned>(queries.size() / 2048 + 1)));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (std::size_t i = t; i < queries.size(); i += threads) out[i] = closest(queries[i], max_distance);
        });
    for (auto& th : pool) th.join();
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
        hit.point += hit.barycentric[k] * impl_->data.mesh->positions[tri[static_cast<std::size_t>(k)]].cast<double>();
        n += hit.barycentric[k] * impl_->data.vertex_normals[tri[static_cast<std::size_t>(k)]];
    }
    hit.normal = n.normalized();
    return hit;
}

RayHit pick(const ClosestPointIndex& index, const Camera& camera, double u, double v) {
    return index.intersect(camera.pixel_ray(u, v));
}

std::vector<double> signed_distances(const ClosestPointIndex& index, std::span<const Vec3d> points) {
    const auto cps = index.closest(points);
    std::vector<double> out(cps.size());
    for (std::size_t i = 0; i < cps.size(); ++i) out[i] = cps[i].signed_distance;
    return out;
}

}  // namespace glint
