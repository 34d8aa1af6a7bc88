// How gusuku-bake's subcommands read their command lines (see readCommandLine in commands.h).
#include <cstdio>

#include "commands.h"
#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"

namespace gusuku::bake_cli {

std::optional<int> readCommandLine(const std::string& program, const std::vector<std::string>& args,
                                   const CommandHelp& help, bool usage_after_bad_usage,
                                   const std::function<void(CommandLine&)>& parse) {
    const std::string usage = formatHelp(help);
    try {
        CommandLine line(program, args);
        line.useOptionTable(help.options);
        if (line.helpRequested()) {
            std::printf("%s", usage.c_str());
            return 0;
        }
        parse(line);
        return std::nullopt;
    } catch (const OptionValueError& error) {
        // A bad value is bad input (exit 1, like a bad site.json), not a misuse of the command.
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    } catch (const UsageError& error) {
        if (usage_after_bad_usage) std::fprintf(stderr, "%s\n\n%s", error.what(), usage.c_str());
        else std::fprintf(stderr, "%s\n", error.what());
        return 2;
    }
}

}  // namespace gusuku::bake_cli
