// gusuku-view: a window onto a bake set, for a site team to judge it (walk around the building, scrub the day,
// try the weather, compare with direct light) and the worked example of an app's GPU-resident frame loop
// (view_frame_loop.h). docs/view.md says how to use it.

#include <cstdio>
#include <string>
#include <vector>

#include "gusuku/tools/command_line.h"
#include "view_app.h"
#include "view_request.h"
#include "view_script.h"
#include "view_session_command.h"

int main(int argc, char** argv) {
    using namespace gusuku::view;
    return gusuku::runToolMain("gusuku-view", [&] {
        const ViewRequest request = parseViewRequest(std::vector<std::string>(argv + 1, argv + argc));
        if (request.help) {
            std::printf("%s", gusuku::formatHelp(viewHelp()).c_str());
            return 0;
        }
        if (isHeadlessRequest(request)) return runHeadless(request);  // --render, --sample-session: no window
        if (request.actions) parseViewActions(*request.actions);  // refused before anything opens
        ViewApp app(request);
        return app.run();
    });
}
