// Shared by the volume harnesses: the iso-surface of a small volume at the middle of its value
// range. note: 32^3 voxels keeps one extraction well under libFuzzer's per-input timeout.
#pragma once

#include "volume/surface.h"
#include "volume/volume.h"

namespace glint::fuzz {

/// A voxel budget that keeps every input within libFuzzer's 2 GB memory limit (float voxels,
/// ITK's buffer of the stored type and the cast copy together).
inline constexpr std::size_t kMaxVoxels = 64u * 1024u * 1024u;

inline void extract_small(const Volume& volume) {
    if (volume.geometry.voxel_count() > 32u * 32u * 32u || volume.voxels.empty()) return;
    const auto range = volume.range();
    if (!(range[1] > range[0])) return;
    SurfaceOptions options;
    options.iso = 0.5 * (static_cast<double>(range[0]) + static_cast<double>(range[1]));
    (void)extract_surface(volume, options);
}

}  // namespace glint::fuzz
