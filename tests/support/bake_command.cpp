#include "bake_command.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "gpu_test_support.h"

namespace gusuku::testing {

namespace {

std::string readText(const std::filesystem::path& path) {
    std::ifstream stream(path);
    std::ostringstream text;
    text << stream.rdbuf();
    return text.str();
}

std::string quoted(const std::string& argument) {
    if (argument.find('\'') != std::string::npos)
        throw std::invalid_argument("runBakeCommand: argument holds a single quote: " + argument);
    return "'" + argument + "'";
}

}  // namespace

CommandResult runBakeCommand(const std::vector<std::string>& args, const std::string& scratch_dir) {
    const std::filesystem::path out = std::filesystem::path(scratch_dir) / "command.out";
    const std::filesystem::path err = std::filesystem::path(scratch_dir) / "command.err";
    std::string command = quoted(bakeExecutablePath());
    for (const std::string& argument : args) command += " " + quoted(argument);
    command += " >" + quoted(out.string()) + " 2>" + quoted(err.string());
    const int status = std::system(command.c_str());
    CommandResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.stdout_text = readText(out);
    result.stderr_text = readText(err);
    return result;
}

}  // namespace gusuku::testing
