// gusuku-view's scripted input (see view_script.h).

#include "view_script.h"

#include <sstream>

#include "gusuku/maths/time_utc.h"
#include "gusuku/tools/command_line.h"
#include "view_modes.h"
#include "view_request.h"
#include "view_session.h"

namespace gusuku::view {

namespace {

[[noreturn]] void refuse(const std::string& action, const std::string& problem) {
    throw OptionValueError("gusuku-view: --actions: " + quotedForMessage(action) + ": " + problem);
}

double numberIn(const std::string& action, const std::string& text, double minimum, double maximum,
                bool below_maximum = false) {
    const std::optional<double> value = parseDecimal(text);
    if (!value || *value < minimum || *value > maximum || (below_maximum && *value == maximum))
        refuse(action, "the value is not a number in [" + defaultNumber(minimum) + ", " + defaultNumber(maximum) +
                           (below_maximum ? ")" : "]"));
    return *value;
}

}  // namespace

std::vector<ViewAction> parseViewActions(const std::string& text) {
    std::vector<ViewAction> actions;
    std::istringstream list(text);
    std::string item;
    while (std::getline(list, item, ';')) {
        std::istringstream words(item);
        ViewAction action;
        words >> action.verb;
        if (action.verb.empty()) continue;  // "a;;b" and a trailing ';'
        std::getline(words >> std::ws, action.text);
        while (!action.text.empty() && action.text.back() == ' ') action.text.pop_back();
        const bool takes_none = action.verb == "quit";
        if (takes_none != action.text.empty())
            refuse(item, takes_none ? "takes no value" : "needs a value (see --help)");
        if (action.verb == "orbit" || action.verb == "pitch") {
            action.number = numberIn(item, action.text, -360.0, 360.0);
        } else if (action.verb == "walk") {
            action.number = numberIn(item, action.text, -1000.0, 1000.0);
        } else if (action.verb == "hour") {
            action.number = numberIn(item, action.text, 0.0, 24.0, true);
        } else if (action.verb == "weather") {
            action.number = numberIn(item, action.text, 0.0, 1.0);
        } else if (action.verb == "msaa") {
            action.number = numberIn(item, action.text, 1.0, 64.0);
        } else if (action.verb == "frame") {
            action.number = numberIn(item, action.text, 0.0, double(kMaxSessionFrames), true);
            if (action.number != double(size_t(action.number))) refuse(item, "not a whole frame index");
        } else if (action.verb == "frames") {
            action.number = numberIn(item, action.text, 1.0, 1000.0);
        } else if (action.verb == "time") {
            try {
                action.number = parseIso8601Utc(action.text);
            } catch (const std::exception& error) {
                refuse(item, error.what());
            }
        } else if (action.verb == "mode") {
            if (!viewModeIndex(action.text)) refuse(item, "not a mode (see --help's --mode)");
        } else if (action.verb == "resize") {
            const auto size = parseSize(action.text, kMinFrameSide, kMaxFrameSide);
            if (!size) refuse(item, "not WxH with each side in [16, 4096]");
            action.width = size->first;
            action.height = size->second;
        } else if (action.verb != "screenshot" && action.verb != "quit") {
            refuse(item, "unknown action (orbit, pitch, walk, hour, time, weather, mode, msaa, frame, frames, resize, "
                         "screenshot, quit)");
        }
        actions.push_back(action);
    }
    return actions;
}

}  // namespace gusuku::view
