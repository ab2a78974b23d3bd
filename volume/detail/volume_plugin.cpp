#include "volume/detail/volume_plugin.h"

#include "mesh/error.h"
#include "mesh/plugin_library.h"

#include <string>

namespace glint::detail {

namespace {

// The Debian packages of the libraries the plugin links (dpkg -S on each .so it loads).
constexpr PluginSpec kPlugin{"libglint_volume_io.so", GLINT_VOLUME_IO_ENTRY, sizeof(VolumeIoTable),
                             "volume support", "libvtk9.1 libinsighttoolkit5.2 libgdcm3.0"};

struct LoadedPlugin {
    const VolumeIoTable* table = nullptr;
    std::string error;  ///< why there is no table
};

LoadedPlugin load() {
    LoadedPlugin plugin;
    plugin.table = static_cast<const VolumeIoTable*>(load_plugin_table(kPlugin, plugin.error));
    return plugin;
}

}  // namespace

const VolumeIoTable& volume_io_plugin() {
    static const LoadedPlugin plugin = load();  // once, thread-safe (C++11 statics)
    if (plugin.table == nullptr) throw IoError(plugin.error);
    return *plugin.table;
}

}  // namespace glint::detail
