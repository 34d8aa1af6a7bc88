// A command's --help from its option table (see option_table.h for the layout the docs test reads back).

#include "gusuku/tools/option_table.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace gusuku {

namespace {

// Lines of at most `width` characters (a longer word stands alone), words split at spaces.
std::vector<std::string> wrapped(const std::string& text, size_t width) {
    std::vector<std::string> lines;
    std::istringstream words(text);
    std::string line;
    for (std::string word; words >> word;) {
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            lines.push_back(line);
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

std::string optionColumn(const OptionHelp& option) {
    std::string column = option.alias.empty() ? option.name : option.alias + ", " + option.name;
    if (!option.value.empty()) column += " " + option.value;
    return column;
}

// Help lines stay within the terminal width the tools' hand-written help kept.
constexpr size_t kHelpWidth = 112;
// The meaning column starts here unless no option column is that long; longer option columns put the meaning
// on the next line.
constexpr size_t kWidestMeaningIndent = 24;

}  // namespace

std::string defaultNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string formatHelp(const CommandHelp& help) {
    std::string text = help.usage + "\n";
    if (!help.description.empty()) text += "\n" + help.description + "\n";
    if (!help.options.empty()) {
        size_t indent = 0;
        for (const OptionHelp& option : help.options)
            indent = std::max(indent, std::min(kWidestMeaningIndent, 2 + optionColumn(option).size() + 2));
        text += "\noptions:\n";
        for (const OptionHelp& option : help.options) {
            std::string first = "  " + optionColumn(option);
            std::vector<std::string> lines = wrapped(option.meaning, kHelpWidth - indent);
            if (!option.default_value.empty()) lines.push_back("default: " + option.default_value);
            const std::string pad(indent, ' ');
            size_t next = 0;
            if (first.size() + 2 <= indent && !lines.empty()) {
                text += first + std::string(indent - first.size(), ' ') + lines[0] + "\n";
                next = 1;
            } else {
                text += first + "\n";
            }
            for (; next < lines.size(); ++next) text += pad + lines[next] + "\n";
        }
    }
    if (!help.notes.empty()) text += "\n" + help.notes + "\n";
    return text;
}

}  // namespace gusuku
