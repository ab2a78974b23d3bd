// glint's version: the project() line of CMakeLists.txt is its one source (glint --version,
// report.json, the Python module's __version__, the .deb).
#pragma once

#ifndef GLINT_VERSION
#error "GLINT_VERSION is defined by the build (mesh/CMakeLists.txt)"
#endif

namespace glint {

/// The release, e.g. "0.1.0".
inline constexpr const char* kVersion = GLINT_VERSION;

}  // namespace glint
