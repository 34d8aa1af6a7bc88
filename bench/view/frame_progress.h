#pragma once
// The bake's progress bar (gusuku_bake/bake_progress.h) for frames: on a terminal one line redrawn, in a log a
// line every 10 %; fraction done, frames, elapsed and time left. Header-only: the session library and gusuku-view
// both include it.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "gusuku_bake/bake_progress.h"

namespace gusuku::view {

class FrameProgress {
public:
    /// `label`: what a frame is ("frame", "traced").
    FrameProgress(size_t total, bool enabled, std::string label = "frame")
        : total_(std::max<size_t>(total, 1)), enabled_(enabled), is_terminal_(isatty(STDERR_FILENO) != 0),
          label_(std::move(label)) {}

    /// `done` frames of the total are finished.
    void advance(size_t done) {
        if (!enabled_) return;
        const double fraction = double(done) / double(total_);
        const bool last = done == total_;
        if (!is_terminal_) {
            const int decile = int(fraction * 10.0);
            if (decile == last_decile_) return;
            last_decile_ = decile;
        }
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        const double left = done > 0 ? elapsed / double(done) * double(total_ - done) : NAN;
        constexpr int kBarWidth = 24;
        const int filled = int(std::lround(fraction * kBarWidth));
        std::string bar(size_t(filled), '#');
        bar.append(size_t(kBarWidth - filled), '.');
        std::fprintf(stderr, "%s[%s] %5.1f%%  %s %zu/%zu  elapsed %s  left %s%s", is_terminal_ ? "\r" : "",
                     bar.c_str(), fraction * 100.0, label_.c_str(), done, total_,
                     bake::formatDuration(elapsed).c_str(), bake::formatDuration(left).c_str(),
                     (last || !is_terminal_) ? "\n" : "");
        std::fflush(stderr);
    }

private:
    size_t total_;
    bool enabled_, is_terminal_;
    std::string label_;
    int last_decile_ = -1;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace gusuku::view
