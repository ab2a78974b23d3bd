#include "image/detail/image_plugin.h"

#include "mesh/error.h"

#include <future>

namespace glint::detail {

namespace {

// The Debian package of the library the plugin links (dpkg -S libOpenImageIO.so.2.4).
constexpr PluginSpec kPlugin{"libglint_image_io.so", GLINT_IMAGE_IO_ENTRY, sizeof(ImageIoTable),
                             "pictures and image files", "libopenimageio2.4"};

struct LoadedPlugin {
    const ImageIoTable* table = nullptr;
    std::string error;  ///< why there is no table
};

LoadedPlugin load() {
    LoadedPlugin plugin;
    plugin.table = static_cast<const ImageIoTable*>(load_plugin_table(kPlugin, plugin.error));
    return plugin;
}

}  // namespace

void preload_image_io_plugin() {
    std::string error;
    if (find_plugin(kPlugin, error).empty()) throw IoError(error);
    // note: the future's destructor (at exit) waits for a load still under way, so the
    // program never ends while another thread is inside dlopen.
    static std::future<void> loading = std::async(std::launch::async, [] {
        try {
            (void)image_io_plugin();
        } catch (...) {  // reported by the first use
        }
    });
}

const ImageIoTable& image_io_plugin() {
    static const LoadedPlugin plugin = load();  // once, thread-safe (C++11 statics)
    if (plugin.table == nullptr) throw IoError(plugin.error);
    return *plugin.table;
}

}  // namespace glint::detail
