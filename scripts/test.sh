#!/usr/bin/env bash
# Install, build, and run the whole test suite on real Vulkan (lavapipe) with the Khronos validation layer on; the
# runtime's tests run a second time on SwiftShader (the swiftshader_* tests, tests/drivers/Drivers.cmake).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
GUSUKU_VALIDATION=1 ctest --output-on-failure --parallel "$(nproc)" --timeout 900
