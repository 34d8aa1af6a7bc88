// The tools' command-line reader: every form of an option, every refusal, and the messages a user reads.

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/tools/command_line.h"

namespace gusuku {
namespace {

std::string usageMessage(const std::function<void()>& parse) {
    try {
        parse();
    } catch (const UsageError& error) {
        return error.what();
    }
    return "(no error)";
}

TEST(CommandLine, ReadsValuesInEveryForm) {
    CommandLine line("tool", {"site.json", "--samples", "64", "--output=out", "-q", "--lat", "-33.5", "extra"});
    EXPECT_FALSE(line.helpRequested());
    EXPECT_EQ(line.integer("--samples", 1, 1000), 64);
    EXPECT_EQ(line.text("--output", "-o"), "out");
    EXPECT_TRUE(line.flag("--quiet", "-q"));
    EXPECT_DOUBLE_EQ(*line.number("--lat", -90, 90), -33.5);  // a negative number is a value, not an option
    EXPECT_FALSE(line.text("--absent").has_value());
    EXPECT_FALSE(line.flag("--absent"));
    EXPECT_EQ(line.positionals(), (std::vector<std::string>{"site.json", "extra"}));
    EXPECT_NO_THROW(line.finish());
}

TEST(CommandLine, LastValueWinsAndAliasesCount) {
    CommandLine line("tool", {"-o", "first", "--output", "second"});
    EXPECT_EQ(line.text("--output", "-o"), "second");
    EXPECT_NO_THROW(line.finish());
}

TEST(CommandLine, HelpIsAFlag) {
    CommandLine line("tool", {"x", "-h"});
    EXPECT_TRUE(line.helpRequested());
}

TEST(CommandLine, RefusalsNameTheProgramTheOptionAndTheProblem) {
    EXPECT_EQ(usageMessage([] { CommandLine("gusuku-bake sun", {"--lat", "200"}).number("--lat", -90, 90); }),
              "gusuku-bake sun: --lat: 200 is outside [-90, 90]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--lat", "nan"}).number("--lat", -90, 90); }),
              "t: --lat: 'nan' is not a finite number in [-90, 90]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--lat", "12abc"}).number("--lat", -90, 90); }),
              "t: --lat: '12abc' is not a finite number in [-90, 90]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--samples", "1.5"}).integer("--samples", 1, 100); }),
              "t: --samples: '1.5' is not an integer in [1, 100]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--samples", "0"}).integer("--samples", 1, 100); }),
              "t: --samples: 0 is outside [1, 100]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--samples", "99999999999999999999"}).integer("--samples", 1, 9); }),
              "t: --samples: '99999999999999999999' is not an integer in [1, 9]");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--output"}).text("--output"); }), "t: --output: needs a value");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--output", "--force"}).text("--output"); }),
              "t: --output: needs a value");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--force=yes"}).flag("--force"); }),
              "t: --force: takes no value, got 'yes'");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--mode", "fast"}).choice("--mode", {"auto", "cosine", "mis"}); }),
              "t: --mode: 'fast' is not auto, cosine or mis");
    EXPECT_EQ(usageMessage([] {
                  CommandLine line("t", {"--frobnicate"});
                  line.positionals();
                  line.finish();
              }),
              "t: unknown option '--frobnicate' (see --help)");
}

TEST(CommandLine, ChoiceReturnsTheIndexGiven) {
    CommandLine line("t", {"--sky-sampling", "mis"});
    EXPECT_EQ(line.choice("--sky-sampling", {"auto", "cosine", "mis"}), 2u);
}

TEST(CommandLine, EverythingAfterADoubleDashIsPositional) {
    CommandLine line("t", {"--quiet", "--", "--not-an-option", "-x"});
    EXPECT_TRUE(line.flag("--quiet"));
    EXPECT_EQ(line.positionals(), (std::vector<std::string>{"--not-an-option", "-x"}));
    EXPECT_NO_THROW(line.finish());
}

}  // namespace
}  // namespace gusuku
