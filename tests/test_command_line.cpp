// The tools' command-line reader: every form of an option, every refusal, and the messages a user reads.

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gusuku/tools/command_line.h"
#include "gusuku/tools/option_table.h"

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

TEST(CommandLine, AnOptionGivenTwiceInAnyFormIsRefused) {
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"-o", "first", "--output", "second"}).text("--output", "-o"); }),
              "t: --output: given 2 times ('first', 'second'); give it once");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--samples=8", "--samples", "8"}).integer("--samples", 1, 9); }),
              "t: --samples: given 2 times ('8', '8'); give it once");
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--force", "--force"}).flag("--force"); }),
              "t: --force: given twice; give it once");
    CommandLine alias_once("t", {"-o", "only"});
    EXPECT_EQ(alias_once.text("--output", "-o"), "only");
}

TEST(CommandLine, NumbersAreDecimalOnly) {
    for (const char* decimal : {"1", "-70.5", "+0.25", ".5", "5.", "1e-3", "2.5E+2"})
        EXPECT_TRUE(gusuku::parseDecimal(decimal).has_value()) << decimal;
    EXPECT_DOUBLE_EQ(*gusuku::parseDecimal("2.5E+2"), 250.0);
    for (const char* not_decimal : {"0x1", "0X1p3", "inf", "-infinity", "nan", " 1", "1 ", "", ".", "-", "1e",
                                    "1e+", "1.2.3", "1e400"})
        EXPECT_FALSE(gusuku::parseDecimal(not_decimal).has_value()) << not_decimal;
    EXPECT_EQ(usageMessage([] { CommandLine("t", {"--cover", "0x1"}).number("--cover", 0, 1); }),
              "t: --cover: '0x1' is not a finite number in [0, 1]");
}

TEST(CommandLine, LongValuesAreCutInMessages) {
    const std::string long_value(100000, '9');
    const std::string message =
        usageMessage([&] { CommandLine("t", {"--mode", long_value}).choice("--mode", {"a", "b"}); });
    EXPECT_EQ(message, "t: --mode: '" + long_value.substr(0, 60) + "...' (100000 characters) is not a or b");
    EXPECT_EQ(gusuku::quotedForMessage(std::string(80, 'x')), "'" + std::string(80, 'x') + "'");
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

// With its option table bound, a command reads only the options its --help lists, and reads every one of them:
// a parser and a help that name different options fail on the first run of the command.
TEST(OptionTable, AnOptionTheHelpDoesNotListIsAProgrammingError) {
    const std::vector<OptionHelp> table = {{"--samples", "", "N", "samples", "256"}};
    CommandLine line("t", {"--samples", "8"});
    line.useOptionTable(table);
    EXPECT_EQ(line.integer("--samples", 1, 9), 8);
    EXPECT_THROW(line.flag("--quiet"), std::logic_error);
    EXPECT_NO_THROW(line.flag("--help"));  // every command's, in no table
}

TEST(OptionTable, AnOptionTheParserNeverReadsIsAProgrammingError) {
    const std::vector<OptionHelp> table = {{"--samples", "", "N", "samples", "256"}, {"--quiet", "", "", "quiet", ""}};
    CommandLine line("t", {});
    line.useOptionTable(table);
    line.integer("--samples", 1, 9);
    EXPECT_THROW(line.finish(), std::logic_error);
    line.flag("--quiet");
    EXPECT_NO_THROW(line.finish());
}

// The layout tests/check_docs_option_tables.py reads back: option blocks at two spaces, the meaning beside them and
// the default on a last line of its own.
TEST(OptionTable, HelpPrintsEachOptionWithItsDefaultOnItsOwnLine) {
    CommandHelp help;
    help.usage = "usage: t SITE";
    help.options = {{"--output", "-o", "DIR", "the folder", ""}, {"--samples", "", "N", "samples a texel", "256"}};
    help.notes = "Exit status: 0 ok.";
    EXPECT_EQ(formatHelp(help),
              "usage: t SITE\n"
              "\n"
              "options:\n"
              "  -o, --output DIR  the folder\n"
              "  --samples N       samples a texel\n"
              "                    default: 256\n"
              "\n"
              "Exit status: 0 ok.\n");
}

}  // namespace
}  // namespace gusuku
