#include "volume/detail/isolated_read.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/plugin_library.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <new>
#include <string>
#include <system_error>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

// What the child leaves in the memory file: this header, then the message (on failure) or the
// format name, the stored type and the voxels.
struct ResultHeader {
    std::uint32_t magic = 0;
    std::uint32_t outcome = 0;  // Outcome
    std::uint64_t text_bytes = 0, format_bytes = 0, stored_bytes = 0, voxel_count = 0;
    std::uint64_t size[3] = {0, 0, 0};
    double spacing[3] = {0, 0, 0}, origin[3] = {0, 0, 0}, direction[9] = {};
};
constexpr std::uint32_t kMagic = 0x676c6476;  // "vdlg"
enum Outcome : std::uint32_t { kVolume = 1, kInputError, kIoError, kOutOfMemory, kOtherError };

std::string quoted_source(const fs::path& p) {
    std::error_code ec;
    return (fs::is_directory(p, ec) ? "DICOM folder \"" : "volume \"") + p.string() + "\"";
}

class Descriptor {
  public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    [[nodiscard]] int get() const { return fd_; }

  private:
    int fd_;
};

// A private temporary folder for the child (GDCM's folder of links, see dicom_check.h): a
// crashed child cannot remove what it made, so the parent removes the whole folder.
class ChildTemp {
  public:
    ChildTemp() {
        std::string pattern = (fs::temp_directory_path() / "glint-dicom-read-XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr)
            throw IoError("cannot make a temporary folder in \"" +
                          fs::temp_directory_path().string() +
                          "\" for the DICOM reader: " + std::strerror(errno));
        path_ = pattern;
        track_staged(path_);
    }
    ~ChildTemp() {
        std::error_code ec;
        fs::remove_all(path_, ec);
        untrack_staged(path_);
    }
    ChildTemp(const ChildTemp&) = delete;
    ChildTemp& operator=(const ChildTemp&) = delete;
    [[nodiscard]] const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

bool write_all(int fd, const void* data, std::size_t n) {
    const auto* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= static_cast<std::size_t>(w);
    }
    return true;
}

bool read_all(int fd, std::uint64_t offset, void* into, std::size_t n) {
    auto* p = static_cast<char*>(into);
    while (n > 0) {
        const ssize_t r = ::pread(fd, p, n, static_cast<off_t>(offset));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= static_cast<std::size_t>(r);
        offset += static_cast<std::uint64_t>(r);
    }
    return true;
}

void write_failure(int fd, Outcome outcome, const std::string& message) {
    ResultHeader h;
    h.magic = kMagic;
    h.outcome = outcome;
    h.text_bytes = message.size();
    if (write_all(fd, &h, sizeof h)) write_all(fd, message.data(), message.size());
}

void write_volume(int fd, const RawVolume& v) {
    ResultHeader h;
    h.magic = kMagic;
    h.outcome = kVolume;
    h.format_bytes = v.format.size();
    h.stored_bytes = v.stored_type.size();
    h.voxel_count = v.voxels.size();
    for (int d = 0; d < 3; ++d) {
        h.size[d] = v.size[static_cast<std::size_t>(d)];
        h.spacing[d] = v.spacing[static_cast<std::size_t>(d)];
        h.origin[d] = v.origin[static_cast<std::size_t>(d)];
    }
    for (std::size_t i = 0; i < 9; ++i) h.direction[i] = v.direction[i];
    if (!write_all(fd, &h, sizeof h) || !write_all(fd, v.format.data(), v.format.size()) ||
        !write_all(fd, v.stored_type.data(), v.stored_type.size()) ||
        !write_all(fd, v.voxels.data(), v.voxels.size() * sizeof(float)))
        ::_exit(3);  // the parent reports a child without a result
}

// The child: default dispositions for the signals a crash raises (a sanitizer's or a fuzzer's
// handler would report the crash as the parent's), quiet standard streams, and _exit so that
// nothing of the parent's (buffered output, atexit handlers) runs twice.
[[noreturn]] void run_child(int result_fd, const fs::path& temp,
                            const std::function<RawVolume()>& read) {
    for (int s : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGTRAP, SIGINT, SIGTERM, SIGPIPE})
        ::signal(s, SIG_DFL);
    if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
        ::dup2(null, STDOUT_FILENO);
        ::dup2(null, STDERR_FILENO);
    }
    ::setenv("TMPDIR", temp.c_str(), 1);
    try {
        write_volume(result_fd, read());
    } catch (const InputError& e) {
        write_failure(result_fd, kInputError, e.what());
    } catch (const IoError& e) {
        write_failure(result_fd, kIoError, e.what());
    } catch (const std::bad_alloc&) {
        write_failure(result_fd, kOutOfMemory, "");
    } catch (const std::exception& e) {
        write_failure(result_fd, kOtherError, e.what());
    } catch (...) {
        write_failure(result_fd, kOtherError, "an unknown exception");
    }
    ::_exit(0);
}

