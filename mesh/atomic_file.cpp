#include "mesh/atomic_file.h"

#include "mesh/error.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <system_error>
#include <unistd.h>

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

void write_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
    const fs::path target = canonical_or_absolute(path);
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
    const fs::path temp = folder / ("." + target.filename().string() + ".tmp-" +
                                    std::to_string(::getpid()) + "-" + std::to_string(counter++));
    try {
        {
            std::ofstream out(temp, std::ios::binary | std::ios::trunc);
            if (!out)
                throw IoError("cannot write \"" + path.string() + "\": cannot create \"" +
                              temp.string() + "\": " + std::strerror(errno));
            write(out);
            out.flush();
            if (!out)
                throw IoError("cannot write \"" + path.string() + "\": write failed (disk full?)");
        }
        fs::rename(temp, target, ec);
        if (ec)
            throw IoError("cannot write \"" + path.string() + "\": rename failed: " + ec.message());
    } catch (...) {
        fs::remove(temp, ec);
        throw;
    }
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    write_atomically(path, [&](std::ostream& out) {
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    });
}

}  // namespace glint
