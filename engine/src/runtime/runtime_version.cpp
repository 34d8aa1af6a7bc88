// The runtime library's one symbol until the runtime issue fills it: its version, so the target builds and a
// consumer can link it.
#include "gusuku/runtime_version.h"

namespace gusuku {

const char* runtimeVersion() noexcept { return "0.1.0"; }

}  // namespace gusuku
