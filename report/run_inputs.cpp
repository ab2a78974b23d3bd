#include "report/run_inputs.h"

#include "report/orientation.h"

#include <exception>
#include <system_error>
#include <thread>

namespace glint {

namespace fs = std::filesystem;

RunInput load_run_input(const std::string& role, const fs::path& path,
                        const SurfaceOptions& surface) {
    LoadedSurface loaded = load_surface(path, surface);
    RunInput in;
    in.record = {role, path,
                 loaded.surface ? "surface of a volume: " + describe(*loaded.surface) : "",
                 loaded.mesh.vertex_count(), loaded.mesh.triangle_count(),
                 // A volume's surface is in its physical space, which ITK reads as LPS.
                 loaded.surface ? "LPS" : to_string(space_stated_in(path)),
                 loaded.surface ? "" : loaded.report.sha256};
    for (const auto& w : loaded.report.warnings)
        in.warnings.push_back(loaded.report.path.string() + ": " + w);
    in.mesh = std::move(loaded.mesh);
    return in;
}

std::pair<RunInput, RunInput> load_run_pair(const fs::path& reference, const fs::path& examined,
                                            const SurfaceOptions& surface,
                                            const std::function<void(std::string_view)>& loaded) {
    const auto tell = [&](std::string_view role) {
        if (loaded) loaded(role);
    };
    if (is_volume_path(reference) || is_volume_path(examined)) {
        RunInput ref = load_run_input("reference", reference, surface);
        tell("reference");
        RunInput exa = load_run_input("examined", examined, surface);
        tell("examined");
        return {std::move(ref), std::move(exa)};
    }
    RunInput exa;
    std::exception_ptr exa_error;
    std::thread other;
    try {
        other = std::thread([&] {
            try {
                exa = load_run_input("examined", examined, surface);
            } catch (...) {
                exa_error = std::current_exception();
            }
        });
    } catch (const std::system_error&) {
        // No thread to be had (address space, a process limit): one file after the other.
        RunInput ref = load_run_input("reference", reference, surface);
        tell("reference");
        exa = load_run_input("examined", examined, surface);
        tell("examined");
        return {std::move(ref), std::move(exa)};
    }
    RunInput ref;
    try {
        ref = load_run_input("reference", reference, surface);
        // note: the examined file may have been read first; the reference is told first
        // anyway (its error wins too), so the count lags, never runs ahead. Inside the try: a
        // listener that throws (a cancelled run) still joins the other thread.
        tell("reference");
    } catch (...) {
        other.join();
        throw;
    }
    other.join();
    if (exa_error) std::rethrow_exception(exa_error);
    tell("examined");
    return {std::move(ref), std::move(exa)};
}

RunInput mesh_run_input(const std::string& role, Mesh mesh, std::string description, fs::path path,
                        std::vector<std::string> warnings) {
    RunInput in;
    in.record = {role, std::move(path), std::move(description), mesh.vertex_count(),
                 mesh.triangle_count()};
    in.mesh = std::move(mesh);
    in.warnings = std::move(warnings);
    return in;
}

void RunRecord::add(const RunInput& input) {
    inputs.push_back(input.record);
    warnings.insert(warnings.end(), input.warnings.begin(), input.warnings.end());
}

void RunRecord::add_file(const std::string& role, const fs::path& path, std::string description) {
    inputs.push_back({role, path, std::move(description), 0, 0});
}

}  // namespace glint
