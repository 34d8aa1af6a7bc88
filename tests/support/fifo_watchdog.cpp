#include "fifo_watchdog.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace gusuku::testing {

bool fifoWasOpenedDuring(const std::string& fifo, const std::function<void()>& action) {
    std::atomic<bool> done{false}, opened{false};
    std::thread watchdog([&] {
        while (!done) {
            // A non-blocking open for writing fails (ENXIO) unless some reader has the FIFO open.
            const int descriptor = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (descriptor >= 0) {
                opened = true;
                close(descriptor);  // the reader sees end-of-file
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    });
    try {
        action();
    } catch (...) {
        done = true;
        watchdog.join();
        throw;
    }
    done = true;
    watchdog.join();
    return opened;
}

bool makeFifo(const std::string& path) { return mkfifo(path.c_str(), 0600) == 0; }

}  // namespace gusuku::testing
