// The runtime's version, for apps that log what they linked (the package's version, CMakeLists.txt's project()).
#include "gusuku/runtime/runtime_version.h"

namespace gusuku {

const char* runtimeVersion() noexcept { return "0.1.0"; }

}  // namespace gusuku
