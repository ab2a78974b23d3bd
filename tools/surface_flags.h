// Command-line flags for surfaces taken from volumes (volume/surface.h), shared by every
// command that accepts a mesh: --iso, --surface-roi (--roi in `glint surface`), --largest,
// --seed, --smooth, --passband, --edge, --tolerance. Text values are parsed while the command
// line is read, so a bad one fails before anything is loaded.
#pragma once

#include "volume/load.h"
#include "volume/surface.h"

#include <CLI/CLI.hpp>

#include <string>

namespace glint::cli {

/// Adds the surface flags to `command`, bound to `options`. `roi_flag` names the ROI flag.
void add_surface_flags(CLI::App& command, SurfaceOptions& options,
                       const std::string& roi_flag = "--surface-roi");

}  // namespace glint::cli
