#include "mesh/memory_limits.h"

#include <embree3/rtcore.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

namespace glint {

namespace {

std::string memory_text(double bytes) {
    char b[48];
    if (bytes >= 1073741824.0) std::snprintf(b, sizeof b, "%.1f GiB", bytes / 1073741824.0);
    else std::snprintf(b, sizeof b, "%.0f MiB", bytes / 1048576.0);
    return b;
}

}  // namespace

std::string memory_limits_text() {
    std::string text;
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        text = "address space limited to " + memory_text(static_cast<double>(limit.rlim_cur)) +
               " (ulimit -v), ";
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0)
        text += memory_text(static_cast<double>(pages) * static_cast<double>(page)) +
                " of memory on this machine";
    else text += "memory size unknown";
    return text;
}

std::string embree_device_failure(int code) {
    switch (static_cast<RTCError>(code)) {
        case RTC_ERROR_OUT_OF_MEMORY:
            return "cannot create an Embree device: out of memory (" + memory_limits_text() +
                   "); Embree reserves its thread pool and allocators up front";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "cannot create an Embree device: this CPU lacks the instructions Embree was "
                   "built for (SSE2 at least)";
        default:
            return "cannot create an Embree device (Embree error " + std::to_string(code) + ")";
    }
}

}  // namespace glint
