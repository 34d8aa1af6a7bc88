#include "bake_stop_signals.h"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <optional>

namespace gusuku::bake_cli {

namespace {

volatile std::sig_atomic_t g_stop_requested = 0;   // signals received (capped at 2)
volatile std::sig_atomic_t g_tracing_started = 0;  // the bake has polled: stops are cooperative from here
// Built before the handlers are installed: a handler may only write(2) and _exit.
std::string g_setup_message;
std::string g_deadline_message;

[[noreturn]] void writeAndExit(const std::string& message) {
    const ssize_t written = write(STDERR_FILENO, message.data(), message.size());
    (void)written;
    _exit(130);
}

void onStopSignal(int) {
    if (g_tracing_started == 0) writeAndExit(g_setup_message);
    if (g_stop_requested != 0) writeAndExit(g_deadline_message);  // a second signal: at once
    g_stop_requested = 1;
}

}  // namespace

BakeStopSignals::BakeStopSignals(const std::string& output_dir) {
    g_stop_requested = 0;
    g_tracing_started = 0;
    g_setup_message = "gusuku-bake: interrupted before tracing began; nothing was traced. Run the same command "
                      "again to bake.\n";
    g_deadline_message = "gusuku-bake: interrupted; stopped without waiting for the current step. The checkpoints "
                         "in " + output_dir + "/.checkpoint hold the work up to the last one. Run the same command "
                         "again to resume.\n";
    std::signal(SIGINT, onStopSignal);
    std::signal(SIGTERM, onStopSignal);
    watch_ = std::thread([this] { watchDeadline(); });
}

BakeStopSignals::~BakeStopSignals() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    finished_ = true;
    watch_.join();
}

std::function<bool()> BakeStopSignals::poll() {
    return [] {
        g_tracing_started = 1;
        return g_stop_requested != 0;
    };
}

void BakeStopSignals::watchDeadline() {
    using Clock = std::chrono::steady_clock;
    std::optional<Clock::time_point> stop_seen;
    while (!finished_) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (g_stop_requested == 0) continue;
        if (!stop_seen) stop_seen = Clock::now();
        if (std::chrono::duration<double>(Clock::now() - *stop_seen).count() > kStopDeadlineSeconds && !finished_)
            writeAndExit(g_deadline_message);
    }
}

}  // namespace gusuku::bake_cli
