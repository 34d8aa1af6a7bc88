#include "gusuku_bake/bake_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gusuku::bake {

std::string formatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0.0) return "--";
    const long total = std::lround(seconds);
    char text[32];
    if (total >= 3600)
        std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", total / 3600, (total / 60) % 60, total % 60);
    else
        std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
    return text;
}

BakeProgress::BakeProgress(double total_work, bool enabled)
    : total_work_(std::max(total_work, 1.0)),
      enabled_(enabled),
      is_terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void BakeProgress::addResumedWork(double work) {
    resumed_work_ += work;
    done_work_ += work;
}

double BakeProgress::secondsElapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double BakeProgress::raysPerSecond() const {
    const double seconds = secondsElapsed();
    return seconds > 0.0 ? double(rays_) / seconds : 0.0;
}

void BakeProgress::advance(const std::string& label, uint32_t samples_done, uint32_t samples_total,
                           double work_done, uint64_t rays, double trace_seconds) {
    done_work_ += work_done;
    traced_work_ += work_done;
    traced_seconds_ += trace_seconds;
    rays_ += rays;
    label_ = label;
    samples_done_ = samples_done;
    samples_total_ = samples_total;
    draw(false);
}

double BakeProgress::secondsLeft() const {
    if (traced_work_ <= 0.0 || traced_seconds_ <= 0.0) return NAN;
    return std::max(0.0, total_work_ - done_work_) * traced_seconds_ / traced_work_;
}

void BakeProgress::finish() {
    // A log (not a terminal) already has its 100 % line when the last advance completed the work.
    if (!is_terminal_ && last_decile_ == 10) return;
    draw(true);
}

void BakeProgress::draw(bool final_line) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    const double fraction = std::clamp(done_work_ / total_work_, 0.0, 1.0);
    if (!final_line) {
        if (is_terminal_) {
            if (std::chrono::duration<double>(now - last_draw_).count() < 0.2) return;
        } else {
            const int decile = int(fraction * 10.0);
            if (decile == last_decile_) return;
            last_decile_ = decile;
        }
    }
    last_draw_ = now;
    const double elapsed = secondsElapsed();
    const double seconds_left = secondsLeft();
    constexpr int kBarWidth = 24;
    const int filled = int(std::lround(fraction * kBarWidth));
    std::string bar(size_t(filled), '#');
    bar.append(size_t(kBarWidth - filled), '.');
    std::fprintf(stderr, "%s[%s] %5.1f%%  %-24s %5u/%u spp  %6.2f Mrays/s  elapsed %s  left %s%s",
                 is_terminal_ ? "\r" : "", bar.c_str(), fraction * 100.0, label_.c_str(), samples_done_,
                 samples_total_, raysPerSecond() / 1e6, formatDuration(elapsed).c_str(),
                 final_line ? "0:00" : formatDuration(seconds_left).c_str(),
                 (final_line || !is_terminal_) ? "\n" : "");
    std::fflush(stderr);
}

}  // namespace gusuku::bake