// Waits for the child, polling the cancellation flag: Ctrl-C reaches the child too (same
// process group), but a request made otherwise (the Python module, the watchdog) would not.
int wait_for(pid_t child) {
    int status = 0;
    for (;;) {
        const pid_t r = ::waitpid(child, &status, WNOHANG);
        if (r == child) return status;
        if (r < 0 && errno != EINTR)
            throw IoError(std::string("lost the DICOM reader process: ") + std::strerror(errno));
        if (cancel_requested()) {
            ::kill(child, SIGKILL);
            while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
            }
            throw_if_cancelled();
        }
        const timespec pause{0, 2'000'000};  // 2 ms
        ::nanosleep(&pause, nullptr);
    }
}

std::string signal_name(int s) {
    const char* abbrev = ::sigabbrev_np(s);
    return abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(s);
}

RawVolume read_result(int fd, const fs::path& input) {
    const std::string where = quoted_source(input);
    ResultHeader h;
    if (!read_all(fd, 0, &h, sizeof h) || h.magic != kMagic)
        throw InputError(where +
                         ": the DICOM reader (GDCM) ended without a result; expected a "
                         "DICOM series it can read");
    auto text = [&](std::uint64_t offset, std::uint64_t bytes) {
        std::string s(bytes, '\0');
        if (bytes > (std::uint64_t{1} << 20) || !read_all(fd, offset, s.data(), s.size()))
            throw IoError(where + ": the DICOM reader's result is cut short");
        return s;
    };
    const std::uint64_t after = sizeof h;
    switch (h.outcome) {
        case kVolume: break;
        case kInputError: throw InputError(text(after, h.text_bytes));
        case kIoError: throw IoError(text(after, h.text_bytes));
        case kOutOfMemory: throw std::bad_alloc();
        default: throw InputError(where + ": " + text(after, h.text_bytes));
    }
    RawVolume v;
    v.format = text(after, h.format_bytes);
    v.stored_type = text(after + h.format_bytes, h.stored_bytes);
    for (int d = 0; d < 3; ++d) {
        v.size[static_cast<std::size_t>(d)] = h.size[d];
        v.spacing[static_cast<std::size_t>(d)] = h.spacing[d];
        v.origin[static_cast<std::size_t>(d)] = h.origin[d];
    }
    for (std::size_t i = 0; i < 9; ++i) v.direction[i] = h.direction[i];
    v.voxels.resize(h.voxel_count);
    if (!read_all(fd, after + h.format_bytes + h.stored_bytes, v.voxels.data(),
                  v.voxels.size() * sizeof(float)))
        throw IoError(where + ": the DICOM reader's result is cut short");
    return v;
}

}  // namespace

RawVolume read_in_child(const fs::path& input, const std::function<RawVolume()>& read) {
    const Descriptor result(::memfd_create("glint-dicom-volume", MFD_CLOEXEC));
    if (result.get() < 0)
        throw IoError(quoted_source(input) +
                      ": cannot make a memory file for the DICOM reader: " + std::strerror(errno));
    const ChildTemp temp;
    finish_background_loads();  // no other thread inside dlopen while the child is made
    const pid_t child = ::fork();
    if (child < 0)
        throw IoError(quoted_source(input) +
                      ": cannot start the DICOM reader process: " + std::strerror(errno));
    if (child == 0) run_child(result.get(), temp.path(), read);
    const int status = wait_for(child);
    if (WIFSIGNALED(status))
        throw InputError(quoted_source(input) + ": the DICOM reader (GDCM) crashed on it (" +
                         signal_name(WTERMSIG(status)) +
                         ", in a child process: nothing else was affected); expected a DICOM "
                         "series it can read");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw InputError(quoted_source(input) +
                         ": the DICOM reader (GDCM) stopped with exit code " +
                         std::to_string(WEXITSTATUS(status)) +
                         " (in a child process); expected a DICOM series it can read");
    return read_result(result.get(), input);
}

}  // namespace glint::detail
