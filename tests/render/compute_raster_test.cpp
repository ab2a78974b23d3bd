// The compute rasteriser (render/context.h Raster::Compute) against the graphics pipeline on
// the same device (lavapipe here, or the device GLINT_DEVICE names): the frames of one mesh and
// view, with the validation layer's synchronisation checks on. What may differ, and why:
// - coverage and the primitive where a sub-sample centre lies on an edge or within rounding of
//   one: both snap to 1/256 pixel and apply the top-left rule, but the pipeline's clip-space
//   arithmetic is not ours to the last bit. At most kEdgeShare of the covered pixels.
// - normals and depth where both kept the same triangle: the compute passes interpolate with
//   the exact corners (weights in double); a driver interpolates in its own precision, maybe
//   from its snapped corners, which moves a weight by up to 1/512 pixel over the triangle's
//   width. Inside a triangle (3×3 pixels of one primitive in both frames, as
//   tests/render/backend_agreement_test.cpp) within kInteriorAngleDeg and kInteriorDepthRel of
//   the depth range (a dense mesh has no such pixels). On slivers seen edge-on at the
//   silhouette a pixel's weights are ill-conditioned and the two can differ by a degree: over
//   all pixels, the 99th percentile within kQ99AngleDeg and kAgreementShare within
//   kAgreementAngleDeg (as the pipeline and Embree must agree). All far below what a sweep
//   resolves (its deviations are degrees, its depths hundredths of the size).
// Measured (2026-11-25), per case the largest: coverage or primitive differing; interior angle
// and depth; all pixels' 99th percentile angle, largest angle and depth:
//   lavapipe            2 pixels of 16k-97k; 1.6e-4°, 3.8e-7; 1.3e-4°, 4.7e-3°, 5.1e-6;
//   NVIDIA H100 (580)   0 pixels;            1.1e-2°, 4.5e-5; 2.5e-2°, 0.77°,   6.7e-4
// (NVIDIA's pipeline interpolates less precisely: its median difference is 1e-3°, lavapipe's
// 1e-5°; Embree agrees with the compute passes to 1e-4° inside triangles on both devices).
#include "render/context.h"
#include "render/renderer.h"
#include "render/view.h"
#include "tests/render/render_test_util.h"
#include "tests/render/test_meshes.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

namespace glint::test {
namespace {

constexpr double kEdgeShare = 0.002;
constexpr double kInteriorAngleDeg = 0.05;
constexpr double kInteriorDepthRel = 2e-4;
constexpr double kQ99AngleDeg = 0.05;
constexpr double kAgreementAngleDeg = 0.5;
constexpr double kAgreementShare = 0.999;

std::shared_ptr<RenderContext> context(Raster raster) {
    ContextOptions o{.backend = Backend::Vulkan, .validation = true, .raster = raster};
    if (std::getenv("GLINT_DEVICE") == nullptr) o.device = "llvmpipe";
    return shared_render_context(o);  // the passes compiled once per process
}

struct Difference {
    std::size_t covered = 0;    // covered in the pipeline's frame
    std::size_t coverage = 0;   // pixels whose coverage differs
    std::size_t primitive = 0;  // covered in both, another primitive
    std::size_t same = 0;       // covered in both with the same primitive
    std::size_t within = 0;     // of `same`, normals within kAgreementAngleDeg
    std::size_t interior = 0;   // of `same`, 3×3 pixels of one primitive in both frames
    double angle_deg = 0.0;     // largest, over `same`
    double depth_rel = 0.0;     // largest |Δ depth| / depth range, over `same`
    double interior_angle_deg = 0.0;
    double interior_depth_rel = 0.0;
    std::vector<double> angles;  // over `same`

