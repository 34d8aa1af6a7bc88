#pragma once
// Tests that a loader refuses a FIFO by its type without opening it. Opening a FIFO for reading blocks until a
// writer appears, so a loader that did open it would hang the test; the watchdog here unblocks such a reader
// (the test then fails on its result instead of hanging).

#include <functional>
#include <string>

namespace gusuku::testing {

/// Runs `action` while a watchdog thread opens and closes the write end of `fifo` whenever a reader holds it.
/// Returns whether anything opened `fifo` for reading meanwhile.
bool fifoWasOpenedDuring(const std::string& fifo, const std::function<void()>& action);

/// Creates a FIFO at `path` (mkfifo, mode 0600); false on failure.
bool makeFifo(const std::string& path);

}  // namespace gusuku::testing
