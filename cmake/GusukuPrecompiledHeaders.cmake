# Precompiled system headers for the desktop tools' libraries and the tests (not the runtime a phone links): parsing
# the standard library, GLM, Vulkan and nlohmann/json was a third to a half of each translation unit's compile, and
# CI's 30 minutes on 2 cores are mostly the build (docs/development.md, "Build time"). Project headers stay out: each
# change to one would rebuild every file of the target. GCC falls back to the headers themselves when a precompiled
# header does not fit a file's flags (CMake passes -Winvalid-pch, which says so).
option(GUSUKU_PRECOMPILED_HEADERS "Precompile the system headers of the baker, tools and tests" ON)

set(GUSUKU_PRECOMPILED_SYSTEM_HEADERS
  <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <cstdlib> <cstring> <filesystem> <fstream> <functional>
  <limits> <map> <memory> <numbers> <optional> <set> <sstream> <stdexcept> <string> <unordered_map> <vector>
  <glm/geometric.hpp> <glm/matrix.hpp> <vulkan/vulkan.h>)

# Gives TARGET its own precompiled header of the common system headers and any further ones named after it.
function(gusuku_precompile_system_headers target)
  if(GUSUKU_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${GUSUKU_PRECOMPILED_SYSTEM_HEADERS} ${ARGN})
  endif()
endfunction()
