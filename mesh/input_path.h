// Why an input path cannot be reached, in words a user can act on (issue 23 item 18): a file
// behind a folder this user may not enter is not "not found", and no bad input either: it is
// an I/O problem of this machine (exit 3), named by the folder that bars the way.
#pragma once

#include <filesystem>
#include <string>

namespace glint {

/// How `path` stands for reading.
enum class PathReach {
    Reachable,  ///< it exists (whatever it is)
    Missing,    ///< it, or a folder on its way, does not exist
    Denied,     ///< a folder on its way may not be entered, or the path may not be looked at
    Failed,     ///< any other error of the filesystem (a loop of links, an I/O error, …)
};

struct PathCheck {
    PathReach reach = PathReach::Reachable;
    /// "" when reachable; else why, e.g. `folder "/data/ct" may not be entered by this user
    /// (permission denied); expected a path this user can reach`.
    std::string reason;
};

/// Looks `path` up (following links) and, when that fails, says why.
[[nodiscard]] PathCheck check_path(const std::filesystem::path& path);

/// Whether `path` exists; throws IoError "<where>: <reason>" (exit 3) when it cannot be looked
/// at: a folder on its way that this user may not enter, or a failing filesystem. A missing
/// path is left to the caller (each names it in its own words and exit code).
[[nodiscard]] bool reachable_input(const std::filesystem::path& path, const std::string& where);

}  // namespace glint
