// Opens libglint_image_io.so (image/plugin/), the only part of glint linked to OpenImageIO,
// on first use (mesh/plugin_library.h says where it is looked for).
#pragma once

#include "image/plugin/image_io_abi.h"
#include "mesh/plugin_library.h"

#include <string>
#include <utility>

namespace glint::detail {

/// The plugin's table, loaded once (thread-safe).
/// \throw IoError (exit code 3) naming what is missing and the Debian package to install.
[[nodiscard]] const ImageIoTable& image_io_plugin();

/// Throws (IoError, as image_io_plugin) at once when the plugin's file is missing, and opens
/// it on a background thread. Idempotent.
void preload_image_io_plugin();

/// Calls `entry(table, message)` and rethrows what it reports.
template <class Entry>
void call_image_io(Entry&& entry) {
    call_plugin(image_io_plugin(), std::forward<Entry>(entry));
}

}  // namespace glint::detail
