#pragma once
// One command-line reader for gusuku's tools (gusuku-bake's subcommands, gusuku-render, gusuku-bench), so
// that every option is parsed, range-checked and reported the same way. Options are GNU-style: `--name VALUE`
// or `--name=VALUE`, flags `--name`, an optional one-letter alias (`-o`); everything not starting with '-' is
// positional. Nothing here prints: errors are thrown as UsageError, whose message is one line
// "<program>: <option>: <problem>", and the caller prints it and exits 2.
//
// Use: construct, take every option the tool knows (flag, text, integer, number, choice), then positionals(),
// then finish(), which refuses anything left over (unknown options). An option given twice is refused: a
// command line that says two things says neither.

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gusuku/formats/input_error.h"  // quotedForMessage

namespace gusuku {

struct OptionHelp;  // gusuku/tools/option_table.h

/// A number in plain decimal notation: an optional sign, digits with an optional fraction, an optional exponent
/// ("-70.5", "1e-3", ".5"). Nothing else: not hexadecimal ("0x1", which strtod reads as 1), "inf", "nan", nor
/// leading or trailing spaces. nullopt when the text is not one, or is beyond double's range.
std::optional<double> parseDecimal(const std::string& text);

/// quotedForMessage (gusuku/formats/input_error.h) quotes values in its messages.

/// A bad command line: an unknown option, a missing value, an unexpected argument. Conventionally exit 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// An option whose value is malformed or out of range (a latitude of 200): bad input rather than bad usage,
/// which tools may report with exit code 1. A UsageError, so callers that do not care catch one type.
class OptionValueError : public UsageError {
public:
    using UsageError::UsageError;
};

class CommandLine {
public:
    /// program: what messages start with ("gusuku-bake bake"); arguments: those after the program/subcommand.
    CommandLine(std::string program, std::vector<std::string> arguments);

    /// Binds the command's option table (gusuku/tools/option_table.h), the one its --help prints: from then on
    /// reading an option the table lacks, or finish() with a table option never read, throws std::logic_error
    /// (a programming error, caught by any test that runs the command), so help and parser name the same options.
    void useOptionTable(const std::vector<OptionHelp>& options);

    /// True when --help or -h was given (removed from the arguments).
    bool helpRequested();

    /// True when the flag (`--name`, or its `-a` alias) is present; removes it. `--name=...` or the flag given twice
    /// is a UsageError.
    bool flag(const std::string& name, const std::string& alias = "");

    /// The value of `--name VALUE` / `--name=VALUE` / `-a VALUE`, removed; nullopt when absent. A missing value
    /// (end of line, or the next word an option) or the option given twice (in any form) is a UsageError.
    std::optional<std::string> text(const std::string& name, const std::string& alias = "");

    /// An integer option in [minimum, maximum]; a UsageError names the option, the text and the range.
    std::optional<int64_t> integer(const std::string& name, int64_t minimum, int64_t maximum,
                                   const std::string& alias = "");

    /// A finite real option in [minimum, maximum], in decimal notation (parseDecimal); hexadecimal ("0x1"), NaN,
    /// inf, spaces and trailing text are refused.
    std::optional<double> number(const std::string& name, double minimum, double maximum,
                                 const std::string& alias = "");

    /// An option whose value must be one of `choices`; returns the index of the choice given.
    std::optional<size_t> choice(const std::string& name, std::initializer_list<const char*> choices,
                                 const std::string& alias = "");

    /// The positional arguments left, in order, removed. Call after every option was taken.
    std::vector<std::string> positionals();

    /// Refuses whatever is left: "unknown option '--x' (see --help)" or "unexpected argument 'y'".
    void finish() const;

    /// Throws UsageError("<program>: <what>"), for checks that span several options.
    [[noreturn]] void fail(const std::string& what) const;
    /// Throws OptionValueError("<program>: <option>: <problem>"), for a value the caller checks itself.
    [[noreturn]] void failValue(const std::string& option, const std::string& problem) const;

    const std::string& program() const { return program_; }

private:
    // Finds `--name`, `--name=...` or `-alias`; returns (index, inline value if `=` was used).
    std::optional<std::pair<size_t, std::optional<std::string>>> find(const std::string& name,
                                                                      const std::string& alias) const;
    // With an option table: refuses a name outside it, and records the name as read.
    void noteRead(const std::string& name);
    std::string program_;
    std::vector<std::string> arguments_;
    bool has_option_table_ = false;
    std::vector<std::string> table_names_;  ///< the table's long names
    std::vector<std::string> read_names_;   ///< the options read so far
};

/// A tool's main(): runs `body` and turns what escapes it into one line on stderr and an exit code:
/// OptionValueError 1 and UsageError 2 (their messages already name the program), any other exception 1 as
/// "<tool>: error: <what>" (InputError's FILE: FIELD: PROBLEM included). Never throws.
int runToolMain(const char* tool, const std::function<int()>& body) noexcept;

}  // namespace gusuku
