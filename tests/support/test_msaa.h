#pragma once
// The samples a pixel that runtime tests which do not test multisampling itself open the runtime with:
// RuntimeOptions' default (4), or GUSUKU_TEST_MSAA_SAMPLES where a driver cannot draw that. scripts/cross-build-aarch64.sh
// sets 1 under qemu-user while arm64 lavapipe emulated there crashes at msaa 4 (tests/aarch64/msaa4_depth_reproducer.c,
// docs/platforms.md): the tests' comparisons are between two paths of the same run, so they hold at either count.

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "gusuku/runtime/runtime.h"

namespace gusuku::testing {

inline uint32_t testMsaaSamples() {
    const char* value = std::getenv("GUSUKU_TEST_MSAA_SAMPLES");
    if (value == nullptr || *value == '\0') return RuntimeOptions{}.msaa_samples;
    const std::string text(value);
    if (text != "1" && text != "2" && text != "4" && text != "8")
        throw std::invalid_argument("GUSUKU_TEST_MSAA_SAMPLES: " + text + " is not 1, 2, 4 or 8");
    return uint32_t(std::stoul(text));
}

}  // namespace gusuku::testing
