#include "volume/detail/volume_plugin.h"

#include "mesh/error.h"

#include <dlfcn.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <vector>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPluginFile = "libglint_volume_io.so";
// The Debian packages of the libraries the plugin links (dpkg -S on each .so it loads).
constexpr const char* kPackages = "libvtk9.1 libinsighttoolkit5.2 libgdcm3.0";

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

struct LoadedPlugin {
    const VolumeIoTable* table = nullptr;
    std::string error;  ///< why there is no table
};

LoadedPlugin load_plugin() {
    const std::vector<fs::path> folders = search_folders();
    fs::path file;
    for (const fs::path& folder : folders) {
        std::error_code ec;
        if (fs::is_regular_file(folder / kPluginFile, ec)) {
            file = folder / kPluginFile;
            break;
        }
    }
    const std::string install = std::string("; install the Debian packages ") + kPackages;
    if (file.empty())
        return {nullptr, std::string("volume support: ") + kPluginFile + " is in none of " +
                             joined(folders) + ", expected glint's lib/glint folder" + install};
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr)
        return {nullptr,
                "volume support: cannot load \"" + file.string() + "\": " + dlerror() + install};
    using Entry = const VolumeIoTable* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, GLINT_VOLUME_IO_ENTRY));
    const VolumeIoTable* table = entry ? entry() : nullptr;
    if (table == nullptr || table->table_size != sizeof(VolumeIoTable))
        return {nullptr, "volume support: \"" + file.string() + "\" has no " +
                             GLINT_VOLUME_IO_ENTRY +
                             " of this glint build, expected the plugin built with it"};
    return {table, {}};  // note: never dlclose'd; VTK and ITK keep global state to the end
}

}  // namespace

const VolumeIoTable& volume_io_plugin() {
    static const LoadedPlugin plugin = load_plugin();  // once, thread-safe (C++11 statics)
    if (plugin.table == nullptr) throw IoError(plugin.error);
    return *plugin.table;
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
