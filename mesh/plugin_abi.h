// What glint's plugins (libglint_volume_io.so, libglint_image_io.so) and the program agree on:
// how an error crosses the dlopen boundary. No exception unwinds through a plugin's entry:
// each entry returns a kind and fills a one-line message (plugin_guarded), and the program
// rethrows it as its own type (mesh/plugin_library.h), so `catch (const InputError&)` sees the
// program's type, not a copy of it in the plugin.
#pragma once

#include "mesh/error.h"

#include <exception>
#include <new>
#include <string>
#include <utility>

namespace glint::detail {

/// What went wrong inside a plugin, as the main side rethrows it.
enum class PluginErrorKind : int {
    None = 0,
    Input = 1,   ///< InputError
    Io = 2,      ///< IoError
    Other = 3,   ///< any other exception (a library bug): Error
    Memory = 4,  ///< std::bad_alloc, rethrown as such (the program reports it with its limits)
};

/// Runs `step` inside a plugin entry: None, or the kind of what it threw with its message.
template <class Step>
PluginErrorKind plugin_guarded(std::string& message, Step&& step) noexcept {
    try {
        std::forward<Step>(step)();
        return PluginErrorKind::None;
    } catch (const InputError& e) {
        message = e.what();
        return PluginErrorKind::Input;
    } catch (const IoError& e) {
        message = e.what();
        return PluginErrorKind::Io;
    } catch (const std::bad_alloc& e) {
        message = e.what();
        return PluginErrorKind::Memory;
    } catch (const std::exception& e) {
        message = e.what();
    } catch (...) {
        message = "an unknown exception";
    }
    return PluginErrorKind::Other;
}

}  // namespace glint::detail
