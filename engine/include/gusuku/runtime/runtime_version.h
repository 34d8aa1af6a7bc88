#pragma once
// The version of gusuku_runtime, the library an AR app links (maths and Vulkan only, docs/design.md 8).

namespace gusuku {

/// "major.minor.patch" of this build of the runtime; never null, no allocation.
const char* runtimeVersion() noexcept;

}  // namespace gusuku
