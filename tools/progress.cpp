#include "tools/progress.h"

#include "mesh/cancel.h"
#include "mesh/stopwatch.h"
#include "tools/command.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <mutex>
#include <utility>

namespace glint::cli {

namespace {

using Clock = std::chrono::steady_clock;

bool progress_shown() {
    return !global_flags().quiet && !global_flags().json && ::isatty(STDERR_FILENO);
}

// "[#######.......................]": `done` of `total` in 30 characters.
std::string bar_text(std::size_t done, std::size_t total) {
    constexpr int kWidth = 30;
    const int filled =
        total ? static_cast<int>(kWidth * static_cast<double>(done) / static_cast<double>(total))
              : kWidth;
    std::string bar(kWidth, '.');
    std::fill_n(bar.begin(), std::clamp(filled, 0, kWidth), '#');
    return "[" + bar + "]";
}

// Items per second and the seconds left at that rate (0 once done).
std::pair<double, double> rate_and_eta(std::size_t done, std::size_t total, double elapsed) {
    const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = rate > 0 && done < total ? static_cast<double>(total - done) / rate : 0.0;
    return {rate, eta};
}

}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      enabled_(progress_shown()),
      start_(Clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
    if (enabled_ && !finished_) std::fputc('\n', stderr);
}

void ProgressBar::update(std::size_t done) {
    throw_if_cancelled();
    if (!enabled_) return;
    done = std::min(done, total_);
    const auto now = Clock::now();
    if (done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(done, false);
}

void ProgressBar::finish() {
    if (!enabled_ || finished_) return;
    draw(total_, true);
    std::fputc('\n', stderr);
    finished_ = true;
}

void ProgressBar::draw(std::size_t done, bool final) {
    const double elapsed = seconds_since(start_);
    const auto [rate, eta] = rate_and_eta(done, total_, elapsed);
    std::fprintf(stderr, "\r%s %s %zu/%zu  %.1f/s  %s %.0fs ", label_.c_str(),
                 bar_text(done, total_).c_str(), done, total_, rate, final ? "took" : "eta",
                 final ? elapsed : eta);
    std::fflush(stderr);
}

StageProgress::StageProgress(std::string prefix)
    : enabled_(progress_shown()), prefix_(std::move(prefix)) {
    if (!prefix_.empty()) prefix_ += ": ";
}

// A run that stopped (an error, a signal) leaves its stage's line as it was, ended.
StageProgress::~StageProgress() {
    if (enabled_ && !name_.empty()) std::fputc('\n', stderr);
}

namespace {
std::mutex g_last_stage_mutex;
std::string g_last_stage;  // guarded by g_last_stage_mutex
}  // namespace

std::string last_stage() {
    const std::lock_guard lock(g_last_stage_mutex);
    return g_last_stage;
}

void StageProgress::stage(std::string_view name) {
    finish();
    name_ = name;
    {
        const std::lock_guard lock(g_last_stage_mutex);
        g_last_stage = prefix_ + std::string(name);
    }
    done_ = total_ = 0;
    start_ = last_draw_ = Clock::now();
    if (enabled_) draw(false);
}

void StageProgress::items(std::size_t done, std::size_t total) {
    throw_if_cancelled();
    if (!enabled_ || name_.empty()) return;
    total_ = total;
    done_ = std::min(done, total);
    const auto now = Clock::now();
    if (done_ < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(false);
}

void StageProgress::finish() {
    if (name_.empty()) return;
    if (enabled_) {
        draw(true);
        std::fputc('\n', stderr);
        std::fflush(stderr);
    }
    name_.clear();
}

void StageProgress::listen(AnalysisObserver& observer) {
    observer.stage = [this, before = std::move(observer.stage)](std::string_view name) {
        if (before) before(name);
        stage(name);
    };
    observer.views = [this](std::size_t done, std::size_t total) { items(done, total); };
    observer.items = [this](std::size_t done, std::size_t total) { items(done, total); };
}

// "sweep        [#####.....] 90/180  21.3/s  eta 4s", "fit          ...", "fit          took
// 0.8s"; "\x1b[K" clears what a longer earlier draw left on the line.
void StageProgress::draw(bool final) {
    const double elapsed = seconds_since(start_);
    std::string counted;
    if (total_ > 0) {
        const auto [rate, eta] = rate_and_eta(done_, total_, elapsed);
        char b[96];
        std::snprintf(b, sizeof b, " %zu/%zu  %.1f/s", done_, total_, rate);
        counted = " " + bar_text(done_, total_) + b;
        if (!final) {
            std::snprintf(b, sizeof b, "  eta %.0fs", eta);
            counted += b;
        }
    }
    if (final) {
        char b[48];
        std::snprintf(b, sizeof b, "  took %.1fs", elapsed);
        counted += b;
    } else if (total_ == 0) {
        counted += " ...";
    }
    std::fprintf(stderr, "\r%s%-12s%s\x1b[K", prefix_.c_str(), name_.c_str(), counted.c_str());
    std::fflush(stderr);
}

}  // namespace glint::cli
