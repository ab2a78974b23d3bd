// Surface extraction speed and memory (not a test): CThead (256 x 256 x 113 short voxels,
// ../shared/data) read + bone surface at iso 1250, largest component; and a synthetic 512³
// float volume (an ellipsoid, generated once) contoured whole. Counters: triangles and the
// process's peak resident memory so far (getrusage), MiB.
#include "volume/phantom.h"
#include "volume/surface.h"

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <filesystem>

namespace {

double peak_mib() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

void BM_CtheadBoneSurface(benchmark::State& state) {
    const std::filesystem::path path =
        std::filesystem::path(GLINT_SHARED_DATA_DIR) / "ct_head_cthead" / "CThead.mhd";
    if (!std::filesystem::exists(path)) {
        state.SkipWithError("../shared/data/ct_head_cthead/CThead.mhd is absent");
        return;
    }
    std::size_t triangles = 0;
    for (auto _ : state) {
        const glint::Volume v = glint::read_volume(path);
        triangles = glint::extract_surface(v, {.iso = 1250.0, .largest = true}).report.triangles;
    }
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["peak_MiB"] = peak_mib();
}
BENCHMARK(BM_CtheadBoneSurface)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Synthetic512Surface(benchmark::State& state) {
    static const glint::Volume volume = [] {
        glint::EllipsoidVolumeOptions o;
        o.grid.size = {512, 512, 512};
        o.grid.spacing = {0.4, 0.4, 0.4};  // the paper's CT voxels
        o.center = {102.2, 102.2, 102.2};
        o.radii = {90, 70, 60};
        return glint::make_ellipsoid_volume(o);
    }();
    std::size_t triangles = 0;
    for (auto _ : state)
        triangles = glint::extract_surface(volume, {.iso = 500.0}).report.triangles;
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["peak_MiB"] = peak_mib();
}
BENCHMARK(BM_Synthetic512Surface)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
