// Opening glint's plugins (the shared libraries in lib/glint/ that alone link the heavy
// libraries: ITK/GDCM/VTK for volumes, OpenImageIO for pictures) on first use, so runs that
// need none of them never map them.
#pragma once

#include "mesh/plugin_abi.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>

namespace glint::detail {

/// One plugin: its file, its one exported entry (`const Table* entry()`, the table's first
/// member its size as the plugin was built), what it serves (for messages) and the Debian
/// packages its libraries come from.
struct PluginSpec {
    const char* file;      ///< "libglint_image_io.so"
    const char* entry;     ///< "glint_image_io_table_v1"
    const char* serves;    ///< "pictures and image files", "volume support"
    const char* packages;  ///< "libopenimageio2.4"
    /// The address space its libraries take to start (bytes; 0: not known): their mappings,
    /// and the stacks and malloc arenas of the threads their initialisers start. Under a
    /// finite address space (ulimit -v) a plugin is loaded only where that much can still be
    /// mapped (plugin_library.cpp).
    std::size_t start_bytes = 0;
};

/// The plugin's file, or empty with `error` set to one line naming where it was looked for
/// and the packages to install (the folders as for load_plugin_table).
[[nodiscard]] std::filesystem::path find_plugin(const PluginSpec& spec, std::string& error);

/// Finds and opens the plugin and returns its entry's address (`file` set to where it was
/// found), or null with `error` set to one line (what is missing or broken, where it was
/// looked for, the packages to install). Looks in $GLINT_PLUGIN_DIR alone when set; else the
/// folder of the program or library that holds this code, its ../lib/glint (bin/ →
/// lib/glint), its ../../glint (an installed Python module in lib/python3/dist-packages),
/// then the configured install lib/glint. Never dlclose'd.
[[nodiscard]] void* load_plugin_entry(const PluginSpec& spec, std::filesystem::path& file,
                                      std::string& error);

/// Runs `load` (a plugin's first load) on a thread of its own, so that a run's work goes on
/// meanwhile. Its errors are the loader's to report at first use: `load` must not throw.
void load_in_background(std::function<void()> load);

/// Waits until every load started by load_in_background has ended. Called before fork(): a
/// child made while another thread is inside dlopen inherits the loader's lock and its lists
/// half-changed, and its first dlopen, dlsym or thrown exception may then hang or crash. And
/// before exit: exit runs the destructors a library registers while it loads at once, and the
/// rest of its start-up then uses what they destroyed.
void finish_background_loads();

/// The line for a plugin whose entry gave no table of this build's size.
[[nodiscard]] std::string plugin_mismatch(const PluginSpec& spec,
                                          const std::filesystem::path& file);

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
        std::filesystem::path file;
        void* symbol = load_plugin_entry(spec, file, l.error);
        if (symbol == nullptr) return l;
        // note: called through its own type (`const Table* ()`): a call through any other
        // function type is undefined (UBSan's -fsanitize=function reports it).
        const Table* table = reinterpret_cast<const Table* (*)()>(symbol)();
        if (table == nullptr || table->table_size != sizeof(Table))
            l.error = plugin_mismatch(spec, file);
        else l.table = table;
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
