// Command-line flags for surfaces taken from volumes (volume/surface.h), shared by every
// command that accepts a mesh: --iso, --surface-roi (--roi in `glint surface`), --largest,
// --seed, --smooth, --passband, --edge, --tolerance. Text values are parsed while the command
// line is read, so a bad one fails before anything is loaded.
#pragma once

#include "volume/load.h"
#include "volume/surface.h"

#include <CLI/CLI.hpp>

#include <string>
#include <utility>

namespace glint::cli {

/// Adds the surface flags to `command`, bound to `options`. `roi_flag` names the ROI flag.
void add_surface_flags(CLI::App& command, SurfaceOptions& options,
                       const std::string& roi_flag = "--surface-roi");

/// A one-line summary of a surface extracted from a volume, for the commands' output.
[[nodiscard]] std::string describe(const SurfaceReport& report);

/// The reference and examined surfaces of a pair (load_surface). Two mesh files are read at
/// once, on two threads; volumes one after the other (ITK's and VTK's readers are not known to
/// be safe side by side). The reference's error is thrown first, as when read in turn.
[[nodiscard]] std::pair<LoadedSurface, LoadedSurface> load_pair(const std::string& reference,
                                                                const std::string& examined,
                                                                const SurfaceOptions& surface);

}  // namespace glint::cli
