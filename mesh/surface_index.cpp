#include "mesh/surface_index.h"

#include "mesh/error.h"
#include "mesh/memory_limits.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <string>
#include <vector>

namespace glint {

namespace {

std::atomic<std::size_t> g_builds{0};

// One Embree device for every index of the process (a device holds the thread pool and the
// allocators; scenes of one device may be queried from any thread).
struct Device {
    RTCDevice device = nullptr;
    std::mutex mutex;   // guards `error` while a scene is built
    std::string error;  // the last message of the error callback
    Device() {
        device = rtcNewDevice(nullptr);
        if (device == nullptr)
            throw DeviceError(embree_device_failure(static_cast<int>(rtcGetDeviceError(nullptr))));
        rtcSetDeviceErrorFunction(
            device,
            [](void* user, RTCError code, const char* message) {
                auto* d = static_cast<Device*>(user);
                d->error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                           (message ? message : "");
            },
            this);
    }
    ~Device() { rtcReleaseDevice(device); }
};

Device& device() {
    static Device d;
    return d;
}

}  // namespace

struct SurfaceIndex::Impl {
    std::vector<Vec3f> positions;  // with one spare element: Embree reads 16 bytes per vertex
    std::vector<Triangle> triangles;
    RTCScene scene = nullptr;
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
    }
};

SurfaceIndex::SurfaceIndex(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
    if (mesh.triangles.empty()) throw InputError("surface index: the mesh has no triangles");
    impl_->positions.reserve(mesh.positions.size() + 1);
    impl_->positions = mesh.positions;
    impl_->triangles = mesh.triangles;
    GLINT_ASSERT(impl_->positions.capacity() > impl_->positions.size(),
                 "no spare position for Embree's 16-byte reads");
    Device& d = device();
    std::lock_guard<std::mutex> lock(d.mutex);
    d.error.clear();
    RTCScene scene = rtcNewScene(d.device);
    impl_->scene = scene;
    const bool compact = mesh.triangle_count() > kCompactIndexTriangles;
    rtcSetSceneFlags(scene, compact ? RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT)
                                    : RTC_SCENE_FLAG_ROBUST);
    // note: medium (Embree's default), not high: on 2M triangles the high-quality build
    // (spatial splits) took 1.2 s more per index and saved a quarter of the query time.
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               impl_->positions.data(), 0, 3 * sizeof(float),
                               impl_->positions.size());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               impl_->triangles.data(), 0, 3 * sizeof(std::uint32_t),
                               impl_->triangles.size());
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    if (!d.error.empty()) throw DeviceError("surface index: " + d.error);
    ++g_builds;
}

SurfaceIndex::~SurfaceIndex() = default;

std::span<const Vec3f> SurfaceIndex::positions() const { return impl_->positions; }
std::span<const Triangle> SurfaceIndex::triangles() const { return impl_->triangles; }

bool SurfaceIndex::indexes(const Mesh& mesh) const {
    return mesh.positions.size() == impl_->positions.size() &&
           mesh.triangles.size() == impl_->triangles.size() &&
           std::equal(mesh.positions.begin(), mesh.positions.end(), impl_->positions.begin()) &&
           std::equal(mesh.triangles.begin(), mesh.triangles.end(), impl_->triangles.begin());
}

void* SurfaceIndex::embree_scene() const { return impl_->scene; }

std::size_t SurfaceIndex::builds() { return g_builds.load(); }

std::shared_ptr<const SurfaceIndex> index_surface(const Mesh& mesh) {
    return std::make_shared<const SurfaceIndex>(mesh);
}

}  // namespace glint
