#include "volume/detail/volume_plugin.h"

#include "mesh/error.h"
#include "mesh/plugin_library.h"

#include <string>

namespace glint::detail {

namespace {

// The Debian packages of the libraries the plugin links (dpkg -S on each .so it loads). Loading
// it takes 77 MB of address space (VmSize before and after, Debian 12) and starts no thread.
constexpr PluginSpec kPlugin{"libglint_volume_io.so", GLINT_VOLUME_IO_ENTRY, "volume support",
                             "libvtk9.1 libinsighttoolkit5.2 libgdcm3.0", std::size_t{96} << 20};

}  // namespace

const VolumeIoTable& volume_io_plugin() { return plugin_table<VolumeIoTable>(kPlugin); }

}  // namespace glint::detail
