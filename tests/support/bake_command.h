#pragma once
// Runs the built gusuku-bake executable as a user would, for tests of its command line.

#include <string>
#include <vector>

namespace gusuku::testing {

struct CommandResult {
    int exit_code = -1;  ///< -1 when the process did not exit normally (a signal)
    std::string stdout_text;
    std::string stderr_text;
};

/// Runs `gusuku-bake ARGS...` (each argument single-quoted for the shell, so it must not contain a single
/// quote) with stdout and stderr captured into files under `scratch_dir`; returns the exit code and both texts.
CommandResult runBakeCommand(const std::vector<std::string>& args, const std::string& scratch_dir);

}  // namespace gusuku::testing
