#include "mesh/atomic_file.h"

#include "mesh/error.h"

#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::mutex& inputs_mutex() {
    static std::mutex m;
    return m;
}
std::set<fs::path>& protected_inputs() {
    static std::set<fs::path> inputs;
    return inputs;
}

fs::path canonical_or_absolute(const fs::path& path) {
    std::error_code ec;
    auto c = fs::weakly_canonical(path, ec);
    return ec ? fs::absolute(path) : c;
}

}  // namespace

void protect_input(const fs::path& path) {
    std::lock_guard lock(inputs_mutex());
    protected_inputs().insert(canonical_or_absolute(path));
}

namespace {

// Checks the target and returns a temporary path beside it with the same extension.
fs::path prepare(const fs::path& path, fs::path& target) {
    target = canonical_or_absolute(path);
    {
        std::lock_guard lock(inputs_mutex());
        if (protected_inputs().count(target))
            throw InputError("output \"" + path.string() +
                             "\" is one of the inputs; refusing to overwrite an input");
    }
    const fs::path folder = target.parent_path();
    std::error_code ec;
    if (!folder.empty() && !fs::is_directory(folder, ec))
        throw IoError("cannot write \"" + path.string() + "\": folder \"" + folder.string() +
                      "\" does not exist");
    static std::atomic<unsigned> counter{0};
    return folder / ("." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                     std::to_string(counter++) + target.extension().string());
}

void commit(const fs::path& temp, const fs::path& target, const fs::path& path) {
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec) throw IoError("cannot write \"" + path.string() + "\": rename failed: " + ec.message());
}

}  // namespace

void write_atomically_to_path(const fs::path& path,
                              const std::function<void(const fs::path&)>& write) {
    fs::path target;
    const fs::path temp = prepare(path, target);
    try {
        write(temp);
        std::error_code ec;
        if (!fs::is_regular_file(temp, ec))
            throw IoError("cannot write \"" + path.string() + "\": the writer produced no file");
        commit(temp, target, path);
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
}

void write_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
    write_atomically_to_path(path, [&](const fs::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw IoError("cannot write \"" + path.string() + "\": cannot create \"" +
                          temp.string() + "\": " + std::strerror(errno));
        write(out);
        out.flush();
        if (!out)
            throw IoError("cannot write \"" + path.string() + "\": write failed (disk full?)");
    });
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    write_atomically(path, [&](std::ostream& out) {
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    });
}

}  // namespace glint
