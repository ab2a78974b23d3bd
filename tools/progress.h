// Progress on stderr: shown only when stderr is a terminal and neither --quiet nor --json is
// given (both classes decide the same way).
#pragma once

#include "analysis/analysis.h"

#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

namespace glint::cli {

/// One bar for one counted task (glint render's views).
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

/// Progress through the stages of a run (load, fit, distance, sweep, decide, each export): a
/// line per stage, named the moment it starts (so the terminal is never blank while a stage
/// works), redrawn in place while its items count (a bar, the rate and an ETA), and closed
/// with the seconds it took. A stage that counts nothing has no ETA: its line says it runs.
class StageProgress {
  public:
    /// `prefix` goes before each line (a scenario's name).
    explicit StageProgress(std::string prefix = {});
    ~StageProgress();
    StageProgress(const StageProgress&) = delete;
    StageProgress& operator=(const StageProgress&) = delete;
    /// Closes the open stage's line and opens `name`'s.
    void stage(std::string_view name);
    /// Items done of `total` within the open stage; redraws at most ~10 times a second.
    /// \throw Cancelled once a signal asked to stop (as ProgressBar::update).
    void items(std::size_t done, std::size_t total);
    /// Closes the open stage's line.
    void finish();
    /// Hooks this onto an analysis' observer: its stages (after what `observer.stage` already
    /// does), its items and the sweep's views (the items of "sweep").
    void listen(AnalysisObserver& observer);

  private:
    void draw(bool final);
    bool enabled_;
    std::string prefix_;
    std::string name_;  ///< the open stage ("" when none)
    std::size_t done_ = 0;
    std::size_t total_ = 0;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
};

/// The stage a StageProgress of this process opened last ("" before any): words for an error
/// that ends a run, such as running out of memory ("while sweep"). Thread-safe.
[[nodiscard]] std::string last_stage();

}  // namespace glint::cli
