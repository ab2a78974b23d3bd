// Registration time and accuracy on the benchmarks' blob pair (bench/blob_pair.h: reference
// and examined of different tessellations, ~200k and ~2M triangles each, a 1 % dent, 5° and
// 2 % motion). Counters: rotation and translation error against the known motion.
// The fit kinds side by side (issue 53): 0 rigid as before (no scale measured), 1 rigid with the
// scale it leaves measured (the default: nine small solves at the end), 2 the similarity fit
// (--fit-scale).
#include "bench/blob_pair.h"
#include "registration/icp.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>

namespace glint {
namespace {

const bench::BlobPair& pair(int size_class) {
    static std::map<int, bench::BlobPair> cache;
    auto it = cache.find(size_class);
    if (it == cache.end()) it = cache.emplace(size_class, bench::make_blob_pair(size_class)).first;
    return it->second;
}

void BM_Register(benchmark::State& state) {
    const bench::BlobPair& p = pair(static_cast<int>(state.range(0)));
    RegistrationOptions o;
    o.measure_scale = state.range(1) >= 1;
    o.fit_scale = state.range(1) == 2;
    RegistrationResult r;
    for (auto _ : state) r = register_meshes(p.reference, p.examined, o);
    const Rigid d = p.truth.inverse() * r.reference_from_examined;
    state.counters["rot_err_deg"] = rotation_angle_deg(d);
    state.counters["transl_err_mm"] = d.translation().norm();
    state.counters["iterations"] = r.iterations;
    state.counters["scale_err"] = std::abs(r.examined_scale - 1.0);
    state.counters["ref_triangles"] = static_cast<double>(p.reference.triangle_count());
    state.counters["exa_triangles"] = static_cast<double>(p.examined.triangle_count());
}
BENCHMARK(BM_Register)
    ->ArgsProduct({{1, 2}, {0, 1, 2}})
    ->ArgNames({"size_class", "fit"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace glint
