#include "mesh/small_file.h"

#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/output_guard.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace glint {

namespace {

std::string kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string size_text(std::size_t bytes) {
    return bytes >= (std::size_t{1} << 20) ? std::to_string(bytes >> 20) + " MiB"
                                           : std::to_string(bytes) + " bytes";
}

}  // namespace

std::string read_small_file(const std::filesystem::path& path, const std::string& what,
                            std::size_t max_bytes) {
    const std::string where = what + " \"" + path.string() + "\"";
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
        const int e = errno;
        // A folder on the way that this user may not enter is named (issue 23 item 18).
        if (const PathCheck c = check_path(path); e == EACCES && c.reach == PathReach::Denied)
            throw IoError(where + ": " + c.reason);
        throw IoError(where + ": cannot open: " + std::strerror(e) +
                      (e == ENOENT ? "" : ", expected a readable file"));
    }
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        const int e = errno;
        ::close(fd);
        throw IoError(where + ": cannot read its size: " + std::strerror(e));
    }
    if (!S_ISREG(st.st_mode)) {
        ::close(fd);
        throw InputError(where + ": is " + kind_of(st.st_mode) + ", expected a file");
    }
    const auto size = static_cast<std::size_t>(st.st_size);
    if (size > max_bytes) {
        ::close(fd);
        throw InputError(where + ": " + std::to_string(size) + " bytes, expected at most " +
                         size_text(max_bytes));
    }
    protect_input(path);  // never an output of this process (issue 52: every file a run reads)
    std::string text(size, '\0');
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::read(fd, text.data() + done, size - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            const int e = errno;
            ::close(fd);
            throw IoError(where + ": cannot read: " + std::strerror(e));
        }
        if (n == 0) break;
        done += static_cast<std::size_t>(n);
    }
    char extra = 0;
    const bool grew = ::read(fd, &extra, 1) > 0;
    ::close(fd);
    if (done != size || grew)
        throw InputError(where + ": changed while it was read (" + std::to_string(size) +
                         " bytes when opened); expected a file no other program is writing");
    return text;
}

}  // namespace glint
