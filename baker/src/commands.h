#pragma once
// The gusuku-bake subcommands. Each takes the arguments after its name and returns the process exit code
// (0 ok, 1 bad input or failure, 2 bad usage). Each prints its own --help.

#include <string>
#include <vector>

namespace gusuku::bake_cli {

int runSunCommand(const std::vector<std::string>& args);       // cmd_sun.cpp
int runSampleCommand(const std::vector<std::string>& args);    // cmd_sample.cpp
int runBakeCommand(const std::vector<std::string>& args);      // cmd_bake.cpp
int runConvergeCommand(const std::vector<std::string>& args);  // cmd_converge.cpp
int runCheckCommand(const std::vector<std::string>& args);     // cmd_check.cpp: validate site.json and load all

}  // namespace gusuku::bake_cli
