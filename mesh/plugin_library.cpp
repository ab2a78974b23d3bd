#include "mesh/plugin_library.h"

#include <dlfcn.h>
#include <sys/mman.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <future>
#include <mutex>
#include <vector>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

// The file of the program or shared library this code is linked into. For the main program
// dladdr answers argv[0] (maybe a bare name found on PATH), so there /proc/self/exe is asked.
fs::path loader_file() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&loader_file), &info) == 0 || info.dli_fname == nullptr)
        return {};
    std::error_code ec;
    if (std::strcmp(info.dli_fname, program_invocation_name) == 0)
        return fs::read_symlink("/proc/self/exe", ec);
    fs::path file = fs::canonical(info.dli_fname, ec);
    return ec ? fs::path() : file;
}

std::vector<fs::path> search_folders() {
    if (const char* dir = std::getenv("GLINT_PLUGIN_DIR"); dir != nullptr && *dir != '\0')
        return {fs::path(dir)};
    std::vector<fs::path> folders;
    if (const fs::path file = loader_file(); !file.empty()) {
        folders.push_back(file.parent_path());
        folders.push_back((file.parent_path() / ".." / "lib" / "glint").lexically_normal());
        // The Python module, installed in lib/python3/dist-packages/.
        folders.push_back((file.parent_path() / ".." / ".." / "glint").lexically_normal());
    }
    folders.emplace_back(GLINT_PLUGIN_INSTALL_DIR);
    return folders;
}

std::string joined(const std::vector<fs::path>& folders) {
    std::string text;
    for (const fs::path& f : folders) text += (text.empty() ? "\"" : ", \"") + f.string() + "\"";
    return text;
}

}  // namespace

fs::path find_plugin(const PluginSpec& spec, std::string& error) {
    const std::vector<fs::path> folders = search_folders();
    for (const fs::path& folder : folders) {
        std::error_code ec;
        if (fs::is_regular_file(folder / spec.file, ec)) return folder / spec.file;
    }
    error = std::string(spec.serves) + ": " + spec.file + " is in none of " + joined(folders) +
            ", expected glint's lib/glint folder; install the Debian packages " + spec.packages;
    return {};
}

namespace {

// note: a plugin's libraries start threads in their own initialisers, where no exception can
// be caught: OpenImageIO's bring log4cplus, whose thread pool ends the process with
// std::terminate ("terminate called without an active exception") when a thread cannot be
// started. Under ulimit -v 600 MB that was 9 of 120 sweeps run three at a time, and the fault
// suite's address-space case failed in CI. Under a finite address space glint first makes sure
// the room the plugin's libraries take to start (PluginSpec::start_bytes) can still be mapped,
// and where it cannot, refuses to load it with the one line a library that cannot be mapped
// gets. Other threads may take some of that room meanwhile: the check narrows the window, it
// cannot close it.
bool room_to_start(const PluginSpec& spec) {
    rlimit limit{};
    if (spec.start_bytes == 0 || getrlimit(RLIMIT_AS, &limit) != 0 ||
        limit.rlim_cur == RLIM_INFINITY)
        return true;
    void* room = mmap(nullptr, spec.start_bytes, PROT_NONE,
                      MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (room == MAP_FAILED) return false;
    munmap(room, spec.start_bytes);
    return true;
}

}  // namespace

void* load_plugin_entry(const PluginSpec& spec, fs::path& file, std::string& error) {
    file = find_plugin(spec, error);
    if (file.empty()) return nullptr;
    if (!room_to_start(spec)) {
        error = std::string(spec.serves) + ": cannot load \"" + file.string() +
                "\": the address space left under its limit (ulimit -v) holds less than the " +
                std::to_string(spec.start_bytes >> 20) +
                " MB its libraries take to start; raise the limit";
        return nullptr;
    }
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
        error = std::string(spec.serves) + ": cannot load \"" + file.string() + "\": " + dlerror() +
                "; install the Debian packages " + spec.packages;
        return nullptr;
    }
    void* entry = dlsym(handle, spec.entry);
    if (entry == nullptr) error = plugin_mismatch(spec, file);
    return entry;  // note: never dlclose'd; the libraries keep global state to the end
}

namespace {

struct BackgroundLoads {
    std::mutex mutex;
    std::vector<std::future<void>> loads;
    // note: destroyed at exit; each future's destructor waits for its load. The program waits
    // earlier (finish_background_loads at the end of main): a load still in dlopen while exit
    // runs has its libraries' destructors run before the rest of their start-up.
};

BackgroundLoads& background_loads() {
    static BackgroundLoads loads;
    return loads;
}

}  // namespace

void load_in_background(std::function<void()> load) {
    BackgroundLoads& b = background_loads();
    const std::lock_guard lock(b.mutex);
    b.loads.push_back(std::async(std::launch::async, std::move(load)));
}

void finish_background_loads() {
    BackgroundLoads& b = background_loads();
    const std::lock_guard lock(b.mutex);
    for (std::future<void>& f : b.loads) f.wait();
}

std::string plugin_mismatch(const PluginSpec& spec, const fs::path& file) {
    return std::string(spec.serves) + ": \"" + file.string() + "\" has no " + spec.entry +
           " of this glint build, expected the plugin built with it";
}

void rethrow_plugin_error(PluginErrorKind kind, const std::string& message) {
    switch (kind) {
        case PluginErrorKind::None: return;
        case PluginErrorKind::Input: throw InputError(message);
        case PluginErrorKind::Io: throw IoError(message);
        case PluginErrorKind::Memory: throw std::bad_alloc();
        case PluginErrorKind::Other: break;
    }
    throw Error(message);
}

}  // namespace glint::detail
