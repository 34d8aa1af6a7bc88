// gusuku-bake's bake, check and sample commands read their command lines with the tools' shared reader
// (gusuku/tools/command_line.h, through readCommandLine in baker/src/commands.h): a bad value exits 1 with the
// reader's one line naming the option, bad usage exits 2, and nothing is opened or written before the command
// line is accepted. The reader's own messages are held to their texts in test_command_line.cpp; this holds the
// commands to the exit codes and messages of commands.h.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bake_command.h"
#include "gpu_test_support.h"

namespace {

namespace fs = std::filesystem;
using gusuku::testing::CommandResult;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Refusal {
    std::vector<std::string> args;
    int exit_code;
    std::string stderr_first_line;  // the whole of stderr unless the command prints its usage after it
};

class BakeCommandLine : public ::testing::Test {
protected:
    void SetUp() override { directory_ = gusuku::testing::makeTemporaryDirectory("gusuku-bake-command-line"); }
    CommandResult run(const std::vector<std::string>& args) {
        return gusuku::testing::runBakeCommand(args, directory_);
    }
    void expectRefused(const std::vector<Refusal>& refusals) {
        for (const Refusal& refusal : refusals) {
            const CommandResult result = run(refusal.args);
            const std::string command = refusal.args.front() + " " + refusal.args.back();
            EXPECT_EQ(result.exit_code, refusal.exit_code) << command << ": " << result.stderr_text;
            EXPECT_EQ(result.stderr_text.substr(0, result.stderr_text.find('\n')), refusal.stderr_first_line)
                << command;
            EXPECT_TRUE(result.stdout_text.empty()) << command << ": " << result.stdout_text;
        }
    }
    std::string directory_;
};

TEST_F(BakeCommandLine, BakeRefusesBadValuesWithOneAndBadUsageWithTwo) {
    const std::string out = directory_ + "/out";
    expectRefused({
        {{"bake", "site.json", "-o", out, "--samples", "0"}, 1,
         "gusuku-bake bake: --samples: 0 is outside [1, 1000000]"},
        {{"bake", "site.json", "--output=" + out, "--samples", "many"}, 1,
         "gusuku-bake bake: --samples: 'many' is not an integer in [1, 1000000]"},
        {{"bake", "site.json", "-o", out, "--fast"}, 2, "gusuku-bake bake: unknown option '--fast' (see --help)"},
        {{"bake", "a.json", "b.json", "-o", out}, 2, "gusuku-bake bake: one site.json only ('b.json' is extra)"},
        {{"bake", "site.json", "--quiet"}, 2, "gusuku-bake bake: needs SITE.json and -o BAKESET_DIR (see --help)"},
        {{"bake", "site.json", "-o"}, 2, "gusuku-bake bake: --output: needs a value"},
        {{"bake", "site.json", "-o", out, "--force=yes"}, 2, "gusuku-bake bake: --force: takes no value, got 'yes'"},
    });
    EXPECT_FALSE(fs::exists(out)) << "nothing is written before the command line is accepted";

    const CommandResult help = run({"bake", "--help"});
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_TRUE(contains(help.stdout_text, "usage: gusuku-bake bake SITE.json -o BAKESET_DIR")) << help.stdout_text;
}

TEST_F(BakeCommandLine, CheckTakesOneSite) {
    expectRefused({
        {{"check"}, 2, "gusuku-bake check: missing SITE_JSON (see --help)"},
        {{"check", "a.json", "b.json"}, 2, "gusuku-bake check: expected one site.json, got more (see --help)"},
        {{"check", "a.json", "--deep"}, 2, "gusuku-bake check: unknown option '--deep' (see --help)"},
    });
}

TEST_F(BakeCommandLine, SampleTakesOneFolderAndShowsItsUsageOnBadUsage) {
    const std::string a = directory_ + "/a", b = directory_ + "/b";
    expectRefused({
        {{"sample"}, 2, "gusuku-bake sample: DIR is missing"},
        {{"sample", a, b}, 2, "gusuku-bake sample: more than one DIR given ('" + a + "', '" + b + "')"},
    });
    EXPECT_TRUE(contains(run({"sample"}).stderr_text, "\n\nusage: gusuku-bake sample DIR [--force]\n"));
    EXPECT_FALSE(fs::exists(a));

    // A file where the folder should be is bad input, found once the command line was accepted.
    const std::string file = directory_ + "/file";
    std::ofstream(file) << "not a folder";
    expectRefused({{{"sample", "--force", file}, 1, "gusuku-bake sample: " + file + " exists and is not a directory"}});
}

}  // namespace
