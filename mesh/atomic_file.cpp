#include "mesh/atomic_file.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/fault_injection.h"
#include "mesh/file_set.h"
#include "mesh/output_guard.h"

#include <unistd.h>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

namespace {

fs::path canonical_or_absolute(const fs::path& path) {
    std::error_code ec;
    auto c = fs::weakly_canonical(path, ec);
    return ec ? fs::absolute(path) : c;
}

// Checks the target and returns a temporary path beside it with the same extension.
fs::path prepare(const fs::path& path, fs::path& target) {
    target = canonical_or_absolute(path);
    refuse_output_over_inputs(path);
    const fs::path folder = target.parent_path();
    std::error_code ec;
    if (!folder.empty() && !fs::is_directory(folder, ec))
        throw IoError("cannot write \"" + path.string() + "\": folder \"" + folder.string() +
                      "\" does not exist");
    static std::atomic<unsigned> counter{0};
    fs::path temp = folder / ("." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                              "-" + std::to_string(counter++) + target.extension().string());
    track_staged(temp);  // removed by the watchdog when a step never comes back
    return temp;
}

// Removes a temporary that will not be committed.
void discard(const fs::path& temp) noexcept {
    std::error_code ec;
    fs::remove(temp, ec);
    untrack_staged(temp);
}

void commit(const fs::path& temp, const fs::path& target, const fs::path& path) {
    fault_point("file-commit");
    throw_if_cancelled();  // a signal that came during the writing is not swallowed here
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec) throw IoError("cannot write \"" + path.string() + "\": rename failed: " + ec.message());
    untrack_staged(temp);
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
    } catch (const IoError& e) {
        discard(temp);
        throw naming_target(e, temp, path);  // a writer names the file it was given
    } catch (...) {
        discard(temp);
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

FileSet::~FileSet() {
    for (const Staged& s : staged_) discard(s.temp);
}

void FileSet::add(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    Staged s;
    s.path = path;
    s.temp = prepare(path, s.target);
    try {
        write(s.temp);
        std::error_code ec;
        if (!fs::is_regular_file(s.temp, ec))
            throw IoError("cannot write \"" + path.string() + "\": the writer produced no file");
    } catch (const IoError& e) {
        discard(s.temp);
        throw naming_target(e, s.temp, path);
    } catch (...) {
        discard(s.temp);
        throw;
    }
    staged_.push_back(std::move(s));
}

void FileSet::add(const fs::path& path, std::string_view contents) {
    add(path, [&](const fs::path& temp) { write_file_atomically(temp, contents); });
}

void FileSet::commit() {
    fault_point("file-commit");
    throw_if_cancelled();  // the destructor removes the temporaries: none of the set appears
    for (std::size_t i = 0; i < staged_.size(); ++i) {
        std::error_code ec;
        fs::rename(staged_[i].temp, staged_[i].target, ec);
        if (!ec) {
            untrack_staged(staged_[i].temp);
            continue;
        }
        const std::string why = ec.message();
        for (std::size_t j = 0; j < i; ++j) fs::remove(staged_[j].target, ec);
        throw IoError("cannot write \"" + staged_[i].path.string() + "\": rename failed: " + why +
                      " (none of its set was kept)");
    }
    staged_.clear();
}

IoError naming_target(const IoError& error, const fs::path& staged, const fs::path& target) {
    std::string text = error.what();
    const std::string from = staged.string(), to = target.string();
    if (!from.empty())
        for (std::size_t at = text.find(from); at != std::string::npos;
             at = text.find(from, at + to.size()))
            text.replace(at, from.size(), to);
    return IoError(text);
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    write_atomically(path, [&](std::ostream& out) {
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    });
}

}  // namespace glint
