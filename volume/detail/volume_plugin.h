// Opens libglint_volume_io.so (volume/plugin/), the only part of glint linked to ITK, GDCM
// and VTK, on first use, so runs that touch no volume never map those libraries.
#pragma once

#include "mesh/plugin_library.h"
#include "volume/plugin/volume_io_abi.h"

#include <string>
#include <utility>

namespace glint::detail {

/// The plugin's table, loaded once (thread-safe) from the first folder that holds it:
/// $GLINT_PLUGIN_DIR alone when set; else the folder of the program or library that holds
/// this code, its ../lib/glint (bin/ → lib/glint), its ../../glint (an installed Python
/// module in lib/python3/dist-packages), then the configured install lib/glint.
/// \throw IoError (exit code 3) naming what is missing and the Debian packages to install.
[[nodiscard]] const VolumeIoTable& volume_io_plugin();

/// Calls `entry(table, message)` and rethrows what it reports.
template <class Entry>
void call_volume_io(Entry&& entry) {
    call_plugin(volume_io_plugin(), std::forward<Entry>(entry));
}

}  // namespace glint::detail
