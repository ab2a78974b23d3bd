// Ground-truth poses of range scans in the Stanford 3D Scanning Repository's .conf format:
// one line per scan, `bmesh <file> tx ty tz qx qy qz qw`, where a scan point p lands in the
// common frame as p_common = R(q)ᵀ·p + t (R(q) the rotation of the unit quaternion as written;
// verified on the bunny: every scan lands on the reconstruction within its scanner noise).
// Other lines (`camera …`, blank, `#` comments) are skipped.
#pragma once

#include "mesh/geometry.h"

#include <filesystem>
#include <string>

namespace glint {

/// The pose of scan `entry` (the file name as the .conf writes it) in `conf`: the transform
/// from the scan's frame to the common frame (reference_from_examined).
/// \throw IoError the file cannot be read; InputError the entry is absent or its line is
/// malformed (file, line, what was found, what was expected).
[[nodiscard]] Rigid read_conf_pose(const std::filesystem::path& conf, const std::string& entry);

}  // namespace glint
