#include "mesh/input_path.h"

#include "mesh/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace glint {

namespace fs = std::filesystem;

namespace {

// The first folder on the way to `path` that this user may not enter (search permission, as
// the effective user), or "" when every folder may be entered.
fs::path barring_folder(const fs::path& path) {
    std::error_code ec;
    fs::path absolute = fs::absolute(path, ec);
    if (ec) absolute = path;
    fs::path folder;
    const fs::path parent = absolute.parent_path();
    for (const fs::path& part : parent) {
        folder /= part;
        if (::faccessat(AT_FDCWD, folder.c_str(), X_OK, AT_EACCESS) != 0 && errno == EACCES)
            return folder;
    }
    return {};
}

}  // namespace

PathCheck check_path(const fs::path& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) return {};
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) return {PathReach::Missing, "file not found"};
    if (err == EACCES) {
        const fs::path folder = barring_folder(path);
        return {PathReach::Denied,
                folder.empty() ? std::string("cannot be looked at by this user (permission "
                                             "denied); expected a path this user can reach")
                               : "folder \"" + folder.string() +
                                     "\" may not be entered by this user (permission denied); "
                                     "expected a path this user can reach"};
    }
    return {PathReach::Failed, std::string("cannot be looked at: ") + std::strerror(err) +
                                   "; expected a readable path"};
}

bool reachable_input(const fs::path& path, const std::string& where) {
    const PathCheck c = check_path(path);
    if (c.reach == PathReach::Denied || c.reach == PathReach::Failed)
        throw IoError(where + ": " + c.reason);
    return c.reach == PathReach::Reachable;
}

}  // namespace glint
