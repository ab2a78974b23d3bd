// A progress bar on stderr: shown only when stderr is a terminal and --quiet is off.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace glint::cli {

class ProgressBar {
  public:
    ProgressBar(std::string label, std::size_t total);
    ~ProgressBar();
    /// Sets the number of items done; redraws at most ~10 times a second.
    void update(std::size_t done);
    /// Changes the total (e.g. once a plan's size is known); `done` is clamped to it.
    void set_total(std::size_t total) { total_ = total; }
    /// Completes the line.
    void finish();

  private:
    void draw(std::size_t done, bool final);
    std::string label_;
    std::size_t total_;
    bool enabled_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace glint::cli
