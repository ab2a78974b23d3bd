// Registration time and accuracy on the benchmarks' blob pair (bench/blob_pair.h: reference
// and examined of different tessellations, ~200k and ~2M triangles each, a 1 % dent, 5° and
// 2 % motion). Counters: rotation and translation error against the known motion.
#include "bench/blob_pair.h"
#include "registration/icp.h"

#include <benchmark/benchmark.h>

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
    RegistrationResult r;
    for (auto _ : state) r = register_meshes(p.reference, p.examined, {});
    const Rigid d = p.truth.inverse() * r.reference_from_examined;
    state.counters["rot_err_deg"] = rotation_angle_deg(d);
    state.counters["transl_err_mm"] = d.translation().norm();
    state.counters["iterations"] = r.iterations;
    state.counters["ref_triangles"] = static_cast<double>(p.reference.triangle_count());
    state.counters["exa_triangles"] = static_cast<double>(p.examined.triangle_count());
}
BENCHMARK(BM_Register)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("size_class")
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace glint
