#pragma once
// One option table per command of gusuku's tools: the table prints the command's --help (formatHelp) and tells
// its CommandLine which options it may read (CommandLine::useOptionTable), so the help, the parser and the docs'
// option tables (tests/check_docs_option_tables.py compares them) cannot drift apart. Each default is written
// from the constant the parser falls back to (a struct's default member, a named constant), never typed twice.

#include <string>
#include <vector>

namespace gusuku {

/// One option as --help shows it.
struct OptionHelp {
    std::string name;           ///< the long form, "--samples"
    std::string alias;          ///< a one-letter form, "-o", or empty
    std::string value;          ///< the value's placeholder, "N"; empty for a flag
    std::string meaning;        ///< what it does, one paragraph (wrapped by formatHelp)
    std::string default_value;  ///< what applies when it is absent; empty when nothing does (required, flag off)
};

/// A command's help: the usage lines, the text before the options, the options, the text after them.
struct CommandHelp {
    std::string usage;        ///< "usage: gusuku-bake bake SITE.json -o DIR [options]" (one or more lines)
    std::string description;  ///< paragraphs, as written (may be empty)
    std::vector<OptionHelp> options;
    std::string notes;        ///< paragraphs after the options (exit status, environment), as written
};

/// The --help text: usage, description, then "options:" with one block per option, the option column
/// ("  -o, --output DIR"), its meaning wrapped beside it and, where it has one, a last line "default: VALUE"
/// in the meaning column; then the notes. Every block starts with "  -" at column 0 and its other lines are
/// indented further, so a reader (the docs test) can take the table back from the text.
std::string formatHelp(const CommandHelp& help);

/// "%g"-style text of a number for a default ("0.05", "69.2", "1024"), as a user would type it.
std::string defaultNumber(double value);

}  // namespace gusuku
