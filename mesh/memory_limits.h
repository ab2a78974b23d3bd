// Words for running out of memory: what limits this process, so that an out-of-memory end
// says how big the room was (issue 23: "out of memory as one line saying what was being done
// and how big it was"), and Embree's error codes in words.
#pragma once

#include <string>

namespace glint {

/// "address space limited to 600 MiB (ulimit -v), 23.4 GiB of memory on this machine"; the
/// first part only where a limit is set.
[[nodiscard]] std::string memory_limits_text();

/// The DeviceError message for an Embree device that could not be made: `code` is
/// rtcGetDeviceError(nullptr), given as an int so that this header needs no Embree.
[[nodiscard]] std::string embree_device_failure(int code);

}  // namespace glint