    void add(const Difference& d) {
        angles.insert(angles.end(), d.angles.begin(), d.angles.end());
        covered += d.covered;
        coverage += d.coverage;
        primitive += d.primitive;
        same += d.same;
        within += d.within;
        interior += d.interior;
        angle_deg = std::max(angle_deg, d.angle_deg);
        depth_rel = std::max(depth_rel, d.depth_rel);
        interior_angle_deg = std::max(interior_angle_deg, d.interior_angle_deg);
        interior_depth_rel = std::max(interior_depth_rel, d.interior_depth_rel);
    }
};

/// Whether the 3×3 pixels around (x, y) show one primitive in both frames.
bool interior(const Frame& a, const Frame& b, int x, int y) {
    if (x == 0 || y == 0 || x == a.width - 1 || y == a.height - 1) return false;
    const auto at = [&](int u, int v) { return static_cast<std::size_t>(v * a.width + u); };
    const std::uint32_t id = a.primitive_id[at(x, y)];
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const std::size_t q = at(x + dx, y + dy);
            if (a.primitive_id[q] != id || b.primitive_id[q] != id) return false;
        }
    }
    return true;
}

Difference compare(const Frame& graphics, const Frame& compute, double depth_range) {
    Difference d;
    for (int y = 0; y < graphics.height; ++y) {
        for (int x = 0; x < graphics.width; ++x) {
            const auto p = static_cast<std::size_t>(y * graphics.width + x);
            const bool a = graphics.is_covered(p);
            const bool b = compute.is_covered(p);
            d.covered += a ? 1 : 0;
            if (graphics.coverage[p] != compute.coverage[p]) ++d.coverage;
            if (!(a && b)) continue;
            if (graphics.primitive_id[p] != compute.primitive_id[p]) {
                ++d.primitive;
                continue;
            }
            ++d.same;
            const double angle = angle_deg(pixel_normal(graphics, p).cast<double>(),
                                           pixel_normal(compute, p).cast<double>());
            const double depth =
                static_cast<double>(std::abs(graphics.depth[p] - compute.depth[p])) / depth_range;
            if (angle <= kAgreementAngleDeg) ++d.within;
            d.angles.push_back(angle);
            d.angle_deg = std::max(d.angle_deg, angle);
            d.depth_rel = std::max(d.depth_rel, depth);
            if (!interior(graphics, compute, x, y)) continue;
            ++d.interior;
            d.interior_angle_deg = std::max(d.interior_angle_deg, angle);
            d.interior_depth_rel = std::max(d.interior_depth_rel, depth);
        }
    }
    return d;
}

/// Renders `views` of `mesh` with both rasterisers and expects the frames to agree.
void expect_same_frames(const Mesh& mesh, const std::vector<View>& views, const FrameOptions& frame,
                        const char* what) {
    Renderer graphics(context(Raster::Graphics), mesh, frame);
    Renderer compute(context(Raster::Compute), mesh, frame);
    ASSERT_EQ(graphics.info().raster, Raster::Graphics);
    ASSERT_EQ(compute.info().raster, Raster::Compute);
    Difference total;
    for (const View& view : views) {
        const Frame g = graphics.render(view);
        const Frame c = compute.render(view);
        total.add(compare(g, c, view.camera.far_plane - view.camera.near_plane));
    }
    const double share = static_cast<double>(total.within) / static_cast<double>(total.same);
    const double q99 = quantile(total.angles, 0.99);
    std::printf(
        "[compute raster %s] covered %zu, coverage differs %zu, primitive differs %zu; "
        "same %zu: within %.1f° %.5f, angle q50 %.2e° q90 %.2e° q99 %.2e° q999 %.2e° "
        "max %.2e°, depth %.2e of the range; interior %zu: max angle %.2e°, depth %.2e\n",
        what, total.covered, total.coverage, total.primitive, total.same, kAgreementAngleDeg, share,
        quantile(total.angles, 0.5), quantile(total.angles, 0.9), q99,
        quantile(total.angles, 0.999), total.angle_deg, total.depth_rel, total.interior,
        total.interior_angle_deg, total.interior_depth_rel);
    EXPECT_GT(total.covered, 1000u) << what;
    EXPECT_LE(static_cast<double>(total.coverage + total.primitive),
              kEdgeShare * static_cast<double>(total.covered))
        << what;
    EXPECT_GE(share, kAgreementShare) << what;
    EXPECT_LE(q99, kQ99AngleDeg) << what;
    EXPECT_LE(total.interior_angle_deg, kInteriorAngleDeg) << what;
    EXPECT_LE(total.interior_depth_rel, kInteriorDepthRel) << what;
    expect_no_validation_messages(graphics);
    expect_no_validation_messages(compute);
}

