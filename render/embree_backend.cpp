// Embree backend: the same Frame as the Vulkan backend by ray casting on the CPU.
//
// One primary ray per sub-sample, cast in coherent 4×4 packets (rtcIntersect16), sub-sample
// (X, Y) of the (w·s) × (h·s) grid at pixel coordinates u = (X + 0.5)/s, v = (Y + 0.5)/s,
// exactly where the rasteriser samples the s× target. Ray directions are scaled so that the
// component along the viewing axis is 1: the hit distance t *is* the linear depth, and the
// near/far planes are t ranges [near, far], as the rasteriser clips them.
// Normal at a hit: Embree's barycentrics (u, v) weight the vertex normals,
//   n = normalize((1 − u − v)·n0 + u·n1 + v·n2),
// which is what the rasteriser's perspective-correct interpolation computes per fragment.
// Scene flag ROBUST: watertight traversal, so rays through shared edges do not leak.
#include "mesh/error.h"
#include "mesh/memory_limits.h"
#include "render/detail/backend.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <span>
#include <string>

namespace glint::detail {
namespace {

struct ErrorLog {
    std::mutex mutex;
    std::string last;
};

void embree_error(void* user, RTCError code, const char* message) {
    auto* log = static_cast<ErrorLog*>(user);
    std::lock_guard<std::mutex> lock(log->mutex);
    log->last = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                (message != nullptr ? message : "?");
}

/// Intersection filter for back-face culling: rejects hits on triangles whose geometric
/// normal (counter-clockwise, outward) points away from the ray origin side.
void cull_back_faces(const RTCFilterFunctionNArguments* args) {
    const auto* face_normals = static_cast<const Vec3f*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const Vec3f& n = face_normals[prim];
        const float d = n.x() * RTCRayN_dir_x(args->ray, args->N, i) +
                        n.y() * RTCRayN_dir_y(args->ray, args->N, i) +
                        n.z() * RTCRayN_dir_z(args->ray, args->N, i);
        if (d >= 0.0f) args->valid[i] = 0;
    }
}

/// The Embree device of a context; scenes (one per mesh) are built on it.
class EmbreeDevice {
  public:
    explicit EmbreeDevice(int threads) {
        const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
        device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
        if (device_ == nullptr) {
            throw DeviceError(embree_device_failure(static_cast<int>(rtcGetDeviceError(nullptr))));
        }
        ++creation_counters().embree_devices;
        rtcSetDeviceErrorFunction(device_, embree_error, &errors_);
    }
    ~EmbreeDevice() { rtcReleaseDevice(device_); }
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    [[nodiscard]] RTCDevice get() const { return device_; }

    void check(const char* what) {
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) {
            std::lock_guard<std::mutex> lock(errors_.mutex);
            throw DeviceError(std::string("Embree: ") + what + " failed: " + errors_.last);
        }
    }

  private:
    ErrorLog errors_;
    RTCDevice device_ = nullptr;
};

class EmbreeBackend final : public RenderBackend {
  public:
    EmbreeBackend(std::shared_ptr<EmbreeDevice> device, const Mesh& mesh,
                  const FrameOptions& options, int threads)
        : options_(options), threads_(threads), device_(std::move(device)) {
        if (options.share_mesh) {
            normals_ = mesh.normals;
            triangles_ = mesh.triangles;
        } else {
            own_normals_ = mesh.normals;
            own_triangles_ = mesh.triangles;
            normals_ = own_normals_;
            triangles_ = own_triangles_;
        }
        try {
            build(mesh);
        } catch (...) {
            release();
            throw;
        }
    }

    ~EmbreeBackend() override { release(); }

    // note: the rays are cast in finish(), so one view is in flight at a time; submit only
    // remembers the view.
    [[nodiscard]] std::size_t max_in_flight() const override { return 1; }
    void submit(const View& view) override { pending_ = view; }
    Frame& finish() override {
        GLINT_ASSERT(pending_.has_value(), "finish without a submitted view");
        const View view = *std::move(pending_);
        pending_.reset();
        render_one(view);
        return frame_;
    }
    void abandon() noexcept override { pending_.reset(); }
    [[nodiscard]] bool works_in_finish() const override { return true; }

  private:
    void release() noexcept {
        if (scene_ != nullptr && !index_) rtcReleaseScene(scene_);
        scene_ = nullptr;
        index_.reset();
    }

    void check(const char* what) { device_->check(what); }

