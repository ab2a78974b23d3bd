#include "tools/progress.h"

#include "mesh/cancel.h"
#include "tools/command.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>

namespace glint::cli {

ProgressBar::ProgressBar(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      enabled_(!global_flags().quiet && !global_flags().json && ::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
    if (enabled_ && !finished_) std::fputc('\n', stderr);
}

void ProgressBar::update(std::size_t done) {
    throw_if_cancelled();
    if (!enabled_) return;
    done = std::min(done, total_);
    const auto now = std::chrono::steady_clock::now();
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
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
    const double eta = rate > 0 && done < total_ ? static_cast<double>(total_ - done) / rate : 0.0;
    constexpr int kWidth = 30;
    const int filled =
        total_ ? static_cast<int>(kWidth * static_cast<double>(done) / static_cast<double>(total_))
               : kWidth;
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = '\0';
    std::fprintf(stderr, "\r%s [%s] %zu/%zu  %.1f/s  %s %.0fs ", label_.c_str(), bar, done, total_,
                 rate, final ? "took" : "eta", final ? elapsed : eta);
    std::fflush(stderr);
}

}  // namespace glint::cli