std::vector<View> ring(const Mesh& mesh, Projection projection, int size) {
    std::vector<View> views;
    int index = 0;
    for (double el : {-50.0, 0.0, 35.0, 89.0}) {
        for (double az = 0.0; az < 360.0; az += 120.0) {
            views.push_back(make_view(mesh, ViewSpec{.azimuth_deg = az + el,
                                                     .elevation_deg = el,
                                                     .width = size,
                                                     .height = size,
                                                     .projection = projection,
                                                     .index = index++}));
        }
    }
    return views;
}

TEST(ComputeRaster, GivesThePipelinesFramesOfADenseClosedMesh) {
    // ~5k triangles at 160²: a few pixels per triangle, the small pass's case.
    const Mesh mesh = make_bumpy_sphere(4);
    expect_same_frames(mesh, ring(mesh, Projection::Orthographic, 160), {}, "bumpy ortho s=1");
    expect_same_frames(mesh, ring(mesh, Projection::Perspective, 96),
                       {.supersample = 2, .cull_back_faces = true}, "bumpy persp s=2 culled");
}

TEST(ComputeRaster, GivesThePipelinesFramesOfLargeTrianglesAndAnOpenSurfaceFromBothSides) {
    // 80 triangles at 192²: hundreds of pixels each, the large pass's case.
    const Mesh sphere = make_icosphere(1);
    expect_same_frames(sphere, ring(sphere, Projection::Orthographic, 192), {}, "icosphere");
    // Back faces seen through nothing: both sides of an open surface, no culling.
    const Mesh plane = make_corrugated_plane(8, 1.0, 0.1, 1.0);
    std::vector<View> views;
    for (double el : {70.0, 20.0, -60.0}) {
        views.push_back(make_view(
            plane, ViewSpec{.azimuth_deg = 30, .elevation_deg = el, .width = 160, .height = 128}));
    }
    expect_same_frames(plane, views, {}, "corrugated");
}

TEST(ComputeRaster, ClipsAtTheNearPlaneAndTheGuardBandAsThePipelineDoes) {
    const Mesh plane = make_corrugated_plane(6, 1.0, 0.1, 1.0);
    std::vector<View> views;
    // A perspective camera close over a grazing surface, its near plane through the mesh: the
    // triangles it cuts are clipped (z ≥ 0), some corners lie behind the eye (w < 0), and those
    // near the eye reach far beyond the guard band.
    View near = make_view(plane, ViewSpec{.azimuth_deg = 10,
                                          .elevation_deg = 12,
                                          .width = 128,
                                          .height = 96,
                                          .projection = Projection::Perspective,
                                          .fov_y_rad = 1.0});
    const Vec3d eye(0.05, -0.1, 0.12);
    const Vec3d target(0.3, 0.6, 0.0);
    const Vec3d forward = (target - eye).normalized();
    const Vec3d right = forward.cross(Vec3d::UnitZ()).normalized();
    const Vec3d up = right.cross(forward);
    near.camera.world_from_camera.linear().col(0) = right;
    near.camera.world_from_camera.linear().col(1) = up;
    near.camera.world_from_camera.linear().col(2) = -forward;
    near.camera.world_from_camera.translation() = eye;
    near.camera.near_plane = 0.15;
    near.camera.far_plane = 3.0;
    views.push_back(near);
    // The far plane through the mesh too.
    View far = near;
    far.camera.near_plane = 0.01;
    far.camera.far_plane = 0.8;
    views.push_back(far);
    // Orthographic, zoomed onto a few triangles that reach far outside the image.
    View zoomed = make_view(
        plane, ViewSpec{.azimuth_deg = 0, .elevation_deg = 60, .width = 64, .height = 64});
    zoomed.camera.ortho_half_height *= 0.004;
    views.push_back(zoomed);
    expect_same_frames(plane, views, {}, "clipped");
}

}  // namespace
}  // namespace glint::test
