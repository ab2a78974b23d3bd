// Opening glint's plugins (the shared libraries in lib/glint/ that alone link the heavy
// libraries: ITK/GDCM/VTK for volumes, OpenImageIO for pictures) on first use, so runs that
// need none of them never map them.
#pragma once

#include "mesh/plugin_abi.h"

#include <cstddef>
#include <filesystem>
#include <string>

namespace glint::detail {

/// One plugin: its file, its one exported entry (returning a table whose first member is the
/// table's size), what it serves (for messages) and the Debian packages its libraries come from.
struct PluginSpec {
    const char* file;        ///< "libglint_image_io.so"
    const char* entry;       ///< "glint_image_io_table_v1"
    std::size_t table_size;  ///< sizeof the table as this program was built
    const char* serves;      ///< "pictures", "volume support"
    const char* packages;    ///< "libopenimageio2.4"
};

/// The plugin's file, or empty with `error` set to one line naming where it was looked for
/// and the packages to install (the folders as for load_plugin_table).
[[nodiscard]] std::filesystem::path find_plugin(const PluginSpec& spec, std::string& error);

/// Finds and opens the plugin and returns its table, or null with `error` set to one line
/// (what is missing or broken, where it was looked for, the packages to install). Looks in
/// $GLINT_PLUGIN_DIR alone when set; else the folder of the program or library that holds
/// this code, its ../lib/glint (bin/ → lib/glint), its ../../glint (an installed Python module
/// in lib/python3/dist-packages), then the configured install lib/glint. Never dlclose'd.
[[nodiscard]] const void* load_plugin_table(const PluginSpec& spec, std::string& error);

/// Rethrows an error a plugin reported as glint's own type (InputError, IoError, Error).
void rethrow_plugin_error(PluginErrorKind kind, const std::string& message);

/// The table of the plugin `spec` names, loaded on the first call (once per Table type,
/// thread-safe). \throw IoError (exit code 3) naming what is missing and what to install.
template <class Table>
[[nodiscard]] const Table& plugin_table(const PluginSpec& spec) {
    struct Loaded {
        const Table* table = nullptr;
        std::string error;  ///< why there is no table
    };
    static const Loaded loaded = [&] {
        Loaded l;
        l.table = static_cast<const Table*>(load_plugin_table(spec, l.error));
        return l;
    }();
    if (loaded.table == nullptr) throw IoError(loaded.error);
    return *loaded.table;
}

/// Calls `entry(table, message)` and rethrows what it reports.
template <class Table, class Entry>
void call_plugin(const Table& table, Entry&& entry) {
    std::string message;
    const PluginErrorKind kind = entry(table, message);
    if (kind != PluginErrorKind::None) rethrow_plugin_error(kind, message);
}

}  // namespace glint::detail
