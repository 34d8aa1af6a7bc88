#pragma once
// InputError: the one exception type for bad input (a file, a field, a problem), so every command-line tool
// can print "FILE: FIELD: PROBLEM" and exit non-zero without crashing.

#include <stdexcept>
#include <string>

namespace gusuku {

/// Thrown for any bad input the software meets: a missing or corrupt file, an out-of-range field, a NaN texel.
/// what() is "<file>: <field>: <problem>". `field` is a JSON-pointer-like path ("/site/latitude_deg") or a
/// location inside a file ("texel (12, 40) channel G", "accessor 3").
class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string field, std::string problem);

    const std::string& file() const noexcept { return file_; }
    const std::string& field() const noexcept { return field_; }
    const std::string& problem() const noexcept { return problem_; }

private:
    std::string file_;
    std::string field_;
    std::string problem_;
};

/// `text` quoted for a one-line message: whole when short, else its first 60 characters, "...", and its length,
/// so that a 100 KB argument or time string never floods the terminal.
std::string quotedForMessage(const std::string& text);

}  // namespace gusuku
