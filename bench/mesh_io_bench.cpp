// Mesh loading speed: load + weld + repairs + normals for binary PLY and binary STL at 200k and
// 2M triangles, glint's own readers beside assimp, plus the parse alone (all repairs off).
//
// The meshes are noisy tori (rows x cols x 2 triangles), generated once into a temporary folder
// that is removed at exit.
#include "mesh/io.h"
#include "mesh/write.h"

#include <benchmark/benchmark.h>

#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

namespace {

namespace fs = std::filesystem;
using glint::LoadOptions;
using glint::Mesh;

Mesh noisy_torus(int rows, int cols) {
    Mesh m;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> noise(-1e-3f, 1e-3f);
    const double two_pi = 6.283185307179586;
    m.positions.reserve(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double u = two_pi * i / rows, v = two_pi * j / cols;
            const double r = 1.0 + 0.3 * std::cos(v);
            m.positions.emplace_back(static_cast<float>(r * std::cos(u)) + noise(rng),
                                     static_cast<float>(r * std::sin(u)) + noise(rng),
                                     static_cast<float>(0.3 * std::sin(v)) + noise(rng));
        }
    auto id = [&](int i, int j) {
        return static_cast<std::uint32_t>((i % rows) * cols + (j % cols));
    };
    m.triangles.reserve(2 * m.positions.size());
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

void write_binary_stl(const Mesh& m, const fs::path& path) {
    std::string s(80, ' ');
    const auto n = static_cast<std::uint32_t>(m.triangles.size());
    s.append(reinterpret_cast<const char*>(&n), 4);
    s.reserve(84 + 50 * m.triangles.size());
    for (const auto& t : m.triangles) {
        const float zero[3] = {0, 0, 0};
        s.append(reinterpret_cast<const char*>(zero), 12);
        for (auto i : t) s.append(reinterpret_cast<const char*>(m.positions[i].data()), 12);
        s.append(2, '\0');
    }
    std::ofstream(path, std::ios::binary).write(s.data(), static_cast<std::streamsize>(s.size()));
}

// The generated files, made on first use and removed at exit.
class Files {
  public:
    ~Files() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    static Files& get() {
        static Files files;
        return files;
    }
    fs::path path(const std::string& size, const std::string& ext) {
        const fs::path p = dir_ / ("torus_" + size + "." + ext);
        if (!fs::exists(p)) {
            // 200k: 250 x 400 x 2 = 200,000 triangles; 2M: 1000 x 1000 x 2.
            const Mesh m = size == "200k" ? noisy_torus(250, 400) : noisy_torus(1000, 1000);
            if (ext == "ply") glint::write_ply(m, p, glint::WriteOptions{.write_normals = false});
            else write_binary_stl(m, p);
        }
        return p;
    }

  private:
    Files()
        : dir_(fs::temp_directory_path() / ("glint_mesh_io_bench_" + std::to_string(::getpid()))) {
        fs::create_directories(dir_);
    }
    fs::path dir_;
};

enum Reader { kFast, kAssimp };

void run(benchmark::State& state, const std::string& size, const std::string& ext, Reader reader,
         const LoadOptions& options) {
    const fs::path path = Files::get().path(size, ext);
    std::size_t triangles = 0;
    for (auto _ : state) {
        auto loaded = reader == kFast ? glint::load_mesh(path, options)
                                      : glint::load_mesh_assimp(path, options);
        triangles = loaded.mesh.triangle_count();
        benchmark::DoNotOptimize(loaded.mesh.positions.data());
    }
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["Mtri/s"] = benchmark::Counter(
        static_cast<double>(triangles) * static_cast<double>(state.iterations()) / 1e6,
        benchmark::Counter::kIsRate);
}

const LoadOptions kFull{};  // weld + repairs + checks + angle-weighted normals
const LoadOptions kParseOnly{
    .weld = false, .drop_degenerate = false, .drop_unused = false, .compute_normals = false};

void register_all() {
    for (const char* size : {"200k", "2M"})
        for (const char* ext : {"ply", "stl"}) {
            for (Reader r : {kFast, kAssimp}) {
                const std::string name = std::string("Load/") + ext + "/" +
                                         (r == kFast ? "glint" : "assimp") + "/" + size;
                benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                    run(s, size, ext, r, kFull);
                })->Unit(benchmark::kMillisecond);
            }
            const std::string name = std::string("ParseOnly/") + ext + "/glint/" + size;
            benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
                run(s, size, ext, kFast, kParseOnly);
            })->Unit(benchmark::kMillisecond);
        }
}

const bool kRegistered = (register_all(), true);

}  // namespace
