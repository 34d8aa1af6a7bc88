#include "bake_stop_signals.h"

#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <ctime>
#include <optional>

namespace gusuku::bake_cli {

namespace {

// How often the signal thread wakes without a signal, to keep the deadline and to see the bake finish.
constexpr long kWakeNanoseconds = 20'000'000;

}  // namespace

BakeStopSignals::BakeStopSignals(const std::string& output_dir) {
    setup_message_ = "gusuku-bake: interrupted before tracing began; nothing was traced. Run the same command "
                     "again to bake.\n";
    packing_message_ = "gusuku-bake: interrupted while writing the runtime pack; the bake set in " + output_dir +
                       " is complete. Run the same command again (or gusuku-bake pack) to write the pack.\n";
    const std::string resume = " The checkpoints in " + output_dir + "/.checkpoint hold the work up to the last "
                               "one. Run the same command again to resume.\n";
    deadline_message_ = "gusuku-bake: interrupted; stopped without waiting for the current step." + resume;
    second_signal_message_ = "gusuku-bake: interrupted twice; stopped at once." + resume;
    stderr_copy_ = dup(STDERR_FILENO);
    sigemptyset(&stop_signals_);
    sigaddset(&stop_signals_, SIGINT);
    sigaddset(&stop_signals_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals_, &previous_mask_);
    signal_thread_ = std::thread([this] { takeSignals(); });
}

BakeStopSignals::~BakeStopSignals() {
    finished_ = true;
    signal_thread_.join();
    pthread_sigmask(SIG_SETMASK, &previous_mask_, nullptr);
    if (stderr_copy_ >= 0) close(stderr_copy_);
}

std::function<bool()> BakeStopSignals::poll() {
    return [this] {
        Phase setup = Phase::kSetup;
        phase_.compare_exchange_strong(setup, Phase::kTracing);
        return stop_requested_.load();
    };
}

bool BakeStopSignals::beginPacking() {
    phase_ = Phase::kPacking;
    return stop_requested_.load();
}

void BakeStopSignals::writeAndExit(const std::string& message) const {
    const ssize_t written =
        write(stderr_copy_ >= 0 ? stderr_copy_ : STDERR_FILENO, message.data(), message.size());
    (void)written;
    _exit(130);  // no destructors: another thread may be inside the driver; the checkpoints are already on disk
}

void BakeStopSignals::takeSignals() {
    using Clock = std::chrono::steady_clock;
    std::optional<Clock::time_point> first_signal;
    while (!finished_) {
        const timespec wake{0, kWakeNanoseconds};
        const int signal_number = sigtimedwait(&stop_signals_, nullptr, &wake);
        if (signal_number == SIGINT || signal_number == SIGTERM) {
            const Phase phase = phase_;
            if (phase == Phase::kSetup) writeAndExit(setup_message_);
            if (phase == Phase::kPacking) writeAndExit(packing_message_);
            if (first_signal) writeAndExit(second_signal_message_);
            first_signal = Clock::now();
            stop_requested_ = true;
        }
        if (first_signal && !finished_ && phase_ != Phase::kPacking &&
            std::chrono::duration<double>(Clock::now() - *first_signal).count() > kStopDeadlineSeconds)
            writeAndExit(deadline_message_);
    }
}

}  // namespace gusuku::bake_cli
