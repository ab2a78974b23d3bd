// Wall time of a step, as report.json's timings and the progress bars give it.
#pragma once

#include <chrono>

namespace glint {

/// Seconds of the steady clock since `t0`.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace glint
