#include "gusuku/formats/input_error.h"

#include <utility>

namespace gusuku {

namespace {
// "<file>: <field>: <problem>", leaving out an empty part (and its separator) so a message about a whole file
// reads "house.glb: truncated" rather than "house.glb: : truncated".
std::string composeMessage(const std::string& file, const std::string& field, const std::string& problem) {
    std::string message;
    for (const std::string* part : {&file, &field, &problem}) {
        if (part->empty()) continue;
        if (!message.empty()) message += ": ";
        message += *part;
    }
    return message;
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string problem)
    : std::runtime_error(composeMessage(file, field, problem)),
      file_(std::move(file)),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

std::string quotedForMessage(const std::string& text) {
    constexpr size_t kLongestQuoted = 80, kShownOfLong = 60;
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "'" + text + "'".
    std::string quoted(1, '\'');
    quoted.append(text, 0, text.size() <= kLongestQuoted ? text.size() : kShownOfLong);
    if (text.size() <= kLongestQuoted) return quoted.append(1, '\'');
    return quoted.append("...' (").append(std::to_string(text.size())).append(" characters)");
}

}  // namespace gusuku
