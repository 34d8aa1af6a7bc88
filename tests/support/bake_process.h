#pragma once
// Runs gusuku-bake as a child process the test can watch, signal and time out (runBakeCommand in
// bake_command.h waits without a limit, so a bake that hangs would hang the test).

#include <sys/types.h>

#include <string>
#include <vector>

namespace gusuku::testing {

/// Starts `gusuku-bake ARGS...` with stdout and stderr sent to stdout_path and stderr_path; returns its pid.
pid_t spawnBakeProcess(const std::vector<std::string>& args, const std::string& stdout_path = "/dev/null",
                       const std::string& stderr_path = "/dev/null");

/// Waits for the child. Returns its exit code, 128 + N when a signal N ended it, or kTimedOut after
/// SIGKILLing a child that was still running after timeout_seconds.
inline constexpr int kTimedOut = -2;
int waitBakeProcess(pid_t pid, double timeout_seconds);

/// Whole file as text ("" when missing).
std::string readTextFile(const std::string& path);

}  // namespace gusuku::testing