    void build(const Mesh& mesh) {
        if (options_.surface_index && !options_.cull_back_faces) {
            // The run's BVH of this surface (mesh/surface_index.h): same flags and build quality
            // as below, so the frames are the same.
            GLINT_ASSERT(options_.surface_index->triangles().size() == mesh.triangle_count() &&
                             options_.surface_index->positions().size() == mesh.vertex_count(),
                         "renderer: the surface index is of another mesh");
            index_ = options_.surface_index;
            scene_ = static_cast<RTCScene>(index_->embree_scene());
            return;
        }
        RTCDevice device = device_->get();
        scene_ = rtcNewScene(device);
        ++creation_counters().embree_scenes;
        // note: above 500k triangles the compact BVH: on 2M triangles it took 60 MB less (113
        // instead of 173 MB per mesh) for 6 % more time per ray; the frames are the same.
        const bool compact = mesh.triangle_count() > kCompactIndexTriangles;
        rtcSetSceneFlags(scene_, compact
                                     ? RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT)
                                     : RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // note: Embree reads the triangles in place and a copy of the positions: it reads
        // vertices with 16-byte loads, so the copy has one spare element of capacity after
        // the last vertex.
        positions_.reserve(mesh.positions.size() + 1);
        positions_ = mesh.positions;
        GLINT_ASSERT(positions_.capacity() > positions_.size(),
                     "no spare position for Embree's 16-byte reads");
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   positions_.data(), 0, 3 * sizeof(float), positions_.size());
        // (Embree only reads a shared index buffer; its API takes it as void*.)
        rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   const_cast<Triangle*>(triangles_.data()), 0,
                                   3 * sizeof(std::uint32_t), triangles_.size());
        if (options_.cull_back_faces) {
            face_normals_.resize(mesh.triangles.size());
            for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
                face_normals_[t] = face_normal(mesh, t);
            rtcSetGeometryUserData(geom, face_normals_.data());
            rtcSetGeometryIntersectFilterFunction(geom, cull_back_faces);
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_);
        check("building the scene");
    }

    // The rays of a view. Sub-sample (X, Y) sits at NDC x = 2(X + ½)/sw − 1, y = 1 − 2(Y + ½)/sh,
    // so ray origins (orthographic) or directions (perspective) are affine in X and Y:
    //   v(X, Y) = v00 + X·dx + Y·dy.
    struct Rays {
        int sw = 0;  // sub-samples across
        bool ortho = true;
        Eigen::Vector3f v00, fixed, dx, dy;
        float tnear = 0.0f, tfar = 0.0f;
    };

    [[nodiscard]] Rays rays_of(const Camera& cam) const {
        const int s = options_.supersample;
        const int sw = cam.width * s;
        const int sh = cam.height * s;
        const Eigen::Matrix3d basis = cam.world_from_camera.linear();
        const Vec3d right = basis.col(0);
        const Vec3d up = basis.col(1);
        const Vec3d forward = -basis.col(2);
        const bool ortho = cam.projection == Projection::Orthographic;
        const double aspect = static_cast<double>(cam.width) / cam.height;
        // Half extents of the image plane: at the eye (orthographic) or at depth 1 (perspective).
        const double half_h = ortho ? cam.ortho_half_height : std::tan(0.5 * cam.fov_y_rad);
        const double half_w = half_h * aspect;
        const Vec3d dx = right * (2.0 * half_w / sw);
        const Vec3d dy = -up * (2.0 * half_h / sh);
        const Vec3d corner =
            right * (-half_w + 0.5 * 2.0 * half_w / sw) + up * (half_h - 0.5 * 2.0 * half_h / sh);
        // Ortho: origin varies, direction = forward. Perspective: origin = eye, direction
        // = forward + offset (component 1 along the viewing axis, so t is the depth).
        Rays r;
        r.sw = sw;
        r.ortho = ortho;
        r.v00 = (ortho ? Vec3d(cam.eye() + corner) : Vec3d(forward + corner)).cast<float>();
        r.fixed = (ortho ? forward : cam.eye()).cast<float>();
        r.dx = dx.cast<float>();
        r.dy = dy.cast<float>();
        r.tnear = static_cast<float>(cam.near_plane);
        r.tfar = static_cast<float>(cam.far_plane);
        return r;
    }

    struct Scratch final : RowScratch {
        std::vector<float> normal_depth;
        std::vector<std::uint32_t> ids;
    };

    // Output rows [y0, y1) into `dst`, whose row 0 is output row `row0`.
    void trace_into(const Rays& rays, int y0, int y1, Scratch& scratch, Frame& dst,
                    int row0) const {
        const int s = options_.supersample;
        if (s == 1) {
            // One sample per pixel: hits go straight into the frame.
            trace_band<true>(rays, y0, y1, scratch, dst, row0);
            return;
        }
        const std::size_t samples =
            static_cast<std::size_t>((y1 - y0) * s) * static_cast<std::size_t>(rays.sw);
        if (scratch.ids.size() < samples) {
            scratch.normal_depth.resize(4 * samples);
            scratch.ids.resize(samples);
        }
        trace_band<false>(rays, y0 * s, y1 * s, scratch, dst, row0);
        resolve_rows(scratch.normal_depth.data(), scratch.ids.data(), s, y0 - row0, y1 - row0, dst);
    }

    // Frame::barycentric: 2 per pixel when asked for at s = 1 (written by trace_band<true>),
    // else empty.
    void size_barycentrics(Frame& f) const {
        if (options_.barycentrics && options_.supersample == 1)
            f.barycentric.resize(2 * f.pixel_count());
        else f.barycentric.clear();
    }

    void render_one(const View& view) {
        const Camera& cam = view.camera;
        if (frame_.width != cam.width || frame_.height != cam.height ||
            frame_.coverage.size() != frame_.pixel_count()) {
            frame_ = make_empty_frame(cam.width, cam.height);
        }
        frame_.normal_space = NormalSpace::World;
        size_barycentrics(frame_);
        const Rays rays = rays_of(cam);
        // Work unit: a band of output rows whose sub-sample rows are a multiple of the 4-row
        // packet height; threads take bands from a shared counter (load balance: empty sky
        // is cheap, surface is not).
        const int rows = band_rows();
        const int bands = (cam.height + rows - 1) / rows;
        const std::size_t samples = static_cast<std::size_t>(rays.sw) *
                                    static_cast<std::size_t>(cam.height) *
                                    static_cast<std::size_t>(options_.supersample);
        // note: below ~16k sub-samples one thread is faster than starting another.
        const int threads = samples < 16384 ? 1 : std::min(threads_, bands);
        std::atomic<int> next_band{0};
        scratch_.resize(static_cast<std::size_t>(threads));
        parallel_for(threads, threads, [&](int t0, int t1) {
            for (int t = t0; t < t1; ++t) {
                Scratch& scratch = scratch_[static_cast<std::size_t>(t)];
                for (int band = next_band++; band < bands; band = next_band++) {
                    const int y0 = band * rows;
                    trace_into(rays, y0, std::min(cam.height, y0 + rows), scratch, frame_, 0);
                }
            }
        });
        check("intersecting rays");
    }

  public:
    [[nodiscard]] int band_rows() const override { return 4 / std::gcd(4, options_.supersample); }
    [[nodiscard]] std::unique_ptr<RowScratch> make_row_scratch() const override {
        return std::make_unique<Scratch>();
    }
    void trace_rows(const View& view, int y0, int y1, RowScratch& scratch,
                    Frame& rows) const override {
        const Camera& cam = view.camera;
        if (rows.width != cam.width || rows.height != y1 - y0 ||
            rows.coverage.size() != rows.pixel_count())
            rows = make_empty_frame(cam.width, y1 - y0);
        rows.normal_space = NormalSpace::World;
        size_barycentrics(rows);
        trace_into(rays_of(cam), y0, y1, static_cast<Scratch&>(scratch), rows, y0);
        device_->check("intersecting rays");
    }

  private:
    /// Loads the 4×4 packet whose top-left sub-sample is (tx, ty): origins, directions, the
    /// ray range, and which lanes lie inside the image and above row Y1.
    static void load_packet(const Rays& rays, int tx, int ty, int Y1, RTCRayHit16& packet,
                            int* valid) {
        const int sw = rays.sw;
        for (int k = 0; k < 16; ++k) {
            const int X = tx + (k & 3);
            const int Y = ty + (k >> 2);
            valid[k] = (X < sw && Y < Y1) ? -1 : 0;
            const Eigen::Vector3f v =
                rays.v00 + static_cast<float>(X) * rays.dx + static_cast<float>(Y) * rays.dy;
            const Eigen::Vector3f& org = rays.ortho ? v : rays.fixed;
            const Eigen::Vector3f& dir = rays.ortho ? rays.fixed : v;
            packet.ray.org_x[k] = org.x();
            packet.ray.org_y[k] = org.y();
            packet.ray.org_z[k] = org.z();
            packet.ray.dir_x[k] = dir.x();
            packet.ray.dir_y[k] = dir.y();
            packet.ray.dir_z[k] = dir.z();
            packet.ray.tnear[k] = rays.tnear;
            packet.ray.tfar[k] = rays.tfar;
            packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
        }
    }

    /// Writes lane k of a traced packet to sub-sample idx: into `dst` (kDirect) or scratch.
    template <bool kDirect>
    void store_lane(const RTCRayHit16& packet, int k, std::size_t idx, Scratch& scratch,
                    Frame& dst) const {
        if (packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
            if constexpr (kDirect) {
                dst.normal[3 * idx] = dst.normal[3 * idx + 1] = dst.normal[3 * idx + 2] = 0.0f;
                dst.primitive_id[idx] = kNoPrimitive;
                dst.depth[idx] = kNoDepth;
                dst.coverage[idx] = 0.0f;
                if (!dst.barycentric.empty())
                    dst.barycentric[2 * idx] = dst.barycentric[2 * idx + 1] =
                        std::numeric_limits<float>::quiet_NaN();
            } else {
                scratch.ids[idx] = kNoPrimitive;
            }
            return;
        }
        const unsigned prim = packet.hit.primID[k];
        const Triangle& tri = triangles_[prim];
        const float u = packet.hit.u[k];
        const float v = packet.hit.v[k];
        Eigen::Vector3f n =
            (1.0f - u - v) * normals_[tri[0]] + u * normals_[tri[1]] + v * normals_[tri[2]];
        const float len = n.norm();
        if (len > 0.0f) n /= len;
        if constexpr (kDirect) {
            float* out = &dst.normal[3 * idx];
            out[0] = n.x();
            out[1] = n.y();
            out[2] = n.z();
            dst.primitive_id[idx] = prim;
            dst.depth[idx] = packet.ray.tfar[k];
            dst.coverage[idx] = 1.0f;
            if (!dst.barycentric.empty()) {
                dst.barycentric[2 * idx] = u;
                dst.barycentric[2 * idx + 1] = v;
            }
        } else {
            float* nd = &scratch.normal_depth[4 * idx];
            nd[0] = n.x();
            nd[1] = n.y();
            nd[2] = n.z();
            nd[3] = packet.ray.tfar[k];
            scratch.ids[idx] = prim;
        }
    }

    /// Casts the sub-sample rows [Y0, Y1) (a multiple of 4 high except at the bottom) in 4×4
    /// packets into scratch (row Y0 first), or, with kDirect (s = 1), into `dst`, whose row 0
    /// is sub-sample row `row0`.
    template <bool kDirect>
    void trace_band(const Rays& rays, int Y0, int Y1, Scratch& scratch, Frame& dst,
                    int row0) const {
        const int sw = rays.sw;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) RTCRayHit16 packet;
        alignas(64) int valid[16];
        // Fields Embree does not write: set once per band.
        for (int k = 0; k < 16; ++k) {
            packet.ray.time[k] = 0.0f;
            packet.ray.mask[k] = 0xFFFFFFFFu;
            packet.ray.id[k] = static_cast<unsigned>(k);
            packet.ray.flags[k] = 0;
        }
        for (int ty = Y0; ty < Y1; ty += 4) {
            for (int tx = 0; tx < sw; tx += 4) {
                load_packet(rays, tx, ty, Y1, packet, valid);
                rtcIntersect16(valid, scene_, &context, &packet);
                for (int k = 0; k < 16; ++k) {
                    if (valid[k] == 0) continue;
                    const int X = tx + (k & 3);
                    const int Y = ty + (k >> 2);
                    const std::size_t idx = static_cast<std::size_t>(kDirect ? Y - row0 : Y - Y0) *
                                                static_cast<std::size_t>(sw) +
                                            static_cast<std::size_t>(X);
                    store_lane<kDirect>(packet, k, idx, scratch, dst);
                }
            }
        }
    }

    FrameOptions options_;
    int threads_ = 1;
    std::span<const Vec3f> normals_;       // the mesh's (share_mesh) or own_normals_
    std::span<const Triangle> triangles_;  // the mesh's (share_mesh) or own_triangles_
    std::vector<Vec3f> own_normals_;
    std::vector<Triangle> own_triangles_;
    std::vector<Vec3f> positions_;
    std::vector<Vec3f> face_normals_;
    std::shared_ptr<const SurfaceIndex> index_;  // the shared BVH, when the scene is its
    std::shared_ptr<EmbreeDevice> device_;
    RTCScene scene_ = nullptr;
    std::optional<View> pending_;
    std::vector<Scratch> scratch_;  // one per worker thread, reused across views
    Frame frame_;
};

class EmbreeContext final : public ContextImpl {
  public:
    explicit EmbreeContext(int threads)
        : threads_(worker_count(threads)), device_(std::make_shared<EmbreeDevice>(threads)) {}
    std::unique_ptr<RenderBackend> make_backend(const Mesh& mesh,
                                                const FrameOptions& options) override {
        return std::make_unique<EmbreeBackend>(device_, mesh, options, threads_);
    }
    [[nodiscard]] int threads() const { return threads_; }

  private:
    int threads_ = 1;
    std::shared_ptr<EmbreeDevice> device_;
};

}  // namespace

std::unique_ptr<ContextImpl> make_embree_context(const ContextOptions& options,
                                                 std::string& device_name,
                                                 std::string& device_type) {
    auto context = std::make_unique<EmbreeContext>(options.threads);
    device_name = std::string("embree ") + RTC_VERSION_STRING + " (CPU, " +
                  std::to_string(context->threads()) + " threads)";
    device_type = "cpu";
    return context;
}

}  // namespace glint::detail
