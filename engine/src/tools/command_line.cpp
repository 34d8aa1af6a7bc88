// The tools' one command-line reader (see command_line.h for the contract).

#include "gusuku/tools/command_line.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <exception>

#include "gusuku/tools/option_table.h"

namespace gusuku {

std::optional<double> parseDecimal(const std::string& text) {
    size_t position = 0;
    const auto digits = [&] {
        const size_t start = position;
        while (position < text.size() && std::isdigit(static_cast<unsigned char>(text[position]))) ++position;
        return position - start;
    };
    if (position < text.size() && (text[position] == '+' || text[position] == '-')) ++position;
    size_t mantissa_digits = digits();
    if (position < text.size() && text[position] == '.') {
        ++position;
        mantissa_digits += digits();
    }
    if (mantissa_digits == 0) return std::nullopt;
    if (position < text.size() && (text[position] == 'e' || text[position] == 'E')) {
        ++position;
        if (position < text.size() && (text[position] == '+' || text[position] == '-')) ++position;
        if (digits() == 0) return std::nullopt;
    }
    if (position != text.size()) return std::nullopt;
    errno = 0;
    const double value = std::strtod(text.c_str(), nullptr);
    if (errno == ERANGE && !std::isfinite(value)) return std::nullopt;
    return value;
}

CommandLine::CommandLine(std::string program, std::vector<std::string> arguments)
    : program_(std::move(program)), arguments_(std::move(arguments)) {}

void CommandLine::fail(const std::string& what) const { throw UsageError(program_ + ": " + what); }

void CommandLine::failValue(const std::string& option, const std::string& problem) const {
    throw OptionValueError(program_ + ": " + option + ": " + problem);
}

std::optional<std::pair<size_t, std::optional<std::string>>> CommandLine::find(const std::string& name,
                                                                               const std::string& alias) const {
    std::optional<std::pair<size_t, std::optional<std::string>>> last;
    for (size_t index = 0; index < arguments_.size(); ++index) {
        const std::string& argument = arguments_[index];
        if (argument == "--") break;  // everything after a bare "--" is positional
        if (argument == name || (!alias.empty() && argument == alias)) {
            last = std::make_pair(index, std::nullopt);
        } else if (argument.size() > name.size() && argument.compare(0, name.size(), name) == 0 &&
                   argument[name.size()] == '=') {
            last = std::make_pair(index, std::optional<std::string>(argument.substr(name.size() + 1)));
        }
    }
    return last;
}

void CommandLine::useOptionTable(const std::vector<OptionHelp>& options) {
    has_option_table_ = true;
    table_names_.clear();
    for (const OptionHelp& option : options) table_names_.push_back(option.name);
}

void CommandLine::noteRead(const std::string& name) {
    if (!has_option_table_ || name == "--help") return;  // --help is every command's, in no table
    if (std::find(table_names_.begin(), table_names_.end(), name) == table_names_.end())
        throw std::logic_error(program_ + ": " + name + " is read but not in the command's option table (--help)");
    read_names_.push_back(name);
}

bool CommandLine::helpRequested() { return flag("--help", "-h"); }

bool CommandLine::flag(const std::string& name, const std::string& alias) {
    noteRead(name);
    bool present = false;
    while (const auto found = find(name, alias)) {
        if (found->second) fail(name + ": takes no value, got " + quotedForMessage(*found->second));
        if (present) fail(name + ": given twice; give it once");
        arguments_.erase(arguments_.begin() + std::ptrdiff_t(found->first));
        present = true;
    }
    return present;
}

std::optional<std::string> CommandLine::text(const std::string& name, const std::string& alias) {
    noteRead(name);
    std::optional<std::string> value;
    // Take every occurrence, then refuse more than one: a repeated option is a mistake the user should see.
    std::vector<std::string> values;
    for (size_t index = 0; index < arguments_.size();) {
        const std::string& argument = arguments_[index];
        if (argument == "--") break;
        const bool bare = argument == name || (!alias.empty() && argument == alias);
        const bool inline_value = argument.size() > name.size() && argument.compare(0, name.size(), name) == 0 &&
                                  argument[name.size()] == '=';
        if (!bare && !inline_value) {
            ++index;
            continue;
        }
        if (inline_value) {
            values.push_back(argument.substr(name.size() + 1));
            arguments_.erase(arguments_.begin() + std::ptrdiff_t(index));
            continue;
        }
        // A value may itself start with '-' only when it is a number ("--lon -70.5").
        const bool has_next = index + 1 < arguments_.size();
        const bool next_is_value =
            has_next && (arguments_[index + 1].empty() || arguments_[index + 1][0] != '-' ||
                         (arguments_[index + 1].size() > 1 &&
                          (std::isdigit(static_cast<unsigned char>(arguments_[index + 1][1])) ||
                           arguments_[index + 1][1] == '.')));
        if (!next_is_value) fail(name + ": needs a value");
        values.push_back(arguments_[index + 1]);
        arguments_.erase(arguments_.begin() + std::ptrdiff_t(index), arguments_.begin() + std::ptrdiff_t(index) + 2);
    }
    if (values.size() > 1)
        fail(name + ": given " + std::to_string(values.size()) + " times (" + quotedForMessage(values[0]) + ", " +
             quotedForMessage(values[1]) + (values.size() > 2 ? ", ..." : "") + "); give it once");
    if (!values.empty()) value = values.back();
    return value;
}

std::optional<int64_t> CommandLine::integer(const std::string& name, int64_t minimum, int64_t maximum,
                                            const std::string& alias) {
    const std::optional<std::string> value = text(name, alias);
    if (!value) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    const long long parsed = std::strtoll(value->c_str(), &end, 10);
    const std::string range = "[" + std::to_string(minimum) + ", " + std::to_string(maximum) + "]";
    if (value->empty() || end == value->c_str() || *end != '\0' || errno == ERANGE)
        failValue(name, quotedForMessage(*value) + " is not an integer in " + range);
    if (parsed < minimum || parsed > maximum) failValue(name, *value + " is outside " + range);
    return int64_t(parsed);
}

std::optional<double> CommandLine::number(const std::string& name, double minimum, double maximum,
                                          const std::string& alias) {
    const std::optional<std::string> value = text(name, alias);
    if (!value) return std::nullopt;
    const std::optional<double> decimal = parseDecimal(*value);
    const double parsed = decimal.value_or(0.0);
    auto format = [](double bound) {
        std::string text = std::to_string(bound);
        // "90.000000" -> "90": ranges read as the user would write them.
        while (text.find('.') != std::string::npos && (text.back() == '0' || text.back() == '.')) {
            const bool dot = text.back() == '.';
            text.pop_back();
            if (dot) break;
        }
        return text;
    };
    const std::string range = "[" + format(minimum) + ", " + format(maximum) + "]";
    if (!decimal || !std::isfinite(parsed))
        failValue(name, quotedForMessage(*value) + " is not a finite number in " + range);
    if (parsed < minimum || parsed > maximum) failValue(name, *value + " is outside " + range);
    return parsed;
}

std::optional<size_t> CommandLine::choice(const std::string& name, std::initializer_list<const char*> choices,
                                          const std::string& alias) {
    const std::optional<std::string> value = text(name, alias);
    if (!value) return std::nullopt;
    size_t index = 0;
    std::string listed;
    for (const char* candidate : choices) {
        if (*value == candidate) return index;
        listed += (index == 0 ? "" : index + 1 == choices.size() ? " or " : ", ") + std::string(candidate);
        ++index;
    }
    failValue(name, quotedForMessage(*value) + " is not " + listed);
}

std::vector<std::string> CommandLine::positionals() {
    std::vector<std::string> taken;
    std::vector<std::string> kept;
    bool after_separator = false;
    for (const std::string& argument : arguments_) {
        if (!after_separator && argument == "--") {
            after_separator = true;
        } else if (after_separator || argument.empty() || argument[0] != '-' || argument == "-") {
            taken.push_back(argument);
        } else {
            kept.push_back(argument);
        }
    }
    arguments_ = std::move(kept);
    return taken;
}

void CommandLine::finish() const {
    for (const std::string& name : table_names_)
        if (std::find(read_names_.begin(), read_names_.end(), name) == read_names_.end())
            throw std::logic_error(program_ + ": " + name + " is in the command's option table (--help) but never read");
    for (const std::string& argument : arguments_) {
        if (!argument.empty() && argument[0] == '-') fail("unknown option " + quotedForMessage(argument) + " (see --help)");
        fail("unexpected argument " + quotedForMessage(argument) + " (see --help)");
    }
}

int runToolMain(const char* tool, const std::function<int()>& body) noexcept {
    try {
        return body();
    } catch (const OptionValueError& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    } catch (const UsageError& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "%s: error: %s\n", tool, error.what());
        return 1;
    } catch (...) {
        std::fprintf(stderr, "%s: error: an unknown exception\n", tool);
        return 1;
    }
}

}  // namespace gusuku
