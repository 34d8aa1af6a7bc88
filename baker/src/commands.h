#pragma once
// The gusuku-bake subcommands. Each takes the arguments after its name and returns the process exit code
// (0 ok, 1 bad input or failure, 2 bad usage). Each prints its own --help.

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gusuku {
class CommandLine;
struct CommandHelp;  // gusuku/tools/option_table.h
}

namespace gusuku::bake_cli {

int runSunCommand(const std::vector<std::string>& args);       // cmd_sun.cpp
int runSampleCommand(const std::vector<std::string>& args);    // cmd_sample.cpp
int runBakeCommand(const std::vector<std::string>& args);      // cmd_bake.cpp
int runConvergeCommand(const std::vector<std::string>& args);  // cmd_converge.cpp
int runCheckCommand(const std::vector<std::string>& args);     // cmd_check.cpp: validate site.json and load all
int runMergeCommand(const std::vector<std::string>& args);     // cmd_merge.cpp: join partial bake sets
int runPackCommand(const std::vector<std::string>& args);      // cmd_pack.cpp: a bake set's runtime pack
int runExportCommand(const std::vector<std::string>& args);    // cmd_export.cpp: a glTF with a slot's lightmap
int runInitCommand(const std::vector<std::string>& args);      // cmd_init.cpp: a starter site.json and checklist
int runGeorefCommand(const std::vector<std::string>& args);    // cmd_georef.cpp: sfm_mesh from ground control points
int runPreviewCommand(const std::vector<std::string>& args);   // cmd_preview.cpp: placement pictures and checks

/// How every subcommand reads its command line (gusuku/tools/command_line.h), so that all behave alike. `parse` takes
/// the command's options and positionals from `line` and calls line.finish(); it throws UsageError for bad usage
/// and OptionValueError for a bad value; `line` reads only the options of `help`'s table (CommandLine::
/// useOptionTable). Returns nullopt when the command is to run, else its exit code: 0 after --help / -h printed
/// `help` (formatHelp) on stdout; 1 after a bad value and 2 after bad usage, each reported as the error's one line
/// on stderr ("gusuku-bake bake: --samples: 0 is outside [1, 1000000]"), followed by the help after bad usage when
/// usage_after_bad_usage.
std::optional<int> readCommandLine(const std::string& program, const std::vector<std::string>& args,
                                   const CommandHelp& help, bool usage_after_bad_usage,
                                   const std::function<void(CommandLine&)>& parse);  // read_command_line.cpp

}  // namespace gusuku::bake_cli
