// The small pair the GPU sweep, GPU analysis and inspect() tests share: a reference condyle and
// a re-tessellated examined one with a 0.4 mm dent, swept on lavapipe (or GLINT_DEVICE's device)
// with a 6 × 2 plan of 96² views.
#pragma once

#include "mesh/damage.h"
#include "mesh/phantom.h"
#include "scanner/sweep.h"

#include <cstdlib>

namespace glint::test {

struct DentedPair {
    Mesh reference = make_phantom(
        {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Ico, .resolution = 4});
    Mesh examined = [] {
        Mesh m = make_phantom(
            {.kind = PhantomKind::Condyle, .scheme = TessellationScheme::Uv, .resolution = 40});
        apply_damage(
            m, {DamageSpec{
                   .kind = DamageKind::Dent, .center = {10, 0, 3}, .radius = 2.5, .depth = 0.4}});
        return m;
    }();
};

/// Built once per test binary.
inline const DentedPair& dented_pair() {
    static const DentedPair p;
    return p;
}

/// The plan and Vulkan settings of those tests: lavapipe unless GLINT_DEVICE names a device (a
/// GPU machine then checks its own arithmetic).
inline SweepOptions small_vulkan_sweep(Accumulation accumulate, Raster raster = Raster::Auto) {
    SweepOptions o;
    o.render.raster = raster;
    o.plan.azimuth_step_deg = 60;
    o.plan.elevations_deg = {-30, 30};
    o.plan.size = 96;
    o.render.backend = Backend::Vulkan;
    if (std::getenv("GLINT_DEVICE") == nullptr) o.render.device = "llvmpipe";
    o.render.supersample = 2;
    o.accumulate = accumulate;
    return o;
}

}  // namespace glint::test
