#pragma once
// gusuku-view's headless runs, which open no window and need no windowing library at run time:
//   --render OUT SESSION_OR_BAKESET   composite a session (or the sample walk of a bake set) into PNG frames;
//   --sample-session DIR BAKESET      path-trace the sample walk into a session folder (docs/session.md).

#include "view_request.h"

namespace gusuku::view {

/// True when the request asks for a headless run.
inline bool isHeadlessRequest(const ViewRequest& request) {
    return request.render_out.has_value() || request.sample_session_out.has_value();
}

/// Runs it on a headless device (VulkanContext: GUSUKU_VALIDATION and GUSUKU_DEVICE apply); returns the exit
/// status. Bad input throws InputError, which main's runToolMain prints as one line.
int runHeadless(const ViewRequest& request);

}  // namespace gusuku::view
